//! The Perez all-weather sky of sky-core, driven by a measurement (`--ghi`, `--dhi`,
//! `--global-lux`).

use sky_core::measurement::Measurement;
use sky_core::{PerezSky, Vec3};

use super::{ModelKind, ParamError, SkyParams, SkySource, param_error, photometric_rgb_batch};

/// The day of the year (for the extraterrestrial irradiance) when the sun is given by angles
/// rather than by `--time`: the March equinox.
pub(super) const DEFAULT_DAY_OF_YEAR: u32 = 80;

/// [`sky_core::PerezSky`] as a [`SkySource`] (D65 chromaticity everywhere).
#[derive(Debug, Clone, Copy)]
pub struct Perez(pub PerezSky);

impl Perez {
    /// The Perez sky for `params`: the sun, and `--ghi` (with `--dhi`, or split by Erbs's
    /// correlation without it) or `--global-lux`.
    ///
    /// # Errors
    /// A [`ParamError`] when a parameter is missing, refused, out of range or a bad reading.
    #[allow(clippy::cast_possible_truncation)]
    pub fn new(params: &SkyParams) -> Result<Self, ParamError> {
        let kind = ModelKind::Perez;
        params.check_applies_to(kind)?;
        let sun = params.required_sun(kind)?;
        let f = |v: f64| v as f32;
        let measurement = match (params.ghi, params.dhi, params.global_lux) {
            (Some(g), Some(d), None) => Measurement::Irradiance {
                global: f(g),
                diffuse: f(d),
            },
            (Some(g), None, None) => Measurement::GlobalIrradiance(f(g)),
            (None, None, Some(lux)) => Measurement::GlobalIlluminance(f(lux)),
            (None, Some(_), _) => {
                return Err(ParamError(
                    "--dhi needs --ghi (the global irradiance)".into(),
                ));
            }
            (Some(_), _, Some(_)) => {
                return Err(ParamError(
                    "--ghi and --global-lux are alternatives: give one".into(),
                ));
            }
            (None, None, None) => {
                return Err(ParamError(
                    "--model perez needs a measurement: --ghi W/m2 [--dhi W/m2] or --global-lux LUX"
                        .into(),
                ));
            }
        };
        let day = params.day_of_year.unwrap_or(DEFAULT_DAY_OF_YEAR);
        // A sun from --time (the day of the year is known only then) is named by --time.
        let error = |e: sky_core::SkyError| match e {
            sky_core::SkyError::SunBelowHorizon { zenith } if params.day_of_year.is_some() => {
                ParamError(format!(
                    "--time: the sun is {:.2} deg below the horizon then (sun zenith {:.2} deg); --model perez takes the sun from the zenith down to the horizon (zenith 0 to 90 deg)",
                    zenith.to_degrees() - 90.0,
                    zenith.to_degrees()
                ))
            }
            other => param_error(kind, other),
        };
        let reading = measurement.read(sun.zenith(), day).map_err(error)?;
        PerezSky::from_reading(sun, &reading)
            .map(Self)
            .map_err(error)
    }
}

impl SkySource for Perez {
    fn describe(&self) -> String {
        let sun = self.0.sun();
        let c = self.0.condition();
        format!(
            "perez: sun zenith {:.2} deg, azimuth {:.2} deg, sky clearness {:.3} (bin {}), brightness {:.3}, diffuse {:.0} lx",
            sun.zenith().to_degrees(),
            sun.azimuth().to_degrees(),
            c.epsilon(),
            c.bin(),
            c.delta(),
            self.0.diffuse_illuminance()
        )
    }

    fn rgb_batch(&self, dirs: &[Vec3], out: &mut [Vec3]) {
        photometric_rgb_batch(&self.0, dirs, out);
    }
}
