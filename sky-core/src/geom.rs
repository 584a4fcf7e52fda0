//! Directions, the sun's position and equirectangular grids.
//!
//! See the crate docs for the axis and angle conventions: +z up, zenith angle θ from +z, azimuth
//! φ from +x towards +y.

use core::f32::consts::{FRAC_PI_2, PI, TAU};

use glam::Vec3;

use crate::error::{SkyError, check_range};
use crate::math;

/// The unit direction with zenith angle `zenith` (θ) and azimuth `azimuth` (φ), in radians:
/// `(sin θ cos φ, sin θ sin φ, cos θ)`.
///
/// ```
/// use sky_core::geom::direction;
/// let up = direction(0.0, 1.0);
/// assert!((up.z - 1.0).abs() < 1e-7);
/// let east = direction(core::f32::consts::FRAC_PI_2, 0.0);
/// assert!((east.x - 1.0).abs() < 1e-7);
/// ```
#[inline]
#[must_use]
pub fn direction(zenith: f32, azimuth: f32) -> Vec3 {
    let (st, ct) = (math::sin(zenith), math::cos(zenith));
    let (sp, cp) = (math::sin(azimuth), math::cos(azimuth));
    Vec3::new(st * cp, st * sp, ct)
}

/// The zenith angle θ in `[0, π]` and azimuth φ in `[0, 2π)` of a direction (need not be unit
/// length; the zero vector gives `(π/2, 0)`).
///
/// ```
/// use sky_core::geom::{direction, zenith_azimuth};
/// let (t, p) = zenith_azimuth(direction(0.5, 4.0));
/// assert!((t - 0.5).abs() < 1e-6 && (p - 4.0).abs() < 1e-6);
/// ```
#[inline]
#[must_use]
pub fn zenith_azimuth(dir: Vec3) -> (f32, f32) {
    let horizontal = math::sqrt(dir.x * dir.x + dir.y * dir.y);
    let zenith = math::atan2_libm(horizontal, dir.z);
    let mut azimuth = math::atan2_libm(dir.y, dir.x);
    if azimuth < 0.0 {
        azimuth += TAU;
    }
    // atan2 of a tiny negative y rounds to exactly 2π after the shift: keep the range half-open.
    if azimuth >= TAU {
        azimuth = 0.0;
    }
    let zenith = if zenith.is_nan() { FRAC_PI_2 } else { zenith };
    let azimuth = if azimuth.is_nan() { 0.0 } else { azimuth };
    (zenith, azimuth)
}

/// Views down to this far below the horizon (in z of the unit direction, cos θ, ≈ radians below
/// it) still count as on the horizon: the f32 nearest π/2 lies 4.4e-8 rad past it, and a view
/// "at the horizon" should not go dark. The crate's one below-horizon rule (crate docs,
/// "Conventions") uses it.
pub const HORIZON_TOLERANCE: f32 = 1e-6;

/// Whether the unit direction `dir` is below the horizon by the crate's one rule (crate docs,
/// "Conventions"): `dir.z < -HORIZON_TOLERANCE`. Every sky model's radiance is 0 there. A NaN
/// `z` is not below the horizon (each model documents its value for non-finite input).
///
/// ```
/// use sky_core::geom::{below_horizon, direction};
/// assert!(below_horizon(direction(100f32.to_radians(), 0.0)));
/// assert!(!below_horizon(direction(core::f32::consts::FRAC_PI_2, 0.0))); // on it
/// ```
#[inline]
#[must_use]
pub fn below_horizon(dir: Vec3) -> bool {
    dir.z < -HORIZON_TOLERANCE
}

/// The angle between two directions in radians, in `[0, π]`.
///
/// Computed as `atan2(|a × b|, a · b)` (the vector form of Vincenty's formula, seed 002 eq. 26),
/// which keeps full relative accuracy near 0 and π, where `acos(a · b)` loses half its digits.
/// The inputs need not be unit length.
#[inline]
#[must_use]
pub fn angle_between(a: Vec3, b: Vec3) -> f32 {
    math::atan2_libm(a.cross(b).length(), a.dot(b))
}

/// The sun's position in the sky: zenith angle and azimuth, in radians.
///
/// `Sun` only checks that the angles are finite and the zenith lies in `[0, π]`; whether a model
/// accepts a sun below the horizon is the model's decision.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sun {
    zenith: f32,
    azimuth: f32,
    dir: Vec3,
}

impl Sun {
    /// A sun at zenith angle `zenith` in `[0, π]` and azimuth `azimuth` (any finite value).
    ///
    /// # Errors
    /// [`SkyError::OutOfRange`] for a zenith outside `[0, π]` or NaN, [`SkyError::NotFinite`] for
    /// a NaN or infinite azimuth.
    pub fn new(zenith: f32, azimuth: f32) -> Result<Self, SkyError> {
        let zenith = check_range("sun zenith [rad]", zenith, 0.0, PI)?;
        if !azimuth.is_finite() {
            return Err(SkyError::NotFinite {
                parameter: "sun azimuth [rad]",
            });
        }
        Ok(Self {
            zenith,
            azimuth,
            dir: direction(zenith, azimuth),
        })
    }

    /// The zenith angle in radians, in `[0, π]`.
    #[must_use]
    pub fn zenith(&self) -> f32 {
        self.zenith
    }

    /// The azimuth in radians, as given.
    #[must_use]
    pub fn azimuth(&self) -> f32 {
        self.azimuth
    }

    /// The unit direction towards the sun.
    #[must_use]
    pub fn direction(&self) -> Vec3 {
        self.dir
    }
}

/// Which part of the sphere an equirectangular grid covers.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Extent {
    /// The upper hemisphere, zenith angle 0 to π/2 from the top row to the bottom row (seed 002,
    /// eqs. 20-21).
    UpperHemisphere,
    /// The whole sphere, zenith angle 0 to π from the top row to the bottom row.
    Sphere,
}

/// An equirectangular (latitude-longitude) grid of pixel centres.
///
/// Column `i` of `width` has azimuth φ = 2π (i + ½) / width (seed 002 eqs. 20-21: u = (i + ½)/W,
/// ψ = 2πu), increasing to the right. Row `j` of `height` has zenith angle
/// θ = θ_max (j + ½) / height, with θ_max = π/2 for [`Extent::UpperHemisphere`] (the seed's
/// v = (2j + 1)/H with `height` = H/2) and π for [`Extent::Sphere`].
///
/// ```
/// use sky_core::geom::{Equirect, Extent};
/// let grid = Equirect::new(1024, 512, Extent::Sphere)?;
/// let d = grid.direction(0, 0); // top-left pixel: near the zenith
/// assert!(d.z > 0.99999);
/// # Ok::<(), sky_core::SkyError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Equirect {
    width: u32,
    height: u32,
    extent: Extent,
}

impl Equirect {
    /// The largest width or height accepted.
    pub const MAX_SIZE: u32 = 1 << 16;

    /// A `width` × `height` grid covering `extent`.
    ///
    /// # Errors
    /// [`SkyError::OutOfRange`] when `width` or `height` is 0 or above [`Self::MAX_SIZE`].
    pub fn new(width: u32, height: u32, extent: Extent) -> Result<Self, SkyError> {
        #[allow(clippy::cast_precision_loss)] // exact: both are at most 2^16
        for (parameter, value) in [("grid width [px]", width), ("grid height [px]", height)] {
            if value == 0 || value > Self::MAX_SIZE {
                return Err(SkyError::OutOfRange {
                    parameter,
                    value: value as f32,
                    min: 1.0,
                    max: Self::MAX_SIZE as f32,
                });
            }
        }
        Ok(Self {
            width,
            height,
            extent,
        })
    }

    /// Width in pixels.
    #[must_use]
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    #[must_use]
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The part of the sphere covered.
    #[must_use]
    pub fn extent(&self) -> Extent {
        self.extent
    }

    fn max_zenith(&self) -> f32 {
        match self.extent {
            Extent::UpperHemisphere => FRAC_PI_2,
            Extent::Sphere => PI,
        }
    }

    /// The zenith angle of row `j` (rows beyond the grid extrapolate linearly).
    #[must_use]
    #[allow(clippy::cast_precision_loss)] // exact below 2^24
    pub fn zenith(&self, j: u32) -> f32 {
        self.max_zenith() * (j as f32 + 0.5) / self.height as f32
    }

    /// The azimuth of column `i` (columns beyond the grid extrapolate linearly).
    #[must_use]
    #[allow(clippy::cast_precision_loss)] // exact below 2^24
    pub fn azimuth(&self, i: u32) -> f32 {
        TAU * (i as f32 + 0.5) / self.width as f32
    }

    /// The unit direction through the centre of pixel (`i`, `j`).
    #[must_use]
    pub fn direction(&self, i: u32, j: u32) -> Vec3 {
        direction(self.zenith(j), self.azimuth(i))
    }

    /// The solid angle of a pixel of row `j`, in steradians (exact for the pixel's area on the
    /// sphere: Δφ (cos θ_top − cos θ_bottom)).
    #[must_use]
    #[allow(clippy::cast_precision_loss)] // exact below 2^24
    pub fn solid_angle(&self, j: u32) -> f32 {
        let dt = self.max_zenith() / self.height as f32;
        let rows_from_zenith = j as f32 + 0.5;
        // The row's middle zenith angle, counted from the nearer pole so that sin stays accurate
        // near the nadir too (sin(π − a) = sin a, and f32 π − a would round).
        let from_pole = match self.extent {
            Extent::Sphere => rows_from_zenith.min(self.height as f32 - rows_from_zenith),
            Extent::UpperHemisphere => rows_from_zenith,
        };
        let dphi = TAU / self.width as f32;
        // cos a − cos b = 2 sin((a+b)/2) sin((b−a)/2): no cancellation near the poles.
        dphi * 2.0 * math::sin(dt * from_pole) * math::sin(0.5 * dt)
    }

    /// The pixel (column, row) whose cell contains `dir`, or `None` when `dir` lies outside the
    /// grid's extent or is not finite.
    #[must_use]
    #[allow(
        clippy::cast_precision_loss,
        clippy::cast_possible_truncation,
        clippy::cast_sign_loss
    )]
    pub fn pixel(&self, dir: Vec3) -> Option<(u32, u32)> {
        if !dir.is_finite() || dir == Vec3::ZERO {
            return None;
        }
        let (zenith, azimuth) = zenith_azimuth(dir);
        let v = zenith / self.max_zenith();
        if v > 1.0 {
            return None;
        }
        let i = math::floor(azimuth / TAU * self.width as f32) as u32;
        let j = math::floor(v * self.height as f32) as u32;
        Some((i.min(self.width - 1), j.min(self.height - 1)))
    }
}

/// `Sun { zenith, azimuth }` in radians (its direction vector is derived from them).
#[cfg(feature = "defmt")]
impl defmt::Format for Sun {
    fn format(&self, f: defmt::Formatter<'_>) {
        defmt::write!(
            f,
            "Sun {{ zenith: {=f32} rad, azimuth: {=f32} rad }}",
            self.zenith(),
            self.azimuth()
        );
    }
}
