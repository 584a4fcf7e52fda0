//! The colour of daylight under cloud, continuous from the clear sky to the overcast.
//!
//! Lee & Hernández-Andrés, *Colors of the daytime overcast sky* (Applied Optics 44(27), 2005),
//! measured daylight spectra beneath overcasts: overcasts are not spectrally neutral; they make
//! daylight **bluer** than clear-sky daylight (sun and sky together, whose typical CCT is about
//! 5,700 K in Hernández-Andrés et al.'s two-year Granada record, JOSA A 18(6), 2001), and the
//! bluing grows with the cloud's optical depth. The CIE gives its daylight illuminant D65
//! (6,504 K) for overcast daylight (as the same paper notes).
//!
//! The model here is an additive mixture, at equal luminance, of the clear sky's light and
//! overcast light of D65's chromaticity, weighted by the **overcast fraction** w:
//!
//! XYZ / Y = (1 − w) XYZ_clear / Y_clear + w XYZ_D65 / Y_D65,
//!
//! with w = 0 at or above the clear-sky level (clear-sky index k_c ≥ 1), rising linearly to 1 at
//! k_c = [`OVERCAST_CLEAR_SKY_INDEX`] and 1 below it, so the colour is continuous in the
//! measurement and exactly the clear sky's at the clear-sky level.
//!
//! **What it is fitted to, and its error**: nothing measured is fitted here. The overcast end is
//! the CIE's D65, not a fit to Lee & Hernández-Andrés's data, and the model does not follow their
//! further bluing with optical depth; the 0.3 of the ramp is this crate's choice, not a fit. Its error against measured
//! daylight is not known. The melanopic content of cloudy daylight is not modelled.

use glam::Vec3;

use crate::cie::D65;
use crate::color::{self, Xyy};

/// The clear-sky index at and below which the sky counts as fully overcast (module docs).
pub const OVERCAST_CLEAR_SKY_INDEX: f32 = 0.3;

/// The overcast fraction w of a sky with clear-sky index `clear_sky_index` (measured over
/// clear-sky global illuminance): 0 at 1 and above, 1 at [`OVERCAST_CLEAR_SKY_INDEX`] and below,
/// linear between; NaN counts as clear.
///
/// ```
/// use sky_core::overcast::overcast_fraction;
/// assert_eq!(overcast_fraction(1.2), 0.0);
/// assert_eq!(overcast_fraction(0.1), 1.0);
/// assert!((overcast_fraction(0.65) - 0.5).abs() < 1e-6);
/// ```
#[must_use]
pub fn overcast_fraction(clear_sky_index: f32) -> f32 {
    let w = (1.0 - clear_sky_index) / (1.0 - OVERCAST_CLEAR_SKY_INDEX);
    if w > 0.0 { w.min(1.0) } else { 0.0 }
}

/// The daylight of illuminance `illuminance` (lux) under a sky of overcast fraction
/// `overcast_fraction` (clamped to [0, 1]) whose clear-sky light is `clear` (XYZ, any positive
/// scale), as XYZ with Y = `illuminance`. At w = 0 the result is `clear` scaled to the
/// illuminance; a black `clear` gives D65's chromaticity.
///
/// ```
/// use sky_core::overcast::daylight_under_cloud;
/// use sky_core::Vec3;
/// let blue_sky = Vec3::new(0.9, 1.0, 1.6);
/// let e = daylight_under_cloud(blue_sky, 1.0, 5_000.0); // fully overcast
/// assert!((e.y - 5_000.0).abs() < 1e-2);
/// assert!((e.x / (e.x + e.y + e.z) - 0.31272).abs() < 1e-5);
/// ```
#[must_use]
pub fn daylight_under_cloud(clear: Vec3, overcast_fraction: f32, illuminance: f32) -> Vec3 {
    let w = if overcast_fraction > 0.0 {
        overcast_fraction.min(1.0)
    } else {
        0.0
    };
    let overcast = color::xyy_to_xyz(Xyy {
        x: D65.0,
        y: D65.1,
        luminance: 1.0,
    });
    if !(clear.y > 0.0 && clear.is_finite()) {
        return overcast * illuminance;
    }
    if w == 0.0 {
        return clear * (illuminance / clear.y);
    }
    ((1.0 - w) * (clear / clear.y) + w * overcast) * illuminance
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn continuous_from_clear_to_overcast() {
        let clear = Vec3::new(0.85, 1.0, 1.4);
        let mut previous = daylight_under_cloud(clear, 0.0, 100.0);
        assert_eq!(previous, clear * 100.0);
        for i in 1..=1000 {
            let w = i as f32 / 1000.0;
            let e = daylight_under_cloud(clear, w, 100.0);
            assert!((e - previous).abs().max_element() < 0.2, "{w}");
            assert!((e.y - 100.0).abs() < 1e-3);
            previous = e;
        }
        assert!(daylight_under_cloud(Vec3::NAN, 0.5, 10.0).is_finite());
        assert_eq!(overcast_fraction(f32::NAN), 0.0);
    }
}
