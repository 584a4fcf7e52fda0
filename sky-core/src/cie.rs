//! The CIE standard general sky: fifteen relative luminance distributions, from overcast to
//! cloudless and turbid (ISO 15469:2004 / CIE S 011/E:2003, *Spatial distribution of daylight —
//! CIE standard general sky*).
//!
//! The luminance of a sky element at zenith angle Z and angular distance χ from the sun, relative
//! to the zenith's, is (the standard's eq. 1)
//!
//! L / L_z = f(χ) φ(Z) / (f(Z_s) φ(0)),
//!
//! with the **gradation** φ(Z) = 1 + a exp(b / cos Z) (φ(90°) = 1; eq. 2) and the **scattering
//! indicatrix** f(χ) = 1 + c [exp(d χ) − exp(d π/2)] + e cos² χ (eq. 3); Z_s is the sun's zenith
//! angle, which is also the zenith's distance from the sun. Each type is one row of a, b, c, d, e
//! of the standard's Table 1: six gradation groups (I-VI) combined with six indicatrix groups
//! (1-6). The standard gives relative distributions; the absolute level here is either a zenith
//! luminance or a diffuse horizontal illuminance that the sky must reproduce.

use core::f32::consts::FRAC_PI_2;

use glam::Vec3;

use crate::color::{self, Xyy};
use crate::error::{SkyError, check_range};
use crate::geom::{self, Sun};
use crate::math;
use crate::photometry::{self, Photometry};

/// ISO 15469:2004 / CIE S 011/E:2003, Table 1: the parameters a, b (gradation) and c, d, e
/// (indicatrix) of the standard general skies, types 1 to 15 in order. Checked value by value
/// against Darula & Kittler, *CIE general sky standard defining luminance distributions*
/// (eSim 2002), whose groups I-VI and 1-6 give the same rows, and against the table of the Lighting
/// Toolbox's `ciesky.m` (F. Rudawski, 2021).
pub const STANDARD_SKIES: [[f32; 5]; 15] = [
    [4.0, -0.70, 0.0, -1.0, 0.00], // 1: CIE standard overcast, steep gradation, uniform in azimuth
    [4.0, -0.70, 2.0, -1.5, 0.15], // 2: overcast, steep gradation, slight brightening towards the sun
    [1.1, -0.80, 0.0, -1.0, 0.00], // 3: overcast, moderate gradation, uniform in azimuth
    [1.1, -0.80, 2.0, -1.5, 0.15], // 4: overcast, moderate gradation, slight brightening towards the sun
    [0.0, -1.00, 0.0, -1.0, 0.00], // 5: sky of uniform luminance
    [0.0, -1.00, 2.0, -1.5, 0.15], // 6: partly cloudy, no gradation, slight brightening towards the sun
    [0.0, -1.00, 5.0, -2.5, 0.30], // 7: partly cloudy, no gradation, brighter circumsolar region
    [0.0, -1.00, 10.0, -3.0, 0.45], // 8: partly cloudy, no gradation, distinct solar corona
    [-1.0, -0.55, 2.0, -1.5, 0.15], // 9: partly cloudy, the sun obscured
    [-1.0, -0.55, 5.0, -2.5, 0.30], // 10: partly cloudy, brighter circumsolar region
    [-1.0, -0.55, 10.0, -3.0, 0.45], // 11: white-blue sky with a distinct solar corona
    [-1.0, -0.32, 10.0, -3.0, 0.45], // 12: CIE standard clear sky, low luminance turbidity
    [-1.0, -0.32, 16.0, -3.0, 0.30], // 13: CIE standard clear sky, polluted atmosphere
    [-1.0, -0.15, 16.0, -3.0, 0.30], // 14: cloudless turbid sky with a broad solar corona
    [-1.0, -0.15, 24.0, -2.8, 0.15], // 15: white-blue turbid sky with a broad solar corona
];

/// The chromaticity the CIE skies are given unless told otherwise: CIE standard illuminant D65
/// (CIE 015:2018, Table T.3: x = 0.31272, y = 0.32903), the CIE's representative daylight.
pub const D65: (f32, f32) = (0.312_72, 0.329_03);

/// The largest zenith luminance a CIE sky takes, cd/m²: above the sun's own disc (about
/// 1.6e9 cd/m² at noon), and low enough that no product of the evaluation (the circumsolar
/// peak of 180 times the zenith's, XYZ of a chromaticity with y = 0.001, linear sRGB,
/// the horizontal integral) reaches f32's range (3.4e38): every value is finite.
pub const MAX_ZENITH_LUMINANCE: f32 = 1e10;

/// The largest diffuse horizontal illuminance a CIE sky is scaled to, lux: far above any
/// daylight (the sun outside the atmosphere gives 1.33e5 lx), and low enough that the zenith
/// luminance it gives stays below [`MAX_ZENITH_LUMINANCE`] for every type and sun.
pub const MAX_DIFFUSE_ILLUMINANCE: f32 = 1e9;

/// The smallest chromaticity y a sky takes: every real colour has y above 0.0048 (the
/// spectrum locus's lowest point, 380-400 nm, and the purple line; CIE 015:2018, Table
/// T.4), and with y at least this, X and Z = (x, 1 − x − y) Y / y stay finite.
pub const MIN_CHROMATICITY_Y: f32 = 1e-3;

/// cos Z is clamped to at least this in the gradation (φ tends to 1 at the horizon for b < 0,
/// and e^{b / 1e-6} is 0 in f32 for every type).
const MIN_COS_ZENITH: f32 = 1e-6;

/// A CIE standard general sky for one sun position, with an absolute luminance scale.
///
/// **Domain**: types 1-15, sun zenith in [0, π/2]. **Units**: luminance in cd/m².
/// **Below the horizon** (the crate's rule, [`geom::below_horizon`]) the luminance is 0. **Colour**: the standard defines
/// luminance only; the sky has one chromaticity everywhere ([`D65`] unless set with
/// [`with_chromaticity`](Self::with_chromaticity)). **Accuracy**: the relative distribution agrees
/// with an f64 evaluation of the standard's formulas to 1e-5 relative (tests in `tests/`); a sky
/// built from a diffuse illuminance reproduces it within 0.5 % (the quadrature of
/// [`photometry`], checked against a brute-force integral).
///
/// ```
/// use sky_core::cie::CieSky;
/// use sky_core::{Photometry, Sun, Vec3};
///
/// let sun = Sun::new(40f32.to_radians(), 0.0)?;
/// let overcast = CieSky::from_diffuse_illuminance(1, sun, 20_000.0)?; // CIE overcast, 20 klx
/// let e = overcast.horizontal_illuminance().y;
/// assert!((e - 20_000.0).abs() < 100.0);
/// // The CIE overcast sky is three times brighter at the zenith than at the horizon.
/// let horizon = overcast.luminance(Vec3::new(1.0, 0.0, 0.0));
/// assert!((overcast.zenith_luminance() / horizon - 3.0).abs() < 0.1);
/// # Ok::<(), sky_core::SkyError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CieSky {
    sun: Sun,
    sky_type: u8,
    /// a, b, c, d, e of Table 1.
    parameters: [f32; 5],
    /// exp(d π/2), the indicatrix's offset.
    indicatrix_offset: f32,
    /// L_z / (f(Z_s) φ(0)), cd/m².
    scale: f32,
    zenith_luminance: f32,
    chromaticity: (f32, f32),
}

impl CieSky {
    /// The sky of type `sky_type` (1-15) for `sun` with zenith luminance `zenith_luminance`
    /// (cd/m², 0 to [`MAX_ZENITH_LUMINANCE`]).
    ///
    /// # Errors
    /// [`SkyError::OutOfRange`] for a type outside 1-15 or a zenith luminance outside
    /// [0, [`MAX_ZENITH_LUMINANCE`]] (or NaN); [`SkyError::SunBelowHorizon`] for a sun zenith
    /// above π/2.
    pub fn new(sky_type: u8, sun: Sun, zenith_luminance: f32) -> Result<Self, SkyError> {
        let zenith_luminance = check_range(
            "zenith luminance [cd/m²]",
            zenith_luminance,
            0.0,
            MAX_ZENITH_LUMINANCE,
        )?;
        let mut sky = Self::relative(sky_type, sun)?;
        sky.zenith_luminance = zenith_luminance;
        sky.scale *= zenith_luminance;
        Ok(sky)
    }

    /// The sky of type `sky_type` (1-15) for `sun`, scaled so that its illuminance on a
    /// horizontal plane is `diffuse_illuminance` (lux, 0 to [`MAX_DIFFUSE_ILLUMINANCE`]).
    ///
    /// # Errors
    /// As [`CieSky::new`], naming the diffuse illuminance and its range
    /// [0, [`MAX_DIFFUSE_ILLUMINANCE`]].
    pub fn from_diffuse_illuminance(
        sky_type: u8,
        sun: Sun,
        diffuse_illuminance: f32,
    ) -> Result<Self, SkyError> {
        let target = check_range(
            "diffuse illuminance [lx]",
            diffuse_illuminance,
            0.0,
            MAX_DIFFUSE_ILLUMINANCE,
        )?;
        let relative = Self::relative(sky_type, sun)?;
        // Every type is positive over the whole hemisphere, so the integral is too.
        let integral = photometry::horizontal_integral(&|d| relative.luminance(d), sun.direction());
        Self::new(sky_type, sun, target / integral)
    }

    /// The sky with zenith luminance 1 cd/m².
    fn relative(sky_type: u8, sun: Sun) -> Result<Self, SkyError> {
        let index = usize::from(sky_type.wrapping_sub(1));
        let Some(&parameters) = STANDARD_SKIES.get(index) else {
            return Err(SkyError::OutOfRange {
                parameter: "CIE sky type",
                value: f32::from(sky_type),
                min: 1.0,
                max: 15.0,
            });
        };
        let zs = sun.zenith();
        if zs > FRAC_PI_2 {
            return Err(SkyError::SunBelowHorizon { zenith: zs });
        }
        let [a, b, c, d, e] = parameters;
        let indicatrix_offset = math::exp_libm(d * FRAC_PI_2);
        let at_zenith_from_sun = 1.0 + c * (math::exp_libm(d * zs) - indicatrix_offset) + {
            let cz = math::cos(zs);
            e * cz * cz
        };
        let gradation_zenith = 1.0 + a * math::exp_libm(b);
        Ok(Self {
            sun,
            sky_type,
            parameters,
            indicatrix_offset,
            scale: 1.0 / (at_zenith_from_sun * gradation_zenith),
            zenith_luminance: 1.0,
            chromaticity: D65,
        })
    }

    /// The same sky with the chromaticity (`x`, `y`) (CIE 1931) everywhere.
    ///
    /// # Errors
    /// [`SkyError::OutOfRange`] for x outside [0, 1] or y outside [[`MIN_CHROMATICITY_Y`], 1]
    /// (or NaN).
    pub fn with_chromaticity(self, x: f32, y: f32) -> Result<Self, SkyError> {
        Ok(Self {
            chromaticity: check_chromaticity(x, y)?,
            ..self
        })
    }

    /// The CIE type, 1-15.
    #[must_use]
    pub fn sky_type(&self) -> u8 {
        self.sky_type
    }

    /// The sun this sky was built for.
    #[must_use]
    pub fn sun(&self) -> Sun {
        self.sun
    }

    /// The parameters a, b, c, d, e of the type (Table 1).
    #[must_use]
    pub fn parameters(&self) -> [f32; 5] {
        self.parameters
    }

    /// Luminance towards `dir` (any length), cd/m²; 0 below the horizon, and for the zero or a
    /// non-finite vector.
    #[inline]
    #[must_use]
    pub fn luminance(&self, dir: Vec3) -> f32 {
        let Some(dir) = dir.try_normalize() else {
            return 0.0;
        };
        if geom::below_horizon(dir) {
            return 0.0;
        }
        let [a, b, c, d, e] = self.parameters;
        let chi = geom::angle_between(dir, self.sun.direction());
        let cos_chi = math::cos(chi);
        let indicatrix =
            1.0 + c * (math::exp(d * chi) - self.indicatrix_offset) + e * cos_chi * cos_chi;
        let gradation = 1.0 + a * math::exp(b / dir.z.max(MIN_COS_ZENITH));
        self.scale * indicatrix * gradation
    }
}

impl Photometry for CieSky {
    fn xyz(&self, dir: Vec3) -> Vec3 {
        let (x, y) = self.chromaticity;
        color::xyy_to_xyz(Xyy {
            x,
            y,
            luminance: self.luminance(dir),
        })
    }

    fn zenith_luminance(&self) -> f32 {
        self.zenith_luminance
    }

    fn horizontal_illuminance(&self) -> Vec3 {
        let (x, y) = self.chromaticity;
        let e = photometry::horizontal_integral(&|d| self.luminance(d), self.sun.direction());
        color::xyy_to_xyz(Xyy { x, y, luminance: e })
    }
}

/// Checks a CIE 1931 chromaticity: x in [0, 1], y in [[`MIN_CHROMATICITY_Y`], 1].
pub(crate) fn check_chromaticity(x: f32, y: f32) -> Result<(f32, f32), SkyError> {
    let x = check_range("chromaticity x", x, 0.0, 1.0)?;
    let y = check_range("chromaticity y", y, MIN_CHROMATICITY_Y, 1.0)?;
    Ok((x, y))
}

#[cfg(test)]
mod tests {
    use super::*;
    use core::f32::consts::PI;

    #[test]
    fn overcast_and_uniform_have_their_closed_forms() {
        let sun = Sun::new(0.7, 1.0).expect("sun");
        // Type 5 is uniform: E = π L.
        let uniform = CieSky::from_diffuse_illuminance(5, sun, 10_000.0).expect("sky");
        let l = uniform.luminance(Vec3::new(0.3, 0.4, 0.5));
        assert!((l * PI - 10_000.0).abs() < 1.0, "{l}");
        // Type 1 has no azimuthal variation: the same at every azimuth of a zenith angle.
        let overcast = CieSky::new(1, sun, 5_000.0).expect("sky");
        let z = 1.1f32;
        let ls: [f32; 4] = core::array::from_fn(|k| {
            overcast.luminance(geom::direction(z, f32::from(u8::try_from(k).unwrap_or(0))))
        });
        assert!(
            ls.iter().all(|v| (v - ls[0]).abs() < 1e-3 * ls[0]),
            "{ls:?}"
        );
        assert!((overcast.luminance(Vec3::Z) - 5_000.0).abs() < 0.1);
    }

    /// Issue 25: the largest levels allowed, every type, sun from the zenith to the horizon,
    /// the most extreme chromaticities: every luminance, XYZ, linear sRGB and illuminance is
    /// finite; just above the bounds the constructors refuse.
    #[test]
    fn the_brightest_skies_allowed_stay_finite() {
        let dirs: [Vec3; 7] = [
            Vec3::Z,
            Vec3::X,
            Vec3::new(0.3, 0.1, 0.95),
            Vec3::new(1.0, 0.0, 1e-7),
            Vec3::new(-1.0, 0.2, 0.01),
            Vec3::new(0.0, 1.0, 1.0),
            Vec3::new(0.7, -0.7, 0.1),
        ];
        let mut largest = 0.0f32;
        for sky_type in 1..=15u8 {
            for k in 0..=18u8 {
                let zs = f32::from(k) * 5f32.to_radians();
                let sun = Sun::new(zs.min(FRAC_PI_2), 0.3).expect("sun");
                let by_lz = CieSky::new(sky_type, sun, MAX_ZENITH_LUMINANCE).expect("sky");
                let by_e = CieSky::from_diffuse_illuminance(sky_type, sun, MAX_DIFFUSE_ILLUMINANCE)
                    .expect("diffuse sky within the zenith luminance's range");
                for sky in [by_lz, by_e] {
                    for (x, y) in [(0.0, MIN_CHROMATICITY_Y), (1.0, MIN_CHROMATICITY_Y), D65] {
                        let sky = sky.with_chromaticity(x, y).expect("chromaticity");
                        for d in dirs {
                            let xyz = sky.xyz(d);
                            let rgb = color::xyz_to_linear_srgb(xyz);
                            assert!(xyz.is_finite() && rgb.is_finite(), "{sky_type} {zs} {d}");
                            largest = largest.max(xyz.abs().max_element());
                        }
                    }
                    assert!(sky.horizontal_illuminance().is_finite());
                    assert!(sky.zenith_luminance().is_finite());
                }
            }
        }
        // Far from f32::MAX: the margin the bounds claim.
        assert!(largest < 1e20, "{largest}");
        let sun = Sun::new(1.0, 0.0).expect("sun");
        assert!(CieSky::new(12, sun, 3e38).is_err());
        assert!(CieSky::new(12, sun, MAX_ZENITH_LUMINANCE * 1.01).is_err());
        assert!(CieSky::from_diffuse_illuminance(12, sun, 3e38).is_err());
        assert!(CieSky::from_diffuse_illuminance(12, sun, f32::INFINITY).is_err());
        assert!(
            CieSky::new(12, sun, 1.0)
                .expect("sky")
                .with_chromaticity(0.3, 1e-30)
                .is_err()
        );
    }

    #[test]
    fn bad_parameters_are_named() {
        let sun = Sun::new(0.5, 0.0).expect("sun");
        assert!(matches!(
            CieSky::new(0, sun, 1.0),
            Err(SkyError::OutOfRange {
                parameter: "CIE sky type",
                ..
            })
        ));
        assert!(CieSky::new(16, sun, 1.0).is_err());
        assert!(CieSky::new(3, sun, f32::NAN).is_err());
        assert!(CieSky::from_diffuse_illuminance(3, sun, -1.0).is_err());
        let below = Sun::new(1.7, 0.0).expect("sun");
        assert!(matches!(
            CieSky::new(12, below, 1.0),
            Err(SkyError::SunBelowHorizon { .. })
        ));
        assert_eq!(
            CieSky::new(12, sun, 1.0).expect("sky").luminance(-Vec3::Z),
            0.0
        );
        assert_eq!(
            CieSky::new(12, sun, 1.0).expect("sky").luminance(Vec3::NAN),
            0.0
        );
    }
}
