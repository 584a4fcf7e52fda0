//! Daylight at every sun elevation: the Preetham sky by day, a fitted twilight decay below the
//! horizon, and a night floor.
//!
//! Preetham's model is undefined with the sun below the horizon. [`Daylight`] extends it:
//!
//! * sun elevation h ≥ 0: the Preetham sky itself;
//! * −18° ≤ h < 0: the Preetham sky with the sun *on* the horizon (same azimuth and
//!   turbidity), its luminance scaled by a factor k(h) with k(0) = 1, so the sky is continuous
//!   at sunset and keeps its sunset chromaticity (the blue hour's colour shift is not modelled);
//! * h < −18°: k(−18°), the end of astronomical twilight, when scattered sunlight falls below
//!   starlight and airglow.
//!
//! log₁₀ k is interpolated linearly between knots at 0°, −6°, −12° and −18°, fitted to the clear-sky
//! horizontal illuminances of the American Meteorological Society's *Glossary of Meteorology*
//! (entries "civil twilight" and "astronomical twilight"): about 410-585 lx at sunset,
//! 2-3.5 lx at the end of civil twilight (−6°), 0.008 lx at the end of nautical twilight
//! (−12°) and 6·10⁻⁴ lx at −18°. Each knot is the geometric mean of the quoted range divided
//! by that at sunset (490 lx), so the *ratios* follow the glossary while the absolute level at
//! sunset is Preetham's. k is strictly increasing, so illuminance is monotone in elevation from
//! −18° to 90° (a test checks every 0.1°), and every output is finite.

use glam::Vec3;

use crate::color::{self, Xyy};
use crate::error::SkyError;
use crate::geom::Sun;
use crate::math;
use crate::photometry::Photometry;
use crate::preetham::PreethamSky;

/// Knots of the twilight decay: (sun elevation in degrees, log₁₀ of the luminance factor).
/// Geometric means of the glossary's ranges over 490 lx: 2.65/490, 0.008/490, 6e-4/490.
const TWILIGHT_KNOTS: [(f32, f32); 4] = [
    (0.0, 0.0),
    (-6.0, -2.267_6),
    (-12.0, -4.787_1),
    (-18.0, -5.912_0),
];

/// The luminance factor k(h) at sun elevation `elevation_deg` (module docs): 1 at and above the
/// horizon, decreasing log-linearly through the knots, constant below −18°. NaN gives the
/// night value.
#[must_use]
pub fn twilight_factor(elevation_deg: f32) -> f32 {
    if elevation_deg >= 0.0 {
        return 1.0;
    }
    let mut log10 = TWILIGHT_KNOTS[TWILIGHT_KNOTS.len() - 1].1;
    for pair in TWILIGHT_KNOTS.windows(2) {
        let ((h0, k0), (h1, k1)) = (pair[0], pair[1]);
        if elevation_deg < h0 && elevation_deg >= h1 {
            log10 = k0 + (k1 - k0) * (elevation_deg - h0) / (h1 - h0);
        }
    }
    math::powf(10.0, log10)
}

/// The clear sky at any sun position: Preetham's by day, scaled for twilight and night (module
/// docs). Luminance in cd/m².
///
/// ```
/// use sky_core::photometry::Photometry;
/// use sky_core::twilight::Daylight;
/// use sky_core::Sun;
///
/// let day = Daylight::new(Sun::new(60f32.to_radians(), 0.0)?, 3.0)?;
/// let dusk = Daylight::new(Sun::new(96f32.to_radians(), 0.0)?, 3.0)?; // sun 6° below
/// let ratio = dusk.horizontal_illuminance().y / day.horizontal_illuminance().y;
/// assert!(ratio > 1e-4 && ratio < 1e-2);
/// # Ok::<(), sky_core::SkyError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Daylight {
    sky: PreethamSky,
    sun: Sun,
    factor: f32,
}

impl Daylight {
    /// The sky for `sun` (any zenith angle in [0, π]) and `turbidity` (Preetham's range).
    ///
    /// # Errors
    /// [`SkyError::OutOfRange`] for a turbidity outside
    /// [[`crate::preetham::MIN_TURBIDITY`], [`crate::preetham::MAX_TURBIDITY`]].
    pub fn new(sun: Sun, turbidity: f32) -> Result<Self, SkyError> {
        let horizon = core::f32::consts::FRAC_PI_2;
        let day_sun = if sun.zenith() > horizon {
            Sun::new(horizon, sun.azimuth())?
        } else {
            sun
        };
        Ok(Self {
            sky: PreethamSky::new(day_sun, turbidity)?,
            sun,
            factor: twilight_factor(90.0 - sun.zenith().to_degrees()),
        })
    }

    /// The sun as given (possibly below the horizon).
    #[must_use]
    pub fn sun(&self) -> Sun {
        self.sun
    }

    /// The luminance factor applied to the Preetham sky: 1 by day, k(h) below the horizon.
    #[must_use]
    pub fn twilight_factor(&self) -> f32 {
        self.factor
    }

    /// Luminance (cd/m²) and chromaticity towards `dir` (as [`PreethamSky::xyy`]).
    #[inline]
    #[must_use]
    pub fn xyy(&self, dir: Vec3) -> Xyy {
        let c = self.sky.xyy(dir);
        Xyy {
            luminance: c.luminance * self.factor,
            ..c
        }
    }

    /// Linear sRGB towards `dir`, cd/m² scale.
    #[inline]
    #[must_use]
    pub fn rgb(&self, dir: Vec3) -> Vec3 {
        color::xyz_to_linear_srgb(Photometry::xyz(self, dir))
    }
}

impl Photometry for Daylight {
    fn xyz(&self, dir: Vec3) -> Vec3 {
        self.sky.xyz(dir) * self.factor
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn factor_is_continuous_and_increasing() {
        assert_eq!(twilight_factor(0.0), 1.0);
        assert!((twilight_factor(-1e-4) - 1.0).abs() < 1e-4);
        let mut previous = 0.0;
        for i in -300..=10 {
            let k = twilight_factor(i as f32 * 0.1);
            assert!(k.is_finite() && k > 0.0);
            assert!(i <= -180 || i > 0 || k > previous, "{i}");
            previous = k;
        }
        assert_eq!(twilight_factor(-40.0), twilight_factor(-18.0));
        assert!(twilight_factor(f32::NAN).is_finite());
    }
}
