//! One sensor is enough: the split of a global horizontal irradiance into its diffuse and direct
//! (beam) parts. Four published separation models, chosen by [`Decomposition`]:
//!
//! * [`dirint`], the default: Perez et al. 1992's DIRINT, DISC's direct normal irradiance
//!   corrected by bins of the zenith-independent clearness index, the sun's zenith and the
//!   reading's stability against the reading before ([`dirint`]'s module docs); no clear sky;
//!   as published ([`DirintForm::Binned`]) or continuous across its bins
//!   ([`DirintForm::Interpolated`], the controller's);
//! * [`dirindex`]: Perez et al. 2002's DIRINDEX, DIRINT scaled to a given clear sky's beam;
//! * [`engerer2`]: Engerer 2015's Engerer2, with a clear sky's global irradiance;
//! * [`erbs`]: the correlation of Erbs, Klein and Duffie, described here.
//!
//! docs/weather.md compares them against measured diffuse irradiance at four public stations'
//! days, nine months of a fifth and a month of a sixth, which is how the default was chosen.
//!
//! Erbs, Klein and Duffie, *Estimation of the diffuse radiation fraction for hourly, daily and
//! monthly-average global radiation* (Solar Energy 28(4), 1982), eq. 1, the hourly diffuse
//! fraction k_d = I_d / I as a function of the clearness index k_t = I / (I₀ cos Z):
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
//! property this crate can state. On clear days it over-predicts the diffuse by 14–115 % in
//! docs/weather.md's check.

use core::f32::consts::FRAC_PI_2;

use crate::error::{SkyError, check_range};
use crate::math;

mod dirint;
mod dirint_table;

pub use dirint::{
    BEAM_FADE, BIN_CENTRES, ClearSky, DISC_BLEND, DISC_SOLAR_CONSTANT, DirintForm,
    MAX_DISC_AIR_MASS, MAX_STABILITY_GAP_MINUTES, PRESSURE_RANGE, STANDARD_PRESSURE, dirindex,
    dirint, dirint_coefficient, disc, disc_air_mass, kt_prime, pressure_from_elevation,
    stability_index,
};

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
    let (global, z, i0) = checked(global, sun_zenith, extraterrestrial)?;
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

/// The inputs every separation model takes, checked: the global irradiance (W/m², at most
/// [`MAX_CLEARNESS_INDEX`] times the extraterrestrial horizontal), the sun zenith (rad) and the
/// extraterrestrial irradiance (W/m²), returned in that order.
fn checked(
    global: f32,
    sun_zenith: f32,
    extraterrestrial: f32,
) -> Result<(f32, f32, f32), SkyError> {
    let z = check_range("sun zenith [rad]", sun_zenith, 0.0, FRAC_PI_2)?;
    let i0 = check_range(
        "extraterrestrial irradiance [W/m²]",
        extraterrestrial,
        1000.0,
        1500.0,
    )?;
    let global = check_range("global irradiance [W/m²]", global, 0.0, global_limit(z, i0))?;
    Ok((global, z, i0))
}

/// The largest global irradiance taken, W/m²: [`MAX_CLEARNESS_INDEX`] times the
/// extraterrestrial horizontal irradiance, cos Z at least [`MIN_COS_ZENITH`].
fn global_limit(z: f32, i0: f32) -> f32 {
    MAX_CLEARNESS_INDEX * i0 * math::cos(z).max(MIN_COS_ZENITH)
}

/// The coefficients of the Engerer2 separation model (module docs of [`engerer2`]):
/// k_d = C + (1 − C) / (1 + exp(β₀ + β₁ k_t + β₂ AST + β₃ θ_z + β₄ Δk_tc)) + β₅ k_de, with AST
/// the apparent solar time in hours and θ_z the sun zenith angle in degrees.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Engerer2Coefficients {
    /// The lower asymptote C.
    pub c: f32,
    /// β₀ … β₅.
    pub beta: [f32; 6],
}

/// Engerer 2015's Engerer2 coefficients, fitted to 1-minute data of six stations in
/// southeastern Australia (Engerer, *Minute resolution estimates of the diffuse fraction of
/// global irradiance for southeastern Australia*, Solar Energy 116, 2015, 215–237, eq. 33 and
/// its table): C 4.2336e-2, β 3.7912 … 1.7073 as below. The same values are those of the
/// authors' public code (Bright and Engerer, github.com/JamieMBright/Engerer2-separation-model,
/// `Engerer2Separation.R`: C 4.2336e-2, β₀ −3.7912, β₁ 7.547948473, β₂ −1.0035892e-2,
/// β₃ 3.147968e-3, β₄ −5.31460674, β₅ 1.707321551).
pub const ENGERER2_2015: Engerer2Coefficients = Engerer2Coefficients {
    c: 4.2336e-2,
    beta: [-3.7912, 7.5479, -1.0036e-2, 3.1480e-3, -5.3146, 1.7073],
};

/// Bright and Engerer's 2019 world-wide re-fit of Engerer2 for 1-minute data (Bright, J. M.,
/// Engerer, N. A., *Engerer2: Global re-parameterisation, update, and validation of an
/// irradiance separation model at different temporal resolutions*, Journal of Renewable and
/// Sustainable Energy 11, 033701, 2019; 75 stations on all continents, the 1-minute set of their
/// table, as in the authors' code above): a weaker cloud-enhancement term (β₅ 0.44 instead of
/// 1.71), so less sensitive to a clear sky that is too dim for the site.
pub const ENGERER2_2019_1MIN: Engerer2Coefficients = Engerer2Coefficients {
    c: 0.105_62,
    beta: [-4.1332, 8.2578, 0.010_087, 8.8801e-4, -4.9302, 0.443_78],
};

/// The equation of time, hours (apparent minus mean solar time) on day `day_of_year` (1–366,
/// clamped), by Spencer's Fourier series (Spencer, *Fourier series representation of the
/// position of the sun*, Search 2(5), 1971, as given by Iqbal, *An Introduction to Solar
/// Radiation*, 1983, eq. 1.4.1): within about 0.6 minutes of the astronomical value (a change of
/// 0.01 h in AST changes Engerer2's k_d by at most 1e-4).
#[must_use]
pub fn equation_of_time_hours(day_of_year: u32) -> f32 {
    let n = day_of_year.clamp(1, 366);
    #[allow(clippy::cast_precision_loss)] // at most 365
    let b = 2.0 * core::f32::consts::PI * (n - 1) as f32 / 365.0;
    let minutes = 229.18
        * (0.000_075 + 0.001_868 * math::cos(b)
            - 0.032_077 * math::sin(b)
            - 0.014_615 * math::cos(2.0 * b)
            - 0.040_849 * math::sin(2.0 * b));
    minutes / 60.0
}

/// The apparent (true) solar time, hours in [0, 24), at `utc_hours` (hours since 00:00 UTC of
/// day `day_of_year`, any finite value) and longitude `longitude_deg` (degrees east):
/// UTC + longitude / 15 + [`equation_of_time_hours`]. NaN or infinite input gives 12 (noon).
#[must_use]
pub fn apparent_solar_time(utc_hours: f32, longitude_deg: f32, day_of_year: u32) -> f32 {
    let t = utc_hours + longitude_deg / 15.0 + equation_of_time_hours(day_of_year);
    if !t.is_finite() {
        return 12.0;
    }
    let wrapped = t - 24.0 * math::floor(t / 24.0);
    if (0.0..24.0).contains(&wrapped) {
        wrapped
    } else {
        0.0
    }
}

/// The largest |argument| of the logistic's exponential in [`engerer2`] (e^±80 stays finite in
/// f32 and the logistic is 0 or 1 to f32 precision long before).
const MAX_LOGISTIC_ARGUMENT: f32 = 80.0;

/// Engerer2's diffuse fraction k_d, clamped to [0, 1], at clearness index `kt`, clear-sky
/// clearness index `ktc` (the clear sky's global over the extraterrestrial horizontal
/// irradiance), apparent solar time `solar_time` (hours), sun zenith `zenith_deg` (degrees) and
/// cloud-enhancement fraction `kde` = max(0, 1 − clear global / global), by `coefficients`.
/// NaN input gives a value in [0, 1] (the clamp), never a panic.
#[must_use]
pub fn engerer2_diffuse_fraction(
    kt: f32,
    ktc: f32,
    solar_time: f32,
    zenith_deg: f32,
    kde: f32,
    coefficients: &Engerer2Coefficients,
) -> f32 {
    let [b0, b1, b2, b3, b4, b5] = coefficients.beta;
    let c = coefficients.c;
    let x = b0 + b1 * kt + b2 * solar_time + b3 * zenith_deg + b4 * (ktc - kt);
    let x = if x.is_nan() {
        0.0
    } else {
        x.clamp(-MAX_LOGISTIC_ARGUMENT, MAX_LOGISTIC_ARGUMENT)
    };
    let kd = c + (1.0 - c) / (1.0 + math::exp(x)) + b5 * kde;
    if kd.is_nan() { 1.0 } else { kd.clamp(0.0, 1.0) }
}

/// Splits the global horizontal irradiance `global` (W/m²) by the Engerer2 separation model
/// (Engerer 2015, eq. 33):
///
/// k_d = C + (1 − C) / (1 + exp(β₀ + β₁ k_t + β₂ AST + β₃ θ_z + β₄ Δk_tc)) + β₅ k_de,
///
/// k_t the clearness index ([`clearness_index`], capped at 1), k_tc the same of the clear sky's
/// global horizontal irradiance `clear_global` (W/m²), Δk_tc = k_tc − k_t, k_de =
/// max(0, 1 − `clear_global` / `global`) (the part of the diffuse attributed to cloud
/// enhancement), AST `solar_time` the apparent solar time in hours ([`apparent_solar_time`]),
/// θ_z the sun zenith angle in degrees (`sun_zenith` is in radians, [0, π/2]), with
/// `coefficients` ([`ENGERER2_2015`] or [`ENGERER2_2019_1MIN`]); k_d is clamped to [0, 1].
/// Near the horizon the conditioning is that of [`erbs`]: cos Z at least [`MIN_COS_ZENITH`] and
/// no beam above [`MAX_BEAM_ZENITH`].
///
/// The model needs a clear sky: its error on clear days follows that clear sky's (k_de counts
/// every watt above `clear_global` as cloud-enhanced diffuse), so `clear_global` should be the
/// site's (the coefficients were fitted with Engerer's Threlkeld-Jordan clear sky). **Error**:
/// Gueymard and Ruiz-Arias (*Extensive worldwide validation and climate sensitivity analysis of
/// direct irradiance predictions from 1-min global irradiance*, Solar Energy 128, 2016, 1–30;
/// 140 models, 54 stations) are reported to rank Engerer2 among the best separation models at
/// 1-minute resolution. On the measured days of docs/weather.md it over-predicts the clear
/// days' diffuse by +47 % to +107 % with the controller's clear sky of the site's month (+43 %
/// to +88 % with pvlib's Ineichen clear sky), depending on the coefficients, and is within
/// 13.4 % (2015) and 16.6 % (2019) RMS on the overcast day.
///
/// ```
/// use sky_core::decomposition::{engerer2, ENGERER2_2015};
/// // A reading at the clear sky's level, k_t 0.76: k_d 0.16.
/// let clear = engerer2(900.0, 30f32.to_radians(), 1361.0, 900.0, 12.0, &ENGERER2_2015)?;
/// assert!(clear.diffuse < 0.2 * clear.global && clear.direct_normal > 800.0);
/// let dull = engerer2(100.0, 30f32.to_radians(), 1361.0, 820.0, 12.0, &ENGERER2_2015)?;
/// assert!(dull.diffuse > 0.9 * dull.global);
/// # Ok::<(), sky_core::SkyError>(())
/// ```
///
/// # Errors
/// [`SkyError::OutOfRange`] as [`erbs`], and for a `clear_global` that is negative or NaN (one
/// above [`MAX_CLEARNESS_INDEX`] times the extraterrestrial horizontal irradiance is taken as
/// that bound), or a `solar_time` outside [0, 24].
pub fn engerer2(
    global: f32,
    sun_zenith: f32,
    extraterrestrial: f32,
    clear_global: f32,
    solar_time: f32,
    coefficients: &Engerer2Coefficients,
) -> Result<Components, SkyError> {
    let (global, z, i0) = checked(global, sun_zenith, extraterrestrial)?;
    let clear = check_range(
        "clear-sky global irradiance [W/m²]",
        clear_global,
        0.0,
        f32::MAX,
    )?
    .min(global_limit(z, i0));
    let ast = check_range("apparent solar time [h]", solar_time, 0.0, 24.0)?;
    let kt = clearness_index(global, z, i0).min(1.0);
    let ktc = clearness_index(clear, z, i0);
    let kde = if global > clear {
        1.0 - clear / global
    } else {
        0.0
    };
    let (diffuse, direct_normal) = if z > MAX_BEAM_ZENITH {
        (global, 0.0)
    } else {
        let kd = engerer2_diffuse_fraction(kt, ktc, ast, z.to_degrees(), kde, coefficients);
        let diffuse = kd * global;
        (diffuse, ((global - diffuse) / math::cos(z)).max(0.0))
    };
    Ok(Components {
        global,
        diffuse,
        direct_normal,
        clearness_index: kt,
    })
}

/// Which separation model splits a global reading ([`crate::measurement`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Decomposition {
    /// DIRINT (Perez et al. 1992, [`dirint`]), continuous across its bins
    /// ([`DirintForm::Interpolated`]), at the site's pressure, with the stability index of the
    /// reading before where the caller keeps it ([`crate::controller::History`]). The default:
    /// the closest to the measured diffuse on the clear days of docs/weather.md (of the models
    /// through the controller), within the overcast bound on most overcast days, and it needs
    /// no clear sky.
    #[default]
    Dirint,
    /// DIRINDEX (Perez et al. 2002, [`dirindex`]), continuous as [`Decomposition::Dirint`]:
    /// DIRINT scaled to the controller's clear sky's beam; only as good as that clear sky's
    /// direct normal irradiance.
    Dirindex,
    /// Erbs et al. 1982 ([`erbs`]): the clearness index alone.
    Erbs,
    /// Engerer2 ([`engerer2`]) with Engerer's 2015 coefficients ([`ENGERER2_2015`]) and the
    /// controller's clear sky.
    Engerer2,
    /// Engerer2 with Bright and Engerer's 2019 world-wide 1-minute coefficients
    /// ([`ENGERER2_2019_1MIN`]) and the controller's clear sky.
    Engerer2Global,
}

/// A separation model with what it needs besides the reading ([`split`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Separation {
    /// [`erbs`].
    Erbs,
    /// [`engerer2`] with these inputs.
    Engerer2 {
        /// The clear sky's global horizontal irradiance at the same time, W/m².
        clear_global: f32,
        /// The apparent solar time, hours in [0, 24] ([`apparent_solar_time`]).
        solar_time: f32,
        /// The coefficients.
        coefficients: Engerer2Coefficients,
    },
    /// [`dirint`] with these inputs.
    Dirint {
        /// The site's pressure, Pa ([`pressure_from_elevation`]).
        pressure: f32,
        /// The reading's stability index ([`stability_index`]), if known.
        stability: Option<f32>,
        /// As published or continuous ([`DirintForm`]).
        form: DirintForm,
    },
    /// [`dirindex`] with these inputs.
    Dirindex {
        /// The site's pressure, Pa ([`pressure_from_elevation`]).
        pressure: f32,
        /// The reading's stability index ([`stability_index`]), if known.
        stability: Option<f32>,
        /// The clear sky at the reading's time.
        clear: ClearSky,
        /// As published or continuous ([`DirintForm`]).
        form: DirintForm,
    },
}

/// Splits `global` (W/m²) with the sun at `sun_zenith` (radians, [0, π/2]) and extraterrestrial
/// irradiance `extraterrestrial` (W/m²) by `separation`.
///
/// # Errors
/// Those of the model ([`erbs`], [`engerer2`], [`dirint`], [`dirindex`]).
pub fn split(
    separation: &Separation,
    global: f32,
    sun_zenith: f32,
    extraterrestrial: f32,
) -> Result<Components, SkyError> {
    match *separation {
        Separation::Erbs => erbs(global, sun_zenith, extraterrestrial),
        Separation::Engerer2 {
            clear_global,
            solar_time,
            coefficients,
        } => engerer2(
            global,
            sun_zenith,
            extraterrestrial,
            clear_global,
            solar_time,
            &coefficients,
        ),
        Separation::Dirint {
            pressure,
            stability,
            form,
        } => dirint(
            global,
            sun_zenith,
            extraterrestrial,
            pressure,
            stability,
            form,
        ),
        Separation::Dirindex {
            pressure,
            stability,
            clear,
            form,
        } => dirindex(
            global,
            sun_zenith,
            extraterrestrial,
            pressure,
            stability,
            &clear,
            form,
        ),
    }
}
