//! One sensor is enough: the split of a global horizontal irradiance into its diffuse and direct
//! (beam) parts, by the correlation of Erbs, Klein and Duffie, *Estimation of the diffuse
//! radiation fraction for hourly, daily and monthly-average global radiation* (Solar Energy
//! 28(4), 1982), eq. 1, the hourly diffuse fraction k_d = I_d / I as a function of the clearness
//! index k_t = I / (I₀ cos Z):
//!
//! * k_d = 1 − 0.09 k_t for k_t ≤ 0.22;
//! * k_d = 0.9511 − 0.1604 k_t + 4.388 k_t² − 16.638 k_t³ + 12.336 k_t⁴ for 0.22 < k_t ≤ 0.80;
//! * k_d = 0.165 for k_t > 0.80.
//!
//! Coefficients from the paper, checked against pvlib's `irradiance.erbs` (a test compares
//! 400 of pvlib 0.16.1's outputs). Near the horizon the clearness index is ill-conditioned;
//! as pvlib does, cos Z is taken as at least 0.065 (Z ≈ 86.3°) in k_t, k_t is capped at 1, and the
//! direct normal irradiance is 0 for Z above 87° (all of the global counted as diffuse).
//!
//! **Error**: Erbs et al. fitted the correlation to hourly data of five stations in the United
//! States; like every one-predictor correlation it cannot follow what k_t alone does not tell
//! (cloud type, aerosol, the sun's height). It is not better than the best, locally adjusted
//! multi-predictor models that Abal et al. (*Performance of empirical models for diffuse fraction
//! in Uruguay*, Solar Energy 141, 2017) evaluate at about 18 % (of the mean) uncertainty in the
//! hourly diffuse fraction; its own error in a given climate is that of such comparisons, not a
//! property this crate can state.

use core::f32::consts::FRAC_PI_2;

use crate::error::{SkyError, check_range};
use crate::math;

/// The smallest cos Z used in the clearness index (pvlib's `min_cos_zenith`).
pub const MIN_COS_ZENITH: f32 = 0.065;

/// The largest sun zenith angle with a direct beam, radians (87°, pvlib's `max_zenith`).
pub const MAX_BEAM_ZENITH: f32 = 87.0 * core::f32::consts::PI / 180.0;

/// Global horizontal irradiance this many times the extraterrestrial horizontal irradiance (with
/// cos Z at least [`MIN_COS_ZENITH`]) is refused: cloud enhancement lifts k_t a little above 1,
/// but never to 1.5.
pub const MAX_CLEARNESS_INDEX: f32 = 1.5;

/// The hourly diffuse fraction of Erbs et al. 1982 at clearness index `kt` (module docs); NaN
/// and values below 0 count as 0.
///
/// ```
/// use sky_core::decomposition::erbs_diffuse_fraction;
/// assert_eq!(erbs_diffuse_fraction(0.1), 1.0 - 0.09 * 0.1);
/// assert_eq!(erbs_diffuse_fraction(0.9), 0.165);
/// ```
#[must_use]
pub fn erbs_diffuse_fraction(kt: f32) -> f32 {
    let kt = if kt > 0.0 { kt } else { 0.0 };
    if kt <= 0.22 {
        1.0 - 0.09 * kt
    } else if kt <= 0.80 {
        0.9511 + kt * (-0.1604 + kt * (4.388 + kt * (-16.638 + kt * 12.336)))
    } else {
        0.165
    }
}

/// A global horizontal irradiance and its parts, W/m².
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Components {
    /// Global horizontal irradiance.
    pub global: f32,
    /// Diffuse horizontal irradiance.
    pub diffuse: f32,
    /// Direct normal irradiance (the beam on a plane facing the sun).
    pub direct_normal: f32,
    /// The clearness index k_t, in [0, 1].
    pub clearness_index: f32,
}

/// The clearness index k_t = I / (I₀ max(cos Z, [`MIN_COS_ZENITH`])) of a global horizontal
/// irradiance `global` (W/m²) with the sun at zenith angle `sun_zenith` (radians, clamped to
/// [0, π/2]) and extraterrestrial irradiance `extraterrestrial` (W/m²), not capped.
#[must_use]
pub fn clearness_index(global: f32, sun_zenith: f32, extraterrestrial: f32) -> f32 {
    let z = if sun_zenith.is_nan() {
        FRAC_PI_2
    } else {
        sun_zenith.clamp(0.0, FRAC_PI_2)
    };
    global / (extraterrestrial * math::cos(z).max(MIN_COS_ZENITH))
}

/// Splits the global horizontal irradiance `global` (W/m²) with the sun at zenith angle
/// `sun_zenith` (radians, [0, π/2]) and extraterrestrial irradiance `extraterrestrial`
/// (W/m², [`crate::solar::extraterrestrial_irradiance`]) by Erbs's correlation.
///
/// ```
/// use sky_core::decomposition::erbs;
/// let sunny = erbs(800.0, 30f32.to_radians(), 1361.0)?;
/// assert!(sunny.diffuse < 0.3 * sunny.global && sunny.direct_normal > 600.0);
/// let dull = erbs(100.0, 30f32.to_radians(), 1361.0)?;
/// assert!(dull.diffuse > 0.95 * dull.global);
/// # Ok::<(), sky_core::SkyError>(())
/// ```
///
/// # Errors
/// [`SkyError::OutOfRange`] for a negative or NaN global irradiance, one above
/// [`MAX_CLEARNESS_INDEX`] times the extraterrestrial horizontal irradiance, a sun zenith outside
/// [0, π/2] or an extraterrestrial irradiance outside [1000, 1500] W/m².
pub fn erbs(global: f32, sun_zenith: f32, extraterrestrial: f32) -> Result<Components, SkyError> {
    let z = check_range("sun zenith [rad]", sun_zenith, 0.0, FRAC_PI_2)?;
    let i0 = check_range(
        "extraterrestrial irradiance [W/m²]",
        extraterrestrial,
        1000.0,
        1500.0,
    )?;
    let limit = MAX_CLEARNESS_INDEX * i0 * math::cos(z).max(MIN_COS_ZENITH);
    let global = check_range("global irradiance [W/m²]", global, 0.0, limit)?;
    let kt = clearness_index(global, z, i0).min(1.0);
    // Above 87° all of it counts as diffuse, so that diffuse + beam stays the global.
    let (diffuse, direct_normal) = if z > MAX_BEAM_ZENITH {
        (global, 0.0)
    } else {
        let diffuse = erbs_diffuse_fraction(kt) * global;
        (diffuse, ((global - diffuse) / math::cos(z)).max(0.0))
    };
    Ok(Components {
        global,
        diffuse,
        direct_normal,
        clearness_index: kt,
    })
}
