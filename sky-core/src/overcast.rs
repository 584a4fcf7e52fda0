//! The colour and melanopic content of daylight under cloud, continuous from the clear sky to
//! the overcast, fitted to measured daylight spectra.
//!
//! **The model** ([`daylight_under_cloud`]) is an additive mixture, at equal luminance, of the
//! clear sky's light and an **overcast light** of fixed chromaticity [`OVERCAST_CHROMATICITY`]
//! and melanopic DER [`OVERCAST_MELANOPIC_DER`], weighted by the **overcast fraction** w
//! ([`overcast_fraction`]):
//!
//! XYZ / Y = (1 − w) XYZ_clear / Y_clear + w XYZ_overcast / Y_overcast,
//!
//! with w = 0 at or above the clear-sky level (clear-sky index k_c ≥ 1), rising linearly to 1 at
//! k_c = [`OVERCAST_CLEAR_SKY_INDEX`] and 1 below it, so the colour is continuous in the
//! measurement and exactly the clear sky's at the clear-sky level. Melanopic EDI is linear in
//! the spectrum, so the same mixture gives the melanopic DER under cloud:
//! (1 − w) DER_clear + w [`OVERCAST_MELANOPIC_DER`] (`controller::step` applies it). Four
//! numbers (the overcast light's x, y and DER, and the index where the ramp ends) are fitted;
//! the form (a linear ramp in k_c that saturates) is the simplest continuous one that is
//! exactly the clear light at k_c = 1 and constant under a full overcast, which is what the
//! measurements show within their scatter (below).
//!
//! **Fitted to**: 27 global horizontal spectra measured in Singapore under skies the observer
//! classified as clear, intermediate and overcast (P. Balakrishnan, *Measuring and Modelling
//! Equatorial Light*, PhD thesis, Singapore University of Technology and Design, 2019; the
//! data set github.com/prijibalakrishnan/equatorialskies), each with its clear-sky index from
//! the measured illuminance over the controller's clear sky (`controller::step`), the fit on
//! alternate days and its error on the other days (`tests/tests/overcast_measured.rs`,
//! docs/weather.md "Colour under cloud"). **Error** on the held-out days (8 spectra, 5 days):
//! RMS Δu′v′ 0.0028 (largest 0.0056), CCT 212 K (447 K), melanopic DER 0.018 (0.041); the test
//! fails above 0.0050, 400 K and 0.035. It is the scatter at a given k_c (a few hundred kelvin
//! between days of the same k_c), which one number for the sky cannot resolve; the D65 end
//! this replaces was twice as far off (0.0058, 454 K, 0.040). The measured overcast light
//! (6,577 K, Duv +0.0022) is bluer than the clear light (as Lee & Hernández-Andrés, *Colors of
//! the daytime overcast sky*, Applied Optics 44(27), 2005, found beneath overcasts at
//! Annapolis) and, in this data, close to D65 (6,504 K) but past it; the further bluing with
//! cloud optical depth that Lee & Hernández-Andrés measured does not show in it and is not
//! followed. One site (equatorial), 27 spectra: the error elsewhere is not known.
//!
//! **Melanopic content** ([`melanopic_der`]): the melanopic daylight (D65) efficacy ratio of CIE
//! S 026:2018 (melanopic EDI over illuminance) of the CIE daylight illuminant D_T at a CCT T,
//! 4,000-25,000 K. The CIE daylight illuminants were built from measured daylight spectra,
//! overcast ones included (Judd, MacAdam & Wyszecki 1964, J. Opt. Soc. Am. 54(8), 1031-1040),
//! so DER(T) at the CCT of the modelled daylight is its melanopic content to the extent that
//! daylight follows D_T.

use glam::Vec3;

use crate::color::{self, Xyy};

mod daylight_basis;
mod fitted;

/// The clear-sky index at and below which the sky counts as fully overcast (fitted; module
/// docs).
pub const OVERCAST_CLEAR_SKY_INDEX: f32 = fitted::CLEAR_SKY_INDEX;

/// The chromaticity (CIE 1931 x, y) of the overcast light, the end of the mixture at
/// w = 1 (fitted to measured overcast daylight; module docs).
pub const OVERCAST_CHROMATICITY: (f32, f32) = fitted::CHROMATICITY;

/// The melanopic daylight (D65) efficacy ratio (CIE S 026:2018) of the overcast light (fitted
/// to the same measured spectra; module docs).
pub const OVERCAST_MELANOPIC_DER: f32 = fitted::MELANOPIC_DER;

/// The overcast fraction w of a sky with clear-sky index `clear_sky_index` (measured over
/// clear-sky global illuminance): 0 at 1 and above, 1 at [`OVERCAST_CLEAR_SKY_INDEX`] and below,
/// linear between; NaN counts as clear.
///
/// ```
/// use sky_core::overcast::{overcast_fraction, OVERCAST_CLEAR_SKY_INDEX};
/// assert_eq!(overcast_fraction(1.2), 0.0);
/// assert_eq!(overcast_fraction(0.1), 1.0);
/// let halfway = 0.5 * (1.0 + OVERCAST_CLEAR_SKY_INDEX);
/// assert!((overcast_fraction(halfway) - 0.5).abs() < 1e-5);
/// ```
#[must_use]
pub fn overcast_fraction(clear_sky_index: f32) -> f32 {
    let w = (1.0 - clear_sky_index) / (1.0 - OVERCAST_CLEAR_SKY_INDEX);
    if w > 0.0 { w.min(1.0) } else { 0.0 }
}

/// The daylight of illuminance `illuminance` (lux) under a sky of overcast fraction
/// `overcast_fraction` (clamped to [0, 1]) whose clear-sky light is `clear` (XYZ, any positive
/// scale), as XYZ with Y = `illuminance`. At w = 0 the result is `clear` scaled to the
/// illuminance, at w = 1 the overcast light ([`OVERCAST_CHROMATICITY`]); a black or non-finite
/// `clear`, or one whose scaled light would overflow, gives the overcast light's chromaticity,
/// so the result is finite for any `clear` and `overcast_fraction` at a finite illuminance.
/// Error against measured daylight under cloud: module docs.
///
/// ```
/// use sky_core::overcast::{daylight_under_cloud, OVERCAST_CHROMATICITY};
/// use sky_core::Vec3;
/// let blue_sky = Vec3::new(0.9, 1.0, 1.6);
/// let e = daylight_under_cloud(blue_sky, 1.0, 5_000.0); // fully overcast
/// assert!((e.y - 5_000.0).abs() < 1e-2);
/// assert!((e.x / (e.x + e.y + e.z) - OVERCAST_CHROMATICITY.0).abs() < 1e-5);
/// ```
#[must_use]
pub fn daylight_under_cloud(clear: Vec3, overcast_fraction: f32, illuminance: f32) -> Vec3 {
    let w = if overcast_fraction > 0.0 {
        overcast_fraction.min(1.0)
    } else {
        0.0
    };
    let overcast = color::xyy_to_xyz(Xyy {
        x: OVERCAST_CHROMATICITY.0,
        y: OVERCAST_CHROMATICITY.1,
        luminance: 1.0,
    });
    if !(clear.y > 0.0 && clear.is_finite()) {
        return overcast * illuminance;
    }
    let light = if w == 0.0 {
        clear * (illuminance / clear.y)
    } else {
        ((1.0 - w) * (clear / clear.y) + w * overcast) * illuminance
    };
    // A clear light of no real colour (X or Z overflowing over a tiny Y) counts as black.
    if light.is_finite() {
        light
    } else {
        overcast * illuminance
    }
}

/// The lowest CCT of the CIE daylight locus, K (CIE 015:2004 §3.1).
pub const DAYLIGHT_MIN_CCT: f32 = 4_000.0;
/// The highest CCT of the CIE daylight locus, K (CIE 015:2004 §3.1).
pub const DAYLIGHT_MAX_CCT: f32 = 25_000.0;
/// The CCT of D65 as the daylight formulas take it, K: 6,500 × 1.4388 / 1.4380 (the change of
/// c₂ since D65 was defined; CIE 015:2004 §3.1).
pub const D65_CCT: f32 = 6_503.6;

/// The CIE daylight locus (CIE 015:2004 §3.1): the chromaticity (x_D, y_D) of the daylight
/// illuminant D_T at CCT `kelvin`, clamped to [`DAYLIGHT_MIN_CCT`]-[`DAYLIGHT_MAX_CCT`] (NaN
/// counts as [`D65_CCT`]):
///
/// x_D = −4.6070·10⁹/T³ + 2.9678·10⁶/T² + 0.09911·10³/T + 0.244063 (4,000-7,000 K),
/// x_D = −2.0064·10⁹/T³ + 1.9018·10⁶/T² + 0.24748·10³/T + 0.237040 (7,000-25,000 K),
/// y_D = −3.000 x_D² + 2.870 x_D − 0.275.
///
/// ```
/// use sky_core::overcast::daylight_locus;
/// // D65's tabulated chromaticity is (0.31272, 0.32903); the formula's y_D is 1e-4 above it.
/// let (x, y) = daylight_locus(6_503.6);
/// assert!((x - 0.31272).abs() < 5e-6 && (y - 0.32913).abs() < 5e-6);
/// ```
#[must_use]
pub fn daylight_locus(kelvin: f32) -> (f32, f32) {
    let t = if kelvin.is_nan() {
        D65_CCT
    } else {
        kelvin.clamp(DAYLIGHT_MIN_CCT, DAYLIGHT_MAX_CCT)
    };
    let u = 1_000.0 / t; // the polynomials in 10³/T
    let x = if t <= 7_000.0 {
        ((-4.6070 * u + 2.9678) * u + 0.09911) * u + 0.244_063
    } else {
        ((-2.0064 * u + 1.9018) * u + 0.24748) * u + 0.237_040
    };
    (x, (-3.000 * x + 2.870) * x - 0.275)
}

/// The melanopic daylight (D65) efficacy ratio (CIE S 026:2018: melanopic EDI over
/// illuminance, dimensionless, 1 for D65) of the CIE daylight illuminant D_T of CCT `kelvin`
/// (clamped to [`DAYLIGHT_MIN_CCT`]-[`DAYLIGHT_MAX_CCT`]; NaN counts as [`D65_CCT`]). The
/// melanopic EDI of daylight of illuminance E (lux) and CCT T is `melanopic_der(T) * E`.
///
/// D_T = S0 + M1 S1 + M2 S2 (CIE 015:2004 §3.1, with M = 0.0241 + 0.2562 x_D − 0.7341 y_D,
/// M1 = (−1.3515 − 1.7703 x_D + 5.9114 y_D) / M, M2 = (0.0300 − 31.4424 x_D + 30.0717 y_D) / M),
/// so the ratio is exact in the six integrals of S0, S1, S2 against ȳ and the S 026 melanopic
/// action spectrum (generated constants, 10 nm bins, 360-830 nm). **Error**: within 2e-6
/// (relative; 5.2e-7 measured) of the f64 spectra on the same bins over the whole range, and
/// within 0.1 % of published values (D65: 1 by definition, 0.9997 here; D55: 0.90402 in the
/// CIE S 026 metrology of F. Rudawski's Lighting Toolbox, 0.9040 here); `tests/tests/overcast.rs`
/// holds both. For daylight off the locus (Duv ≠ 0) it is the DER of the daylight illuminant
/// of the same CCT, not of the light itself.
///
/// ```
/// use sky_core::overcast::melanopic_der;
/// assert!((melanopic_der(6_503.6) - 1.0).abs() < 1e-3);     // D65, by S 026's definition
/// assert!(melanopic_der(5_000.0) < melanopic_der(10_000.0)); // bluer daylight, more melanopic
/// ```
#[must_use]
pub fn melanopic_der(kelvin: f32) -> f32 {
    use daylight_basis::{ILLUMINANCE, MELANOPIC_EDI};
    let (x, y) = daylight_locus(kelvin);
    // M, M·M1 and M·M2: the ratio is homogeneous in the weights, so M cancels.
    let w = [
        0.0241 + 0.2562 * x - 0.7341 * y,
        -1.3515 - 1.7703 * x + 5.9114 * y,
        0.0300 - 31.4424 * x + 30.0717 * y,
    ];
    let dot = |c: [f32; 3]| w[0] * c[0] + w[1] * c[1] + w[2] * c[2];
    dot(MELANOPIC_EDI) / dot(ILLUMINANCE)
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
