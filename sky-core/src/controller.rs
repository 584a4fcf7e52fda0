//! One step of a daylight-following luminaire's schedule: from a UTC time and a site to the sun's
//! position, the daylight's horizontal illuminance, chromaticity and colour temperature (the
//! global light of sun and sky, or the sky alone: [`Light`]), and the drive levels of an RGBW
//! luminaire that reproduce that chromaticity.
//!
//! Without a measurement the light is the clear-sky daylight of [`crate::daylight`]. With one (an
//! outdoor lux sensor, a pyranometer, or a pyranometer pair giving the diffuse too; see
//! [`Measurement`], [`crate::measurement`]) the illuminance is the measured global one and its colour is that of daylight
//! under cloud ([`crate::overcast`]), from the clear-sky index (measured over clear-sky global
//! illuminance); the sky type is the Perez sky-clearness bin ([`crate::perez`]), from the diffuse
//! and direct parts of the measurement, split by a separation model when only the global is known
//! ([`Settings::decomposition`]: Erbs's correlation by default, or Engerer2 with the step's
//! clear sky; [`crate::decomposition`]), and W/m² become lux by Perez's global efficacy
//! ([`crate::efficacy`]).
//!
//! The one definition shared by `sky-train schedule` on the host and the controller firmware
//! example (`firmware/src/bin/controller.rs`, checked against this same function run on the
//! host), so that the two cannot drift apart.

use glam::Vec3;

use crate::cct::Cct;
use crate::color::{self, Xyy};
use crate::daylight::{self, ClearAtmosphere, Daylight};
pub use crate::decomposition::Decomposition;
use crate::decomposition::{self as split, ENGERER2_2015, ENGERER2_2019_1MIN, Separation};
use crate::error::SkyError;
use crate::led::{Channel, Drive, Luminaire};
pub use crate::measurement::Measurement;
use crate::overcast;
use crate::perez::SkyCondition;
use crate::solar::{Site, SunAlgorithm, SunPosition, UtcTime};

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
    /// Diffuse horizontal illuminance, lx: the diffuse irradiance through Perez's diffuse
    /// efficacy.
    pub diffuse_illuminance: f32,
    /// Direct illuminance on the horizontal plane, lx: the direct normal irradiance times
    /// cos Z through Perez's direct efficacy. The three efficacies are separate fits, so the
    /// diffuse and direct illuminances add up to the global only within their errors.
    pub direct_illuminance: f32,
    /// The clear sky's horizontal illuminance at the same time ([`clear_sky_illuminance`]), XYZ
    /// with Y in lux.
    pub clear_sky: Vec3,
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
    /// ([`Decomposition`]); Engerer2's clear sky is this step's ([`clear_sky_irradiance`]).
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
    /// The clear-sky daylight at this time and place (global, diffuse, direct, melanopic EDI).
    pub daylight: Daylight,
    /// The followed light's illuminance on a horizontal plane, CIE XYZ with Y in lux: the
    /// clear sky's global or diffuse light ([`Light`]) without a measurement; with one, the
    /// measured global (or diffuse) illuminance with the colour of that light under cloud.
    pub illuminance: Vec3,
    /// The melanopic EDI of that light, lux (CIE S 026:2018, D65-equivalent): the clear sky's
    /// global or diffuse light's without a measurement; with one, the mixture of
    /// [`overcast::daylight_under_cloud`] taken through melanopic content too: the measured
    /// illuminance times (1 − w) DER_clear + w DER_D65, with w the overcast fraction and
    /// DER_D65 = 1 (S 026 defines melanopic EDI against D65).
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
/// of aerosol optical depth `aod` at sea level with the default ozone ([`Daylight::new`]). The
/// controller's own clear-sky level is at its site: [`Daylight::with_atmosphere`] with
/// [`clear_atmosphere`], whose global illuminance the clear-sky index is measured over.
///
/// # Errors
/// [`SkyError::OutOfRange`] for `aod` outside [[`daylight::MIN_AOD`], [`daylight::MAX_AOD`]].
pub fn clear_sky_illuminance(sun: &SunPosition, aod: f32) -> Result<Vec3, SkyError> {
    Ok(Daylight::new(sun.sun(), aod)?.global())
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

/// The separation of a global reading at `time`, `site`, with the sun at `sun_zenith`
/// (radians) and the clear sky's global illuminance `clear_lux`, by `decomposition`.
fn separation(
    decomposition: Decomposition,
    time: &UtcTime,
    site: &Site,
    sun_zenith: f32,
    clear_lux: f32,
) -> Separation {
    let coefficients = match decomposition {
        Decomposition::Erbs => return Separation::Erbs,
        Decomposition::Engerer2 => ENGERER2_2015,
        Decomposition::Engerer2Global => ENGERER2_2019_1MIN,
    };
    let day = time.day_of_year();
    #[allow(clippy::cast_precision_loss, clippy::cast_possible_truncation)] // hours, degrees
    let utc_hours =
        time.hour() as f32 + time.minute() as f32 / 60.0 + time.second() as f32 / 3600.0;
    #[allow(clippy::cast_possible_truncation)]
    let longitude = site.longitude() as f32;
    Separation::Engerer2 {
        clear_global: clear_sky_irradiance(clear_lux, sun_zenith, day),
        solar_time: split::apparent_solar_time(utc_hours, longitude, day),
        coefficients,
    }
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
    let full_scale_lux = settings.full_scale_lux;
    if !(full_scale_lux > 0.0 && full_scale_lux.is_finite()) {
        return Err(SkyError::OutOfRange {
            parameter: "full-scale illuminance [lx]",
            value: full_scale_lux,
            min: f32::MIN_POSITIVE,
            max: f32::MAX,
        });
    }
    let sun = settings.sun.position(time, site)?;
    let daylight = Daylight::with_atmosphere(sun.sun(), &clear_atmosphere(site, settings))?;
    let clear = daylight.global();
    let (followed, followed_melanopic) = match settings.light {
        Light::Global => (clear, daylight.melanopic_edi()),
        Light::Sky => (daylight.diffuse(), daylight.diffuse_melanopic_edi()),
    };
    let (illuminance, melanopic_edi, weather) = match measurement {
        None => (followed, followed_melanopic, None),
        Some(m) => {
            let zenith = sun.sun().zenith();
            let separation = separation(settings.decomposition, time, site, zenith, clear.y);
            let reading = m.read_with_water(
                zenith,
                time.day_of_year(),
                &separation,
                settings.precipitable_water,
            )?;
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
                diffuse_illuminance: reading.diffuse_illuminance(zenith),
                direct_illuminance: reading.direct_illuminance(zenith),
                clear_sky: clear,
                clear_sky_index: index,
                overcast_fraction: w,
            };
            let measured = match settings.light {
                Light::Global => reading.global_illuminance,
                Light::Sky => reading.diffuse_illuminance(sun.sun().zenith()),
            };
            // Melanopic EDI is linear in the spectrum, so the mixture at equal luminance mixes
            // the efficacy ratios; the overcast end is D65, whose ratio is 1 by definition.
            let clear_part = if followed.y > 0.0 {
                followed_melanopic * (measured / followed.y)
            } else {
                measured
            };
            (
                overcast::daylight_under_cloud(followed, w, measured),
                ((1.0 - w) * clear_part + w * measured).min(f32::MAX),
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
