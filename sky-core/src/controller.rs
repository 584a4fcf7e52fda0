//! One step of a daylight-following luminaire's schedule: from a UTC time and a site to the sun's
//! position, the sky's horizontal illuminance and colour temperature, and the drive levels of an
//! RGBW luminaire that reproduce that colour.
//!
//! Without a measurement the sky is the clear sky of [`clear_sky_illuminance`]. With one (an
//! outdoor lux sensor, a pyranometer, or a pyranometer pair giving the diffuse too; see
//! [`Measurement`], [`crate::measurement`]) the illuminance is the measured global one and its colour is that of daylight
//! under cloud ([`crate::overcast`]), from the clear-sky index (measured over clear-sky global
//! illuminance); the sky type is the Perez sky-clearness bin ([`crate::perez`]), from the diffuse
//! and direct parts of the measurement, split by Erbs's correlation when only the global is known
//! ([`crate::decomposition`]), and W/m² become lux by Perez's global efficacy
//! ([`crate::efficacy`]).
//!
//! The one definition shared by `sky-train schedule` on the host and the controller firmware
//! example (`firmware/src/bin/controller.rs`, checked against this same function run on the
//! host), so that the two cannot drift apart.

use glam::Vec3;

use crate::cct::{self, Cct};
use crate::color::{self, Xyy};
use crate::error::SkyError;
use crate::led::{Channel, Drive, Luminaire};
pub use crate::measurement::Measurement;
use crate::overcast;
use crate::perez::SkyCondition;
use crate::photometry::Photometry;
use crate::solar::{Site, SunPosition, UtcTime};
use crate::twilight::Daylight;

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

/// What a measurement told the controller.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Weather {
    /// The Perez sky-clearness bin, 1 (overcast) to 8 (clear); 0 with the sun below the horizon.
    pub sky_type: u8,
    /// Sky clearness ε and brightness Δ, with the sun above the horizon.
    pub condition: Option<SkyCondition>,
    /// Global horizontal irradiance, W/m² (measured, or the illuminance over Perez's global
    /// efficacy).
    pub global_irradiance: f32,
    /// The clear sky's horizontal illuminance at the same time ([`clear_sky_illuminance`]), XYZ
    /// with Y in lux.
    pub clear_sky: Vec3,
    /// Measured over clear-sky global illuminance.
    pub clear_sky_index: f32,
    /// The overcast fraction of [`crate::overcast`] (0 clear, 1 overcast).
    pub overcast_fraction: f32,
}

/// What the controller computes at one time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Step {
    /// The sun (SPA: geometric and apparent zenith, compass azimuth).
    pub sun: SunPosition,
    /// The sky's illuminance on a horizontal plane, CIE XYZ with Y in lux: the clear sky's
    /// ([`clear_sky_illuminance`]) without a measurement, the measured global illuminance with
    /// the colour of daylight under cloud with one.
    pub illuminance: Vec3,
    /// CCT and Duv of that illuminance's chromaticity.
    pub cct: Cct,
    /// The luminaire's levels reproducing the sky's chromaticity, at a luminous output
    /// proportional to the illuminance: full output (all channels' lumens) at `full_scale_lux`.
    pub drive: Drive<4>,
    /// What the measurement told, when there was one.
    pub weather: Option<Weather>,
}

/// The clear sky's horizontal illuminance for `sun` (XYZ, Y in lux), the one source of the
/// controller's clear-sky level: [`Daylight`], the Preetham sky of `turbidity` (2 to 6) blended
/// into twilight below the horizon. It is the **sky alone**, without the direct sun (sky-core has
/// no direct-sun model yet), so the clear-sky index of a sunny day's global reading lies well
/// above 1; replacing this function by a daylight model with the sun is the one change that
/// makes the index measured over clear-sky *global* illuminance.
///
/// # Errors
/// [`SkyError::OutOfRange`] for a turbidity outside 2-6.
pub fn clear_sky_illuminance(sun: &SunPosition, turbidity: f32) -> Result<Vec3, SkyError> {
    Ok(Daylight::new(sun.sun(), turbidity)?.horizontal_illuminance())
}

/// The controller's step at `time` for `site`: the sky (the clear sky of Preetham `turbidity`,
/// 2 to 6, blended into twilight below the horizon, or what `measurement` says; module docs),
/// its horizontal illuminance and CCT, and `lamp`'s drive levels (levels clip at full output
/// when the sky is brighter than `full_scale_lux`, keeping the chromaticity). A measurement equal
/// to the clear sky's illuminance gives the clear-sky step's illuminance, CCT and levels exactly.
///
/// ```
/// use sky_core::controller::{example_luminaire, step, Measurement};
/// use sky_core::solar::{Site, UtcTime};
///
/// let vienna = Site::new(48.21, 16.37, 190.0)?;
/// let lamp = example_luminaire()?;
/// let time = UtcTime::new(2026, 3, 20, 11, 0, 0.0)?;
/// let noon = step(&time, &vienna, 3.0, 10_000.0, &lamp, None)?;
/// assert!(noon.illuminance.y > 10_000.0);            // diffuse sky light, in lux
/// assert!(noon.cct.kelvin > 5_000.0);                // a blue sky
/// let pwm = noon.drive.quantise(12)?;                // 12-bit duty cycles, R, G, B, W
/// assert!(pwm.iter().any(|&d| d == 4095));           // brighter than full scale: clipped
///
/// let dull = step(&time, &vienna, 3.0, 10_000.0, &lamp, Some(Measurement::GlobalIlluminance(4_000.0)))?;
/// let weather = dull.weather.expect("measured");
/// assert_eq!(dull.illuminance.y, 4_000.0);           // the measured illuminance
/// assert!(weather.clear_sky_index < 0.3 && weather.overcast_fraction == 1.0);
/// assert!(weather.sky_type <= 2);                    // overcast in Perez's bins
/// # Ok::<(), sky_core::SkyError>(())
/// ```
///
/// # Errors
/// [`SkyError::OutOfRange`] for a turbidity outside 2-6, a `full_scale_lux` that is not
/// positive and finite, a bad measurement ([`Measurement`]), or a sky colour without a CCT (not
/// seen for daylight).
#[inline] // with a literal `None`, the measurement path is left out of the binary
pub fn step(
    time: &UtcTime,
    site: &Site,
    turbidity: f32,
    full_scale_lux: f32,
    lamp: &Luminaire<4>,
    measurement: Option<Measurement>,
) -> Result<Step, SkyError> {
    if !(full_scale_lux > 0.0 && full_scale_lux.is_finite()) {
        return Err(SkyError::OutOfRange {
            parameter: "full-scale illuminance [lx]",
            value: full_scale_lux,
            min: f32::MIN_POSITIVE,
            max: f32::MAX,
        });
    }
    let sun = SunPosition::new(time, site)?;
    let clear = clear_sky_illuminance(&sun, turbidity)?;
    let (illuminance, weather) = match measurement {
        None => (clear, None),
        Some(m) => {
            let reading = m.read(sun.sun().zenith(), time.day_of_year())?;
            // The clear sky is positive at every elevation (twilight's night floor included).
            let index = (reading.global_illuminance / clear.y.max(f32::MIN_POSITIVE)).min(f32::MAX);
            let w = overcast::overcast_fraction(index);
            let weather = Weather {
                sky_type: reading.condition.map_or(0, |c| c.bin()),
                condition: reading.condition,
                global_irradiance: reading.global_irradiance,
                clear_sky: clear,
                clear_sky_index: index,
                overcast_fraction: w,
            };
            (
                overcast::daylight_under_cloud(clear, w, reading.global_illuminance),
                Some(weather),
            )
        }
    };
    let colour = color::xyz_to_xyy(illuminance);
    let cct = cct::cct_duv(colour.x, colour.y)?;
    let full_output: f32 = lamp.channels().iter().map(|c| c.full_output).sum();
    let drive = lamp.drive(Xyy {
        luminance: full_output * illuminance.y / full_scale_lux,
        ..colour
    });
    Ok(Step {
        sun,
        illuminance,
        cct,
        drive,
        weather,
    })
}
