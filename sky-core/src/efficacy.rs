//! Luminous efficacy of daylight, from W/m² to lux: the models of Perez, Ineichen, Seals,
//! Michalsky, Stewart, *Modeling daylight availability and irradiance components from direct and
//! global irradiance* (Solar Energy 44(5), 1990), Table 4, by sky-clearness bin
//! ([`crate::perez::SkyCondition::bin`]):
//!
//! * global horizontal: K_g = a + b W + c cos Z + d ln Δ (eq. 6);
//! * diffuse horizontal: K_d = a + b W + c cos Z + d ln Δ (eq. 7);
//! * direct normal: K_b = max(0, a + b W + c exp(5.73 Z − 5) + d Δ) (eq. 8);
//!
//! in lm/W, with Z the sun's zenith angle in radians (clamped to [0, π/2]), W the precipitable
//! water in cm ([`precipitable_water`]) and Δ the sky brightness (clamped to
//! [`crate::perez::BRIGHTNESS_RANGE`], so that ln Δ stays finite). The paper validates the
//! models against measurements at sites other than those they were fitted to (its §5); those
//! errors are the paper's and are not restated here.
//!
//! **Continuous in ε** (a deviation from the paper, whose coefficients step at the bin edges:
//! up to 40 % in the global efficacy between bins 1 and 2 at the extremes of Δ and water, a few per cent
//! at typical skies): the coefficients hold as tabulated at each bin's centre
//! ([`BIN_CENTRES`]: the middle of bins 1-7, and for the open bin 8 its lower edge 6.2 plus half
//! of bin 7's width) and are interpolated linearly in ε between neighbouring centres (below
//! bin 1's centre and above bin 8's they are those of bins 1 and 8). The efficacy is then
//! continuous, its change across any ε interval bounded by its slope: the relative change of
//! the global and diffuse efficacies is at most 2.4 times the relative change of ε (between
//! the centres of bins 1 and 2 at Δ = 0.01; a test holds it). Within a bin, the deviation from
//! the tabulated value is at most the half step to the neighbouring bin, and 0 at the centre.
//! [`SkyCondition::bin`] (the sky type) is unchanged.
//!
//! Coefficients transcribed from Radiance's `gendaylit.c` (which follows Table 4) and checked
//! value by value against Radiance's `gendaymtx.c` (diffuse and direct) and the `cPerezSkyModel`
//! class of the CitySim solver (all three): they agree everywhere.

use crate::math;
use crate::perez::SkyCondition;

/// Rows a, b, c, d of one efficacy model for the eight sky-clearness bins.
type EfficacyTable = [[f32; 4]; 8];

/// Table 4, global horizontal efficacy (eq. 6).
const GLOBAL: EfficacyTable = [
    [96.63, -0.47, 11.50, -9.16],
    [107.54, 0.79, 1.79, -1.19],
    [98.73, 0.70, 4.40, -6.95],
    [92.72, 0.56, 8.36, -8.31],
    [86.73, 0.98, 7.10, -10.94],
    [88.34, 1.39, 6.06, -7.60],
    [78.63, 1.47, 4.93, -11.37],
    [99.65, 1.86, -4.46, -3.15],
];

/// Table 4, diffuse horizontal efficacy (eq. 7).
const DIFFUSE: EfficacyTable = [
    [97.24, -0.46, 12.00, -8.91],
    [107.22, 1.15, 0.59, -3.95],
    [104.97, 2.96, -5.53, -8.77],
    [102.39, 5.59, -13.95, -13.90],
    [100.71, 5.94, -22.75, -23.74],
    [106.42, 3.83, -36.15, -28.83],
    [141.88, 1.90, -53.24, -14.03],
    [152.23, 0.35, -45.27, -7.98],
];

/// Table 4, direct normal efficacy (eq. 8).
const DIRECT: EfficacyTable = [
    [57.20, -4.55, -2.98, 117.12],
    [98.99, -3.46, -1.21, 12.38],
    [109.83, -4.90, -1.71, -8.81],
    [110.34, -5.84, -1.99, -4.56],
    [106.36, -3.97, -1.75, -6.16],
    [107.19, -1.25, -1.51, -26.73],
    [105.75, 0.77, -1.26, -34.44],
    [101.18, 1.58, -1.10, -8.29],
];

/// The sky clearness ε at which each bin's coefficients hold as tabulated (module docs): the
/// middle of each of bins 1-7 (edges 1, [`crate::perez::CLEARNESS_BIN_EDGES`]), and for bin 8,
/// open above 6.2, 6.2 + (6.2 − 4.5) / 2.
pub const BIN_CENTRES: [f32; 8] = [1.0325, 1.1475, 1.365, 1.725, 2.375, 3.65, 5.35, 7.05];

/// The coefficients of `table` at sky clearness `epsilon`: linear between [`BIN_CENTRES`],
/// constant beyond the first and the last (NaN counts as bin 1's).
fn coefficients(table: &EfficacyTable, epsilon: f32) -> [f32; 4] {
    let last = BIN_CENTRES.len() - 1;
    if epsilon.is_nan() || epsilon <= BIN_CENTRES[0] {
        return table[0];
    }
    if epsilon >= BIN_CENTRES[last] {
        return table[last];
    }
    let j = BIN_CENTRES
        .iter()
        .rposition(|&c| c <= epsilon)
        .unwrap_or(0)
        .min(last - 1);
    let t = (epsilon - BIN_CENTRES[j]) / (BIN_CENTRES[j + 1] - BIN_CENTRES[j]);
    let (a, b) = (table[j], table[j + 1]);
    [0, 1, 2, 3].map(|i| a[i] + t * (b[i] - a[i]))
}

/// The precipitable water used when none is known, cm: 2 cm, Radiance gendaylit's default (and
/// what the dew point of 11 °C that gendaymtx assumes gives).
pub const DEFAULT_PRECIPITABLE_WATER: f32 = 2.0;

/// The precipitable water the efficacies take, cm: [`Efficacy::new`] counts water outside it
/// as its nearer end (10 cm is above any measured column; Perez et al.'s data reached about
/// 5 cm).
pub const PRECIPITABLE_WATER_RANGE_CM: (f32, f32) = (0.0, 10.0);

/// The atmosphere's precipitable water in cm from the surface dew point `dew_point` in °C:
/// W = exp(0.07 T_d − 0.075) (Wright, Perez, Michalsky, *Luminous efficacy of direct
/// irradiance: variations with insolation and moisture conditions*, Solar Energy 42(5), 1989,
/// the relation Perez et al. 1990 use). The dew point is clamped to [−60, 40] °C (NaN: 11 °C).
///
/// ```
/// let w = sky_core::efficacy::precipitable_water(11.0);
/// assert!((w - 2.0).abs() < 0.01);
/// ```
#[must_use]
pub fn precipitable_water(dew_point: f32) -> f32 {
    let t = if dew_point.is_nan() {
        11.0
    } else {
        dew_point.clamp(-60.0, 40.0)
    };
    math::exp_libm(0.07 * t - 0.075)
}

/// The three efficacies of one sky, lm/W.
///
/// ```
/// use sky_core::efficacy::{Efficacy, DEFAULT_PRECIPITABLE_WATER};
/// use sky_core::perez::SkyCondition;
///
/// let clear = SkyCondition::new(8.0, 0.12)?;
/// let k = Efficacy::new(&clear, 30f32.to_radians(), DEFAULT_PRECIPITABLE_WATER);
/// assert!(k.global > 100.0 && k.global < 115.0);   // lm/W
/// assert!(k.diffuse > k.direct);                      // blue sky light, yellower sun
/// # Ok::<(), sky_core::SkyError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Efficacy {
    /// Global horizontal illuminance per global horizontal irradiance, lm/W (eq. 6).
    pub global: f32,
    /// Diffuse horizontal illuminance per diffuse horizontal irradiance, lm/W (eq. 7).
    pub diffuse: f32,
    /// Direct normal illuminance per direct normal irradiance, lm/W, at least 0 (eq. 8).
    pub direct: f32,
}

impl Efficacy {
    /// The efficacies for `condition` (its ε through [`BIN_CENTRES`], module docs), a sun at zenith angle `sun_zenith` (radians) and
    /// precipitable water `water` (cm; NaN or negative counts as 0, more than 10 cm as 10:
    /// [`PRECIPITABLE_WATER_RANGE_CM`]).
    #[must_use]
    pub fn new(condition: &SkyCondition, sun_zenith: f32, water: f32) -> Self {
        let epsilon = condition.epsilon();
        let z = if sun_zenith.is_nan() {
            core::f32::consts::FRAC_PI_2
        } else {
            sun_zenith.clamp(0.0, core::f32::consts::FRAC_PI_2)
        };
        let (dry, wettest) = PRECIPITABLE_WATER_RANGE_CM;
        let w = if water > dry { water.min(wettest) } else { dry };
        let delta = condition.clamped_delta();
        let (cos_z, ln_delta) = (math::cos(z), math::ln(delta));
        let horizontal = |t: &EfficacyTable| {
            let [a, b, c, d] = coefficients(t, epsilon);
            a + b * w + c * cos_z + d * ln_delta
        };
        let [a, b, c, d] = coefficients(&DIRECT, epsilon);
        Self {
            global: horizontal(&GLOBAL),
            diffuse: horizontal(&DIFFUSE),
            direct: (a + b * w + c * math::exp_libm(5.73 * z - 5.0) + d * delta).max(0.0),
        }
    }
}
