//! sky-core's clear-sky daylight sky ([`sky_core::daylight::DaylightSky`]): the physical
//! atmosphere's radiance distilled into day, dusk and night networks, the sun from the zenith
//! to 18° below the horizon.

use sky_core::Vec3;
use sky_core::daylight::{DEFAULT_AOD, Daylight as Light, DaylightSky};

use super::{ModelKind, ParamError, SkyParams, SkySource, param_error};
use crate::dispatch;

/// [`DaylightSky`] as a [`SkySource`].
pub struct Daylight {
    sky: DaylightSky,
    label: String,
}

impl Daylight {
    /// The daylight sky for `params`: the sun zenith is required (0 to 180 deg; beyond 108 deg
    /// the sky is the 108 deg one), the azimuth defaults to 0 and `--aod` to sky-core's
    /// default atmosphere's.
    ///
    /// # Errors
    /// A [`ParamError`] when a parameter is missing, refused or out of range.
    #[allow(clippy::cast_possible_truncation)]
    pub fn new(params: &SkyParams) -> Result<Self, ParamError> {
        let kind = ModelKind::Daylight;
        params.check_applies_to(kind)?;
        let sun = params.required_sun(kind)?;
        let aod = params.physical.aod.map_or(DEFAULT_AOD, |a| a as f32);
        let light = Light::new(sun, aod).map_err(|e| param_error(kind, e))?;
        Ok(Self {
            sky: light.sky(),
            label: format!(
                "{kind}: sun zenith {:.2} deg, azimuth {:.2} deg, aerosol optical depth {aod}",
                sun.zenith().to_degrees(),
                sun.azimuth().to_degrees(),
            ),
        })
    }
}

impl SkySource for Daylight {
    fn describe(&self) -> String {
        self.label.clone()
    }

    fn shader_params(&self) -> Option<Result<(sky_gpu::Model, Vec<f32>), sky_gpu::UnsupportedSky>> {
        let params = sky_gpu::models::daylight::params(&self.sky);
        Some(Ok((sky_gpu::Model::Daylight, params)))
    }

    fn rgb_batch(&self, dirs: &[Vec3], out: &mut [Vec3]) {
        dispatch::daylight_batch(&self.sky, dirs, out);
    }
}
