//! The Perez all-weather sky with Preetham's coefficients (seed 002, eqs. 1-19).
//!
//! Luminance `Y` and chromaticity `x, y` each follow the Perez distribution
//! F(θ, γ) = (1 + A e^{B / cos θ}) (1 + C e^{D γ} + E cos² γ) (eq. 10), scaled so that the zenith
//! takes the values of eqs. 16-19 (eqs. 11-12). θ is the view's zenith angle and γ the angle
//! between the view and the sun.

use core::f32::consts::PI;

use glam::Vec3;

use crate::color::{self, Xyy};
use crate::error::{SkyError, check_range};
use crate::geom::Sun;
use crate::math;

/// The smallest turbidity accepted. Seed 000 (§III-D) trains on Preetham skies with turbidity
/// 2 to 6, "valid for the original methods"; below 2 the model's horizon brightens implausibly
/// (Zotti et al. 2007, cited by seed 001 §2.2).
pub const MIN_TURBIDITY: f32 = 2.0;
/// The largest turbidity accepted (see [`MIN_TURBIDITY`]).
pub const MAX_TURBIDITY: f32 = 6.0;

/// cos θ is clamped to at least this, so e^{B / cos θ} stays finite (it is 0 in f32 well before:
/// |B| ≥ 0.13 over the valid turbidities, and e^{-0.13e6} underflows).
pub const MIN_COS_THETA: f32 = 1e-6;

/// Views down to this far below the horizon (in cos θ, ≈ radians) still count as on the horizon:
/// [`geom::HORIZON_TOLERANCE`](crate::geom::HORIZON_TOLERANCE), the crate's one below-horizon
/// rule (crate docs, "Conventions").
pub const HORIZON_TOLERANCE: f32 = crate::geom::HORIZON_TOLERANCE;

/// The five Perez coefficients A-E of one channel (seed 002, eq. 10).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct PerezCoefficients {
    /// Darkening or brightening of the horizon.
    pub a: f32,
    /// Luminance gradient near the horizon.
    pub b: f32,
    /// Relative intensity of the circumsolar region.
    pub c: f32,
    /// Width of the circumsolar region.
    pub d: f32,
    /// Relative backscattered light.
    pub e: f32,
}

impl PerezCoefficients {
    /// The coefficients as linear functions of turbidity: rows of `[slope, intercept]`
    /// (eqs. 13-15).
    fn from_turbidity(rows: &[[f32; 2]; 5], t: f32) -> Self {
        let at = |r: usize| rows[r][0] * t + rows[r][1];
        Self {
            a: at(0),
            b: at(1),
            c: at(2),
            d: at(3),
            e: at(4),
        }
    }

    /// The Perez function F(θ, γ), eq. 10, from cos θ (clamped to at least 1e-6), γ in radians and
    /// cos γ.
    #[inline]
    #[must_use]
    pub fn evaluate(&self, cos_theta: f32, gamma: f32, cos_gamma: f32) -> f32 {
        self.evaluate_parts(
            1.0 / cos_theta.max(MIN_COS_THETA),
            gamma,
            cos_gamma * cos_gamma,
        )
    }

    /// Eq. 10 from 1 / cos θ, γ and cos² γ (shared by the three channels of a direction).
    #[inline(always)]
    fn evaluate_parts(&self, inv_cos_theta: f32, gamma: f32, cos2_gamma: f32) -> f32 {
        (1.0 + self.a * math::exp(self.b * inv_cos_theta))
            * (1.0 + self.c * math::exp(self.d * gamma) + self.e * cos2_gamma)
    }

    /// The coefficients with B and D multiplied by log₂e, for [`Self::evaluate_log2`].
    fn to_log2(self) -> Self {
        let l = core::f32::consts::LOG2_E;
        Self {
            b: self.b * l,
            d: self.d * l,
            ..self
        }
    }

    /// [`Self::evaluate_parts`] for coefficients from [`Self::to_log2`]: e^{B u} = 2^{(B log₂e) u},
    /// saving a multiplication per exponential.
    #[inline(always)]
    fn evaluate_log2(&self, inv_cos_theta: f32, gamma: f32, cos2_gamma: f32) -> f32 {
        (1.0 + self.a * math::exp2(self.b * inv_cos_theta))
            * (1.0 + self.c * math::exp2(self.d * gamma) + self.e * cos2_gamma)
    }
}

/// Eq. 13: Perez coefficients of luminance Y, `[slope, intercept]` in turbidity T.
const PEREZ_LUMINANCE: [[f32; 2]; 5] = [
    [0.1787, -1.4630],
    [-0.3554, 0.4275],
    [-0.0227, 5.3251],
    [0.1206, -2.5771],
    [-0.0670, 0.3703],
];
/// Eq. 14: Perez coefficients of chromaticity x.
const PEREZ_X: [[f32; 2]; 5] = [
    [-0.0193, -0.2592],
    [-0.0665, 0.0008],
    [-0.0004, 0.2125],
    [-0.0641, -0.8989],
    [-0.0033, 0.0452],
];
/// Eq. 15: Perez coefficients of chromaticity y.
const PEREZ_Y: [[f32; 2]; 5] = [
    [-0.0167, -0.2608],
    [-0.0950, 0.0092],
    [-0.0079, 0.2102],
    [-0.0441, -1.6537],
    [-0.0109, 0.0529],
];
/// Eq. 18: zenith chromaticity x = [T² T 1] M [θs³ θs² θs 1]ᵀ.
const ZENITH_X: [[f32; 4]; 3] = [
    [0.0017, -0.0037, 0.0021, 0.000],
    [-0.0290, 0.0638, -0.0320, 0.0039],
    [0.1169, -0.2120, 0.0605, 0.2589],
];
/// Eq. 19: zenith chromaticity y.
const ZENITH_Y: [[f32; 4]; 3] = [
    [0.0028, -0.0061, 0.0032, 0.000],
    [-0.0421, 0.0897, -0.0415, 0.0052],
    [0.1535, -0.2676, 0.0667, 0.2669],
];

/// Zenith luminance in cd/m², eqs. 16-17 (which give kcd/m²; the factor 1000 converts).
fn zenith_luminance(t: f32, sun_zenith: f32) -> f32 {
    let chi = (4.0 / 9.0 - t / 120.0) * (PI - 2.0 * sun_zenith);
    1000.0 * ((4.0453 * t - 4.9710) * math::tan(chi) - 0.2155 * t + 2.4192)
}

/// Zenith chromaticity, eqs. 18-19.
fn zenith_chromaticity(m: &[[f32; 4]; 3], t: f32, sun_zenith: f32) -> f32 {
    let s = sun_zenith;
    let powers_s = [s * s * s, s * s, s, 1.0];
    let powers_t = [t * t, t, 1.0];
    let mut sum = 0.0;
    for (row, pt) in m.iter().zip(powers_t) {
        let r: f32 = row.iter().zip(powers_s).map(|(c, p)| c * p).sum();
        sum += pt * r;
    }
    sum
}

/// What [`PreethamSky`]'s per-direction kernel reads besides the sun direction
/// ([`PreethamSky::kernel_constants`]).
///
/// Channel c of a direction (Y, x, y for c = 0, 1, 2) is
/// `scale[c] · (1 + A 2^{B' / cos θ}) (1 + C 2^{D' γ} + E cos² γ)` with the coefficients of
/// `perez_log2[c]`, whose B' and D' are eq. 10's B and D times log₂e (e^{B u} = 2^{(B log₂e) u}).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct KernelConstants {
    /// The Perez coefficients of Y, x and y, B and D multiplied by log₂e.
    pub perez_log2: [PerezCoefficients; 3],
    /// Zenith value / F(0, θs) per channel (Y in cd/m², x, y): the factors of eqs. 11-12.
    pub scale: [f32; 3],
}

/// The Preetham clear sky for one sun position and turbidity.
///
/// Construct it once per sun and atmosphere with [`PreethamSky::new`]; then evaluate any number
/// of view directions with [`xyy`](Self::xyy), [`xyz`](Self::xyz), [`rgb`](Self::rgb) or the
/// batch forms [`xyy_batch`](Self::xyy_batch), [`rgb_batch`](Self::rgb_batch).
///
/// **Domain**: turbidity in [[`MIN_TURBIDITY`], [`MAX_TURBIDITY`]], sun zenith in [0, π/2].
/// **Units**: luminance in cd/m² (eq. 16 gives kcd/m²; this type multiplies by 1000), linear
/// sRGB on the same scale. **Below the horizon** (view `z < -1e-6`, so that the f32 nearest π/2
/// still counts as the horizon) the luminance is 0 and the chromaticity that of the horizon
/// (θ = π/2) at the same angle from the sun.
/// **Accuracy**: agrees with an f64 evaluation of eqs. 10-19 to 1e-5 relative in Y, x and y
/// (tested over the whole domain and the upper hemisphere). The batch functions give the same
/// results as the single-direction ones, bit for bit, on every target.
///
/// ```
/// use sky_core::{geom, PreethamSky, Sun};
/// let sky = PreethamSky::new(Sun::new(0.3, 0.0)?, 2.5)?;
/// let towards_sun = sky.xyy(geom::direction(0.35, 0.0));
/// let away = sky.xyy(geom::direction(0.35, core::f32::consts::PI));
/// assert!(towards_sun.luminance > away.luminance);
/// # Ok::<(), sky_core::SkyError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PreethamSky {
    sun: Sun,
    turbidity: f32,
    /// Perez coefficients of Y, x and y.
    perez: [PerezCoefficients; 3],
    /// The same with B and D scaled by log₂e, for the per-direction kernel.
    perez_log2: [PerezCoefficients; 3],
    /// Zenith Y (cd/m²), x and y.
    zenith: Xyy,
    /// Zenith value / F(0, θs) per channel, the factors of eqs. 11-12.
    scale: [f32; 3],
}

impl PreethamSky {
    /// The sky for `sun` (zenith in [0, π/2]) and `turbidity` in
    /// [[`MIN_TURBIDITY`], [`MAX_TURBIDITY`]].
    ///
    /// # Errors
    /// [`SkyError::SunBelowHorizon`] for a sun zenith above π/2; [`SkyError::OutOfRange`] for a
    /// turbidity outside the range or NaN.
    pub fn new(sun: Sun, turbidity: f32) -> Result<Self, SkyError> {
        let t = check_range("turbidity", turbidity, MIN_TURBIDITY, MAX_TURBIDITY)?;
        let theta_s = sun.zenith();
        if theta_s > core::f32::consts::FRAC_PI_2 {
            return Err(SkyError::SunBelowHorizon { zenith: theta_s });
        }
        let perez = [
            PerezCoefficients::from_turbidity(&PEREZ_LUMINANCE, t),
            PerezCoefficients::from_turbidity(&PEREZ_X, t),
            PerezCoefficients::from_turbidity(&PEREZ_Y, t),
        ];
        let zenith = Xyy {
            x: zenith_chromaticity(&ZENITH_X, t, theta_s),
            y: zenith_chromaticity(&ZENITH_Y, t, theta_s),
            luminance: zenith_luminance(t, theta_s),
        };
        let at_zenith = [zenith.luminance, zenith.x, zenith.y];
        let cos_s = math::cos(theta_s);
        let scale = core::array::from_fn(|c| at_zenith[c] / perez[c].evaluate(1.0, theta_s, cos_s));
        Ok(Self {
            sun,
            turbidity: t,
            perez,
            perez_log2: perez.map(PerezCoefficients::to_log2),
            zenith,
            scale,
        })
    }

    /// The sun this sky was built for.
    #[must_use]
    pub fn sun(&self) -> Sun {
        self.sun
    }

    /// The turbidity this sky was built for.
    #[must_use]
    pub fn turbidity(&self) -> f32 {
        self.turbidity
    }

    /// The zenith's luminance (cd/m²) and chromaticity, eqs. 16-19.
    #[must_use]
    pub fn zenith(&self) -> Xyy {
        self.zenith
    }

    /// The Perez coefficients of luminance Y and chromaticities x and y, in that order.
    #[must_use]
    pub fn perez_coefficients(&self) -> [PerezCoefficients; 3] {
        self.perez
    }

    /// The constants of the per-direction kernel, exactly as [`xyy`](Self::xyy) uses them: for
    /// GPU shaders (sky-gpu) that evaluate eqs. 10-12 with these values as uniforms.
    #[must_use]
    pub fn kernel_constants(&self) -> KernelConstants {
        KernelConstants {
            perez_log2: self.perez_log2,
            scale: self.scale,
        }
    }

    /// Luminance (cd/m²) and chromaticity towards `dir`, eqs. 11-12.
    ///
    /// `dir` need not be normalised if its length lies in [1e-18, 1e18]; the zero vector and
    /// non-finite vectors give a finite, meaningless value.
    #[inline]
    #[must_use]
    pub fn xyy(&self, dir: Vec3) -> Xyy {
        self.xyy_lane(dir)
    }

    /// CIE XYZ towards `dir` (Y in cd/m²), eq. 27 applied to [`xyy`](Self::xyy).
    #[inline]
    #[must_use]
    pub fn xyz(&self, dir: Vec3) -> Vec3 {
        color::xyy_to_xyz(self.xyy(dir))
    }

    /// Linear sRGB towards `dir`, on the cd/m² scale, eq. 28 applied to [`xyz`](Self::xyz).
    #[inline]
    #[must_use]
    pub fn rgb(&self, dir: Vec3) -> Vec3 {
        self.rgb_lane(dir)
    }

    /// [`xyy`](Self::xyy) for many directions: fills `out[i]` for every `i` below
    /// `min(dirs.len(), out.len())`, with the same results as `xyy` bit for bit. The loop is
    /// written to compile to SIMD code.
    #[inline(always)]
    pub fn xyy_batch(&self, dirs: &[Vec3], out: &mut [Xyy]) {
        for (o, d) in out.iter_mut().zip(dirs) {
            *o = self.xyy_lane(*d);
        }
    }

    /// [`rgb`](Self::rgb) for many directions: fills `out[i]` for every `i` below
    /// `min(dirs.len(), out.len())`, with the same results as `rgb` bit for bit. The loop is
    /// written to compile to SIMD code.
    #[inline(always)]
    pub fn rgb_batch(&self, dirs: &[Vec3], out: &mut [Vec3]) {
        for (o, d) in out.iter_mut().zip(dirs) {
            *o = self.rgb_lane(*d);
        }
    }

    /// [`rgb`](Self::rgb), always inlined so that loops over directions vectorise.
    #[inline(always)]
    fn rgb_lane(&self, dir: Vec3) -> Vec3 {
        color::xyz_to_linear_srgb(color::xyy_to_xyz(self.xyy_lane(dir)))
    }

    /// Eqs. 10-12 without a branch, always inlined so that loops over directions vectorise.
    #[inline(always)]
    fn xyy_lane(&self, dir: Vec3) -> Xyy {
        // normalize_or_zero, with the kernel rsqrt (libm's sqrt is not vectorisable).
        let inv_len = math::rsqrt(dir.length_squared());
        let dir = dir * inv_len;
        let s = self.sun.direction();
        // NaN goes to −1.
        let cos_gamma = math::at_most(math::at_least(dir.dot(s), -1.0), 1.0);
        let cross2 = dir.cross(s).length_squared();
        let sin_gamma = cross2 * math::rsqrt(cross2);
        let gamma = math::atan2(sin_gamma, cos_gamma);
        // cos θ ≤ 1 also for a vector too long for f32's squares, which is not unit length
        // after the normalisation (the Perez function is only defined for cos θ in (0, 1]).
        let inv_cos_theta = 1.0 / math::at_least(math::at_most(dir.z, 1.0), MIN_COS_THETA);
        let cos2_gamma = cos_gamma * cos_gamma;
        let f = |c: usize| {
            self.scale[c] * self.perez_log2[c].evaluate_log2(inv_cos_theta, gamma, cos2_gamma)
        };
        let above = if dir.z >= -HORIZON_TOLERANCE {
            1.0
        } else {
            0.0
        };
        Xyy {
            x: f(1),
            y: f(2),
            luminance: f(0) * above,
        }
    }
}
