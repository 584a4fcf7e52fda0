//! One step of a daylight-following luminaire's schedule: from a UTC time and a site to the sun's
//! position, the daylight's horizontal illuminance, chromaticity and colour temperature (the
//! global light of sun and sky, or the sky alone: [`Light`]), and the drive levels of an RGBW
//! luminaire that reproduce that chromaticity.
//!
//! Without a measurement the light is the clear-sky daylight of [`crate::daylight`], its sun's
//! beam from the sun's refracted position ([`Daylight::refracted`]). With one (an
//! outdoor lux sensor, a pyranometer, or a pyranometer pair giving the diffuse too; see
//! [`Measurement`], [`crate::measurement`]) the illuminance is the measured global one and its colour is that of daylight
//! under cloud ([`crate::overcast`]), from the clear-sky index (measured over clear-sky global
//! illuminance); the sky type is the Perez sky-clearness bin ([`crate::perez`]), from the diffuse
//! and direct parts of the measurement, split by a separation model when only the global is known
//! ([`Settings::decomposition`]: Perez's DIRINT by default, continuous across its bins
//! ([`crate::decomposition::DirintForm::Interpolated`]: a slowly changing reading gives a slowly
//! changing split, efficacy and colour), with the stability index of the
//! reading before when the caller keeps a [`History`] ([`step_with_history`]); DIRINDEX or
//! Engerer2 with the step's clear sky, or Erbs's correlation; [`crate::decomposition`]), and
//! W/m² become lux by Perez's global efficacy ([`crate::efficacy`]).
//!
//! The one definition shared by `sky-train schedule` on the host and the controller firmware
//! example (`firmware/src/bin/controller.rs`, checked against this same function run on the
//! host), so that the two cannot drift apart.

use glam::Vec3;

use crate::cct::Cct;
use crate::color::{self, Xyy};
use crate::daylight::{self, ClearAtmosphere, Daylight};
pub use crate::decomposition::Decomposition;
use crate::decomposition::{
    self as split, ClearSky, DirintForm, ENGERER2_2015, ENGERER2_2019_1MIN,
    MAX_STABILITY_GAP_MINUTES, Separation,
};
use crate::efficacy::{DEFAULT_PRECIPITABLE_WATER, Efficacy};
use crate::error::SkyError;
use crate::led::{Channel, Drive, Luminaire};
pub use crate::measurement::Measurement;
use crate::overcast;
use crate::perez::SkyCondition;
use crate::self_calibration::{self, Calibrated, Observation, SelfCalibration};
use crate::solar::{self, Site, SunAlgorithm, SunPosition, UtcTime};

/// The example RGBW luminaire: typical LED chromaticities (CIE 1931 x, y) and outputs in lumens
/// at full drive: red 625 nm (0.700, 0.295; 300 lm), green 525 nm (0.170, 0.700; 600 lm), royal
/// blue 450 nm (0.135, 0.060; 100 lm) and a 3000 K white (0.4369, 0.4041; 900 lm).
///
/// # Errors
/// None in practice (the channels are valid); the [`Luminaire::rgbw`] checks are kept.
pub fn example_luminaire() -> Result<Luminaire<4>, SkyError> {
    let ch = |x, y, full_output| Channel { x, y, full_output };
    Luminaire::rgbw(
        ch(0.700, 0.295, 300.0),
        ch(0.170, 0.700, 600.0),
        ch(0.135, 0.060, 100.0),
        ch(0.4369, 0.4041, 900.0),
    )
}

/// What a measurement told the controller: the reading, its split and its light, and how it
/// compares with the clear sky.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Weather {
    /// The Perez sky-clearness bin, 1 (overcast) to 8 (clear); 0 with the sun below the horizon.
    pub sky_type: u8,
    /// Sky clearness ε and brightness Δ, with the sun above the horizon.
    pub condition: Option<SkyCondition>,
    /// Global horizontal irradiance, W/m² (measured, thermal offsets counted as 0; or the
    /// illuminance over Perez's global efficacy).
    pub global_irradiance: f32,
    /// Diffuse horizontal irradiance, W/m²: the measured diffuse where there is one, else
    /// the split of the global by [`Settings::decomposition`] ([`crate::measurement`]).
    pub diffuse_irradiance: f32,
    /// Direct normal irradiance, W/m², of that split (0 with the sun more than 87° from the
    /// zenith).
    pub direct_normal_irradiance: f32,
    /// Global horizontal illuminance, lx: the measured one, or the global irradiance through
    /// Perez's global efficacy.
    pub global_illuminance: f32,
    /// Diffuse horizontal illuminance, lx: the global illuminance's diffuse part, apportioned
    /// by Perez's diffuse and direct efficacies
    /// ([`crate::measurement::Reading::parts_illuminance`]).
    pub diffuse_illuminance: f32,
    /// Direct illuminance on the horizontal plane, lx: the global illuminance's direct part;
    /// with the diffuse it sums to the global.
    pub direct_illuminance: f32,
    /// The clear sky's horizontal illuminance at the same time ([`clear_sky_illuminance`]) times
    /// [`Weather::clear_sky_factor`], XYZ with Y in lux.
    pub clear_sky: Vec3,
    /// The factor the clear sky was scaled by: 1 from [`step`]; from [`step_calibrated`], the
    /// site's clear-sky level learned by [`SelfCalibration`] before this reading.
    pub clear_sky_factor: f32,
    /// The measured global illuminance over the clear sky's ([`Weather::clear_sky`]); `None`
    /// where the clear sky's global illuminance is below [`MIN_CLEAR_SKY_LUX`] (the sun more
    /// than about 3° below the horizon), where a ratio would only measure the sensor's noise
    /// over the twilight (a night reading of 0.3 W/m² gave 1.6e8).
    pub clear_sky_index: Option<f32>,
    /// The overcast fraction of [`crate::overcast`] (0 clear, 1 overcast) of the ratio
    /// (E + L) / (E_clear + L), E the measured and E_clear the clear sky's global illuminance,
    /// L = [`MIN_CLEAR_SKY_LUX`]: the clear-sky index by day (within L / E_clear: under 2.5 % with
    /// the sun above 5°, 1 % above 10°), 1 for a reading equal to the clear sky, and continuous into the
    /// night (where it tends to 1: nothing tells the cloud, the light keeps the clear sky's
    /// colour at the measured level).
    pub overcast_fraction: f32,
}

/// The clear sky's global horizontal illuminance, lx, below which the clear-sky index is not
/// defined ([`Weather::clear_sky_index`]): 100 lx, about 1 W/m², the order of a pyranometer's
/// thermal offset, and reached by the default clear sky with the sun about 3° below the
/// horizon (2.8° at Vienna at the equinox).
pub const MIN_CLEAR_SKY_LUX: f32 = 100.0;

/// Which daylight the luminaire follows.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Light {
    /// Sun and sky on a horizontal plane (the global light): a room lit by a window the sun
    /// shines through, or a luminaire standing in for the outdoors.
    #[default]
    Global,
    /// The sky alone (the diffuse light): a north-facing window or a skylight the sun never
    /// enters.
    Sky,
}

/// The controller's settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settings {
    /// The clear atmosphere's aerosol optical depth at 550 nm ([`daylight::MIN_AOD`] to
    /// [`daylight::MAX_AOD`]; [`daylight::DEFAULT_AOD`] is the clear-sky record's; a site's
    /// month: `sky-train site`).
    pub aerosol_optical_depth: f32,
    /// The clear atmosphere's total ozone column, Dobson units ([`daylight::OZONE_RANGE_DU`];
    /// default [`daylight::OZONE_DU`]; it matters in twilight). The surface pressure comes from
    /// the site's elevation ([`clear_atmosphere`]).
    pub ozone_du: f32,
    /// The site's precipitable water, cm, at which a measured irradiance becomes lux (Perez's
    /// efficacies; default [`crate::efficacy::DEFAULT_PRECIPITABLE_WATER`]): a dry site's clear
    /// light has more lumens per watt.
    pub precipitable_water: f32,
    /// The light followed.
    pub light: Light,
    /// The horizontal illuminance, lux, at which the luminaire gives its full output.
    pub full_scale_lux: f32,
    /// The sun position's algorithm: [`SunAlgorithm::Fast`] (2000-2110) by default,
    /// [`SunAlgorithm::Spa`] for other years or SPA's precision.
    pub sun: SunAlgorithm,
    /// The separation model that splits a global reading without a diffuse one
    /// ([`Decomposition`]); DIRINT's pressure is the site's elevation's
    /// ([`split::pressure_from_elevation`]); the clear sky of DIRINDEX and Engerer2 is this
    /// step's ([`clear_sky_irradiance`], [`clear_sky_direct_normal_irradiance`]).
    pub decomposition: Decomposition,
}

impl Default for Settings {
    /// The default atmosphere, the global light, full output at 10,000 lx, the fast sun, the
    /// default separation model ([`Decomposition::default`]).
    fn default() -> Self {
        Self {
            aerosol_optical_depth: daylight::DEFAULT_AOD,
            ozone_du: daylight::OZONE_DU,
            precipitable_water: crate::efficacy::DEFAULT_PRECIPITABLE_WATER,
            light: Light::Global,
            full_scale_lux: 10_000.0,
            sun: SunAlgorithm::Fast,
            decomposition: Decomposition::default(),
        }
    }
}

/// What the controller computes at one time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Step {
    /// The sun ([`Settings::sun`]'s algorithm: geometric and apparent zenith, compass azimuth).
    pub sun: SunPosition,
    /// The clear-sky daylight at this time and place (global, diffuse, direct, melanopic EDI),
    /// on this day's Earth-Sun distance ([`Daylight::on_day`]).
    pub daylight: Daylight,
    /// The followed light's illuminance on a horizontal plane, CIE XYZ with Y in lux: the
    /// clear sky's global or diffuse light ([`Light`]) without a measurement; with one, the
    /// measured global (or diffuse) illuminance with the colour of that light under cloud.
    pub illuminance: Vec3,
    /// The melanopic EDI of that light, lux (CIE S 026:2018, D65-equivalent): the clear sky's
    /// global or diffuse light's without a measurement; with one, the mixture of
    /// [`overcast::daylight_under_cloud`] taken through melanopic content too (exact for a
    /// mixture at equal luminance: melanopic EDI is linear in the spectrum): the measured
    /// illuminance times (1 − w) DER_clear + w [`overcast::OVERCAST_MELANOPIC_DER`], with w the
    /// overcast fraction.
    pub melanopic_edi: f32,
    /// CCT and Duv of that illuminance's chromaticity; `None` where |Duv| >
    /// [`daylight::MAX_DUV`] (the night-blue sky of nautical twilight).
    pub cct: Option<Cct>,
    /// The luminaire's levels reproducing the light's chromaticity (not its CCT: twilight blue
    /// where the gamut allows), at a luminous output proportional to the illuminance: full
    /// output (all channels' lumens) at `full_scale_lux`.
    pub drive: Drive<4>,
    /// What the measurement told, when there was one.
    pub weather: Option<Weather>,
}

/// The clear sky's global horizontal illuminance for `sun` (XYZ, Y in lux) under an atmosphere
/// of aerosol optical depth `aod` at sea level with the default ozone, the sun's beam refracted
/// ([`Daylight::refracted`]). The controller's own clear-sky level is at its site:
/// [`Daylight::refracted`] with [`clear_atmosphere`], whose global illuminance the clear-sky
/// index is measured over.
///
/// # Errors
/// [`SkyError::OutOfRange`] for `aod` outside [[`daylight::MIN_AOD`], [`daylight::MAX_AOD`]].
pub fn clear_sky_illuminance(sun: &SunPosition, aod: f32) -> Result<Vec3, SkyError> {
    let atmosphere = ClearAtmosphere {
        aerosol_optical_depth: aod,
        ..ClearAtmosphere::default()
    };
    Ok(Daylight::refracted(sun, &atmosphere)?.global())
}

/// The controller's clear atmosphere at `site`: the settings' aerosol optical depth and ozone
/// column, and the site's elevation (its surface pressure).
#[must_use]
pub fn clear_atmosphere(site: &Site, settings: &Settings) -> ClearAtmosphere {
    #[allow(clippy::cast_possible_truncation)] // metres, validated by the daylight tables
    ClearAtmosphere {
        aerosol_optical_depth: settings.aerosol_optical_depth,
        elevation_m: site.elevation() as f32,
        ozone_du: settings.ozone_du,
    }
}

/// The clear sky's global horizontal irradiance, W/m², for a clear-sky global illuminance
/// `clear_lux` (lx, [`clear_sky_illuminance`]) with the sun at zenith `sun_zenith` (radians) on
/// day `day_of_year`: that illuminance read as a lux sensor's reading
/// ([`Measurement::GlobalIlluminance`]: over Perez's global efficacy of the sky condition of its
/// own Erbs split), so that it meets a measured irradiance through the same efficacy as the
/// measured light does. 0 with the sun down or an illuminance the reading refuses.
#[must_use]
pub fn clear_sky_irradiance(clear_lux: f32, sun_zenith: f32, day_of_year: u32) -> f32 {
    if sun_zenith > core::f32::consts::FRAC_PI_2 {
        return 0.0;
    }
    Measurement::GlobalIlluminance(clear_lux)
        .read(sun_zenith, day_of_year)
        .map_or(0.0, |r| r.global_irradiance)
}

/// The clear sky's direct normal irradiance, W/m², for its direct normal illuminance
/// `direct_normal_lux` (lx, [`Daylight::direct_normal`]) and global illuminance `clear_lux`
/// (lx) with the sun at zenith `sun_zenith` (radians) on day `day_of_year`: the illuminance
/// over Perez's direct efficacy of the sky condition that [`clear_sky_irradiance`] finds for
/// `clear_lux`. 0 with the sun down, a zero efficacy or an illuminance the reading refuses.
#[must_use]
pub fn clear_sky_direct_normal_irradiance(
    direct_normal_lux: f32,
    clear_lux: f32,
    sun_zenith: f32,
    day_of_year: u32,
) -> f32 {
    if sun_zenith.is_nan() || sun_zenith > core::f32::consts::FRAC_PI_2 {
        return 0.0;
    }
    let condition = Measurement::GlobalIlluminance(clear_lux)
        .read(sun_zenith, day_of_year)
        .ok()
        .and_then(|r| r.condition);
    let k = condition.map_or(0.0, |c| {
        Efficacy::new(&c, sun_zenith.max(0.0), DEFAULT_PRECIPITABLE_WATER).direct
    });
    if k > 0.0 && direct_normal_lux > 0.0 {
        (direct_normal_lux / k).min(f32::MAX)
    } else {
        0.0
    }
}

/// What DIRINT's stability index needs of the readings before ([`split::stability_index`],
/// Perez et al. 1992, eq. 3): the last reading's zenith-independent clearness index, the clear
/// sky's at the same time (for DIRINDEX), and when it was taken. A luminaire following a
/// sensor keeps one across its steps ([`step_with_history`]); it is 16 bytes and needs no
/// more than RAM (after a restart the first reading has no stability index, as after a gap of
/// more than [`MAX_STABILITY_GAP_MINUTES`]).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct History {
    last: Option<LastReading>,
}

#[derive(Debug, Clone, Copy, PartialEq)]
struct LastReading {
    /// Minutes since 2000-01-01 00:00 UTC.
    minute: f64,
    kt_prime: f32,
    clear_kt_prime: f32,
}

impl History {
    /// No reading before.
    #[must_use]
    pub const fn new() -> Self {
        Self { last: None }
    }

    /// The stability index of a reading at `minute` with k_t' `kt_prime`, and of the clear
    /// sky's `clear_kt_prime`, against the last reading: `None` without one, or when it is not
    /// before `minute` or more than [`MAX_STABILITY_GAP_MINUTES`] before.
    fn stability(
        &self,
        minute: f64,
        kt_prime: f32,
        clear_kt_prime: f32,
    ) -> (Option<f32>, Option<f32>) {
        match self.last {
            Some(l)
                if minute > l.minute
                    && minute - l.minute <= f64::from(MAX_STABILITY_GAP_MINUTES) =>
            {
                (
                    split::stability_index(kt_prime, Some(l.kt_prime), None),
                    split::stability_index(clear_kt_prime, Some(l.clear_kt_prime), None),
                )
            }
            _ => (None, None),
        }
    }
}

/// Minutes since 2000-01-01 00:00 UTC of `time` (proleptic Gregorian days, Hinnant's
/// days-from-civil).
fn minutes_since_2000(time: &UtcTime) -> f64 {
    let (y, m) = (i64::from(time.year()), i64::from(time.month()));
    let y = if m <= 2 { y - 1 } else { y };
    let era = y.div_euclid(400);
    let yoe = y - era * 400;
    let mp = (m + 9) % 12;
    let doy = (153 * mp + 2) / 5 + i64::from(time.day()) - 1;
    let doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
    // 730,425: days from 0000-03-01 to 2000-01-01 in this counting.
    let days = era * 146_097 + doe - 730_425;
    #[allow(clippy::cast_precision_loss)] // days within ±3,000 years: exact in f64
    let day_minutes = days as f64 * 1440.0;
    day_minutes + f64::from(time.hour()) * 60.0 + f64::from(time.minute()) + time.second() / 60.0
}

/// The global irradiance a measurement tells before its split, W/m²: a lux reading through the
/// first-guess efficacy ([`crate::measurement::FIRST_EFFICACY`]); for the stability index only,
/// where a common factor between neighbouring readings cancels.
fn global_irradiance_of(m: &Measurement) -> f32 {
    match *m {
        Measurement::GlobalIrradiance(g) | Measurement::Irradiance { global: g, .. } => g,
        Measurement::GlobalIlluminance(lux) => lux / crate::measurement::FIRST_EFFICACY,
    }
}

/// The separation of a global reading `m` at `time`, `site`, with the sun at `sun_zenith`
/// (radians) and the clear sky `daylight`, by `decomposition`, and the history's entry for
/// this reading (`None` with the sun down).
fn separation(
    decomposition: Decomposition,
    m: &Measurement,
    time: &UtcTime,
    site: &Site,
    sun_zenith: f32,
    daylight: &Daylight,
    history: &History,
) -> (Separation, Option<LastReading>) {
    let day = time.day_of_year();
    let clear_lux = daylight.global().y;
    let up = sun_zenith <= core::f32::consts::FRAC_PI_2;
    #[allow(clippy::cast_possible_truncation)] // metres
    let pressure = split::pressure_from_elevation(site.elevation() as f32);
    let i0 = solar::extraterrestrial_irradiance(day);
    let clear_global = || clear_sky_irradiance(clear_lux, sun_zenith, day);
    // DIRINT's and DIRINDEX's stability index: this reading's k_t' and the clear sky's against
    // the history's (the other models neither use nor keep it).
    let uses_history = matches!(
        decomposition,
        Decomposition::Dirint | Decomposition::Dirindex
    );
    let uses_clear = decomposition == Decomposition::Dirindex;
    let clear = if uses_clear { clear_global() } else { 0.0 };
    let (stability, clear_stability, last) = if uses_history {
        let minute = minutes_since_2000(time);
        let kt_prime = split::kt_prime(global_irradiance_of(m), sun_zenith, i0, pressure);
        let clear_kt_prime = split::kt_prime(clear, sun_zenith, i0, pressure);
        let (stability, clear_stability) = history.stability(minute, kt_prime, clear_kt_prime);
        let last = up.then_some(LastReading {
            minute,
            kt_prime,
            clear_kt_prime,
        });
        (stability, clear_stability, last)
    } else {
        (None, None, None)
    };
    let coefficients = match decomposition {
        Decomposition::Erbs => return (Separation::Erbs, last),
        Decomposition::Dirint => {
            return (
                Separation::Dirint {
                    pressure,
                    stability,
                    form: DirintForm::Interpolated,
                },
                last,
            );
        }
        Decomposition::Dirindex => {
            let direct_normal = clear_sky_direct_normal_irradiance(
                daylight.direct_normal().y,
                clear_lux,
                sun_zenith,
                day,
            );
            return (
                Separation::Dirindex {
                    pressure,
                    stability,
                    clear: ClearSky {
                        global: clear,
                        direct_normal,
                        stability: clear_stability,
                    },
                    form: DirintForm::Interpolated,
                },
                last,
            );
        }
        Decomposition::Engerer2 => ENGERER2_2015,
        Decomposition::Engerer2Global => ENGERER2_2019_1MIN,
    };
    #[allow(clippy::cast_precision_loss, clippy::cast_possible_truncation)] // hours, degrees
    let utc_hours =
        time.hour() as f32 + time.minute() as f32 / 60.0 + time.second() as f32 / 3600.0;
    #[allow(clippy::cast_possible_truncation)]
    let longitude = site.longitude() as f32;
    (
        Separation::Engerer2 {
            clear_global: clear_global(),
            solar_time: split::apparent_solar_time(utc_hours, longitude, day),
            coefficients,
        },
        last,
    )
}

/// The controller's step at `time` for `site`: the clear-sky daylight ([`Daylight`]) or what
/// `measurement` says (module docs), the followed light's ([`Settings::light`]) illuminance and
/// CCT, and `lamp`'s drive levels (levels clip at full output when the light is brighter than
/// `full_scale_lux`, keeping the chromaticity). A measurement equal to the clear sky's global
/// illuminance gives the clear-sky step's global illuminance and levels exactly.
///
/// ```
/// use sky_core::controller::{example_luminaire, step, Light, Measurement, Settings};
/// use sky_core::solar::{Site, UtcTime};
///
/// let vienna = Site::new(48.21, 16.37, 190.0)?;
/// let lamp = example_luminaire()?;
/// let time = UtcTime::new(2026, 3, 20, 11, 0, 0.0)?;
/// let settings = Settings::default();
/// let noon = step(&time, &vienna, &settings, &lamp, None)?;
/// assert!(noon.illuminance.y > 50_000.0);            // sun and sky, in lux
/// assert!(noon.cct.expect("on the locus").kelvin > 4_500.0);
/// let pwm = noon.drive.quantise(12)?;                // 12-bit duty cycles, R, G, B, W
/// assert!(pwm.iter().any(|&d| d == 4095));           // brighter than full scale: clipped
///
/// let north = Settings { light: Light::Sky, ..settings };
/// let window = step(&time, &vienna, &north, &lamp, None)?;
/// assert!(window.illuminance.y < 0.5 * noon.illuminance.y); // the sky alone
///
/// let dull = step(&time, &vienna, &settings, &lamp, Some(Measurement::GlobalIlluminance(4_000.0)))?;
/// let weather = dull.weather.expect("measured");
/// assert_eq!(dull.illuminance.y, 4_000.0);           // the measured illuminance
/// assert!(weather.clear_sky_index.expect("by day") < 0.3 && weather.overcast_fraction == 1.0);
/// assert!(weather.sky_type <= 2);                    // overcast in Perez's bins
/// # Ok::<(), sky_core::SkyError>(())
/// ```
///
/// # Errors
/// [`SkyError::OutOfRange`] for an aerosol optical depth, ozone column or site elevation out of the daylight tables' range ([`daylight::ClearAtmosphere`]), a `full_scale_lux` that
/// is not positive and finite, a year outside the sun algorithm's range ([`SunAlgorithm`]), or
/// a bad measurement ([`Measurement`]).
#[inline] // with a literal `None`, the measurement path is left out of the binary
pub fn step(
    time: &UtcTime,
    site: &Site,
    settings: &Settings,
    lamp: &Luminaire<4>,
    measurement: Option<Measurement>,
) -> Result<Step, SkyError> {
    step_with_history(time, site, settings, lamp, measurement, &mut History::new())
}

/// [`step`] for one reading of a series: `history` holds what DIRINT's stability index needs of
/// the reading before ([`History`]), and is updated with this one (a reading that is refused
/// leaves it as it was; a step with the sun down or without a measurement forgets it). With
/// [`Decomposition::Dirint`] or [`Decomposition::Dirindex`], readings a minute to an hour apart
/// split better this way than one by one (docs/weather.md); the other models do not use it.
///
/// ```
/// use sky_core::controller::{example_luminaire, step_with_history, History, Measurement, Settings};
/// use sky_core::solar::{Site, UtcTime};
///
/// let tucson = Site::new(32.23, -110.96, 786.0)?;
/// let (lamp, settings) = (example_luminaire()?, Settings::default());
/// let mut history = History::new();
/// let mut diffuse = Vec::new();
/// for (minute, ghi) in [(0, 826.0), (1, 826.6)] {
///     let time = UtcTime::new(2018, 10, 18, 19, 24 + minute, 0.0)?;
///     let s = step_with_history(&time, &tucson, &settings, &lamp,
///         Some(Measurement::GlobalIrradiance(ghi)), &mut history)?;
///     diffuse.push(s.weather.expect("measured").diffuse_irradiance);
/// }
/// // A steady clear sky: the second reading is known to be stable, so less of it is diffuse.
/// assert!(diffuse[1] < diffuse[0] && diffuse[1] < 0.12 * 826.6);
/// # Ok::<(), sky_core::SkyError>(())
/// ```
///
/// # Errors
/// Those of [`step`].
#[inline] // as `step`
pub fn step_with_history(
    time: &UtcTime,
    site: &Site,
    settings: &Settings,
    lamp: &Luminaire<4>,
    measurement: Option<Measurement>,
    history: &mut History,
) -> Result<Step, SkyError> {
    let sun = settings.sun.position(time, site)?;
    step_at(time, site, sun, settings, lamp, measurement, 1.0, history)
}

/// [`step_with_history`] for a series of measurements whose clear sky is scaled by the site's
/// clear-sky level that `calibration` has learned ([`crate::self_calibration`]; the factor at
/// the sun's elevation, learned before this reading), the reading then given to
/// `calibration`: the measured global irradiance against the unscaled clear sky's
/// ([`clear_sky_irradiance`]). Returns the step (its [`Weather::clear_sky_factor`] the factor
/// used) and what the calibration made of the reading. Call it at the interval the calibration
/// was made for, in time order; `history` is kept as [`step_with_history`] keeps it.
///
/// ```
/// use sky_core::clear_period::Criteria;
/// use sky_core::controller::{example_luminaire, step_calibrated, History, Measurement, Settings};
/// use sky_core::self_calibration::{Bounds, SelfCalibration, Status};
/// use sky_core::solar::{Site, UtcTime};
///
/// let site = Site::new(48.21, 16.37, 190.0)?;
/// let mut cal = SelfCalibration::new(Criteria::RENO_HANSEN_2016, 60, 16.37, Bounds::DEFAULT)?;
/// let mut history = History::new();
/// let time = UtcTime::new(2026, 6, 21, 10, 0, 0.0)?;
/// let (s, c) = step_calibrated(&time, &site, &Settings::default(), &example_luminaire()?,
///                              Measurement::GlobalIrradiance(820.0), &mut cal, &mut history)?;
/// assert_eq!(s.weather.expect("measured").clear_sky_factor, 1.0); // nothing learned yet
/// assert_eq!(c.status, Status::Learning);
/// # Ok::<(), sky_core::SkyError>(())
/// ```
///
/// # Errors
/// Those of [`step`].
#[inline] // as `step`: a firmware's constant settings (the fast sun) leave SPA out of its flash
pub fn step_calibrated(
    time: &UtcTime,
    site: &Site,
    settings: &Settings,
    lamp: &Luminaire<4>,
    measurement: Measurement,
    calibration: &mut SelfCalibration,
    history: &mut History,
) -> Result<(Step, Calibrated), SkyError> {
    let sun = settings.sun.position(time, site)?;
    #[allow(clippy::cast_possible_truncation)] // degrees
    let elevation = sun.elevation_deg() as f32;
    let factor = calibration.factor(elevation);
    let s = step_at(
        time,
        site,
        sun,
        settings,
        lamp,
        Some(measurement),
        factor,
        history,
    )?;
    let (measured, clear_lux) = s
        .weather
        .map_or((0.0, 0.0), |w| (w.global_irradiance, s.daylight.global().y));
    let clear = clear_sky_irradiance(clear_lux, sun.sun().zenith(), time.day_of_year());
    let c = calibration.update(&Observation {
        seconds: self_calibration::unix_seconds(time),
        sun_elevation_deg: elevation,
        measured,
        clear,
    });
    Ok((s, c))
}

/// The step with the sun found, the clear sky scaled by `clear_scale` where it meets a
/// measurement, and `history` kept ([`step_with_history`]).
#[allow(clippy::too_many_arguments)]
#[inline]
fn step_at(
    time: &UtcTime,
    site: &Site,
    sun: SunPosition,
    settings: &Settings,
    lamp: &Luminaire<4>,
    measurement: Option<Measurement>,
    clear_scale: f32,
    history: &mut History,
) -> Result<Step, SkyError> {
    let full_scale_lux = settings.full_scale_lux;
    if !(full_scale_lux > 0.0 && full_scale_lux.is_finite()) {
        return Err(SkyError::OutOfRange {
            parameter: "full-scale illuminance [lx]",
            value: full_scale_lux,
            min: f32::MIN_POSITIVE,
            max: f32::MAX,
        });
    }
    let daylight =
        Daylight::refracted(&sun, &clear_atmosphere(site, settings))?.on_day(time.day_of_year());
    let clear = daylight.global() * clear_scale;
    let (followed, followed_melanopic) = match settings.light {
        Light::Global => (clear, daylight.melanopic_edi() * clear_scale),
        Light::Sky => (
            daylight.diffuse() * clear_scale,
            daylight.diffuse_melanopic_edi() * clear_scale,
        ),
    };
    let (illuminance, melanopic_edi, weather) = match measurement {
        None => {
            *history = History::new();
            (followed, followed_melanopic, None)
        }
        Some(m) => {
            let zenith = sun.sun().zenith();
            let (separation, last) = separation(
                settings.decomposition,
                &m,
                time,
                site,
                zenith,
                &daylight,
                history,
            );
            let reading = m.read_with_water(
                zenith,
                time.day_of_year(),
                &separation,
                settings.precipitable_water,
            )?;
            history.last = last;
            let (diffuse_lux, direct_lux) = reading.parts_illuminance(zenith);
            let lux = reading.global_illuminance;
            let index = (clear.y >= MIN_CLEAR_SKY_LUX).then(|| (lux / clear.y).min(f32::MAX));
            // The colour's ratio, continuous at night and 1 for a reading equal to the clear sky.
            let colour_index =
                ((lux + MIN_CLEAR_SKY_LUX) / (clear.y + MIN_CLEAR_SKY_LUX)).min(f32::MAX);
            let w = overcast::overcast_fraction(colour_index);
            let weather = Weather {
                sky_type: reading.condition.map_or(0, |c| c.bin()),
                condition: reading.condition,
                global_irradiance: reading.global_irradiance,
                diffuse_irradiance: reading.diffuse_irradiance,
                direct_normal_irradiance: reading.direct_normal_irradiance,
                global_illuminance: reading.global_illuminance,
                diffuse_illuminance: diffuse_lux,
                direct_illuminance: direct_lux,
                clear_sky: clear,
                clear_sky_factor: clear_scale,
                clear_sky_index: index,
                overcast_fraction: w,
            };
            let measured = match settings.light {
                Light::Global => reading.global_illuminance,
                Light::Sky => diffuse_lux,
            };
            // Melanopic EDI is linear in the spectrum, so the mixture at equal luminance mixes
            // the efficacy ratios (a clear light without light counts as the overcast light).
            let overcast_part = overcast::OVERCAST_MELANOPIC_DER * measured;
            let clear_part = if followed.y > 0.0 {
                followed_melanopic * (measured / followed.y)
            } else {
                overcast_part
            };
            (
                overcast::daylight_under_cloud(followed, w, measured),
                ((1.0 - w) * clear_part + w * overcast_part).min(f32::MAX),
                Some(weather),
            )
        }
    };
    let colour = color::xyz_to_xyy(illuminance);
    let full_output: f32 = lamp.channels().iter().map(|c| c.full_output).sum();
    let drive = lamp.drive(Xyy {
        luminance: full_output * illuminance.y / full_scale_lux,
        ..colour
    });
    Ok(Step {
        sun,
        daylight,
        illuminance,
        melanopic_edi,
        cct: daylight::cct_of(illuminance),
        drive,
        weather,
    })
}
