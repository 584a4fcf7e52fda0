//! The AOAS sky of sky-core (seed 004): O'Neil's single scattering in one skydome, with a
//! style. This is also the source the neural-sky trainer samples for stylised skies.

use sky_core::aoas::{AoasSky, DayCycle};
use sky_core::{SkyError, Sun, Vec3};

use crate::args::{ParamError, describe, radians};
use crate::dispatch;
use crate::style_file;

use super::{ModelKind, SkyParams, SkySource, param_error};

/// [`sky_core::AoasSky`] as a [`SkySource`]: linear RGB in O'Neil's relative units (see
/// [`AoasSky`]), so `sample`'s luminance Y is relative too, not cd/m².
#[derive(Debug, Clone)]
pub struct Aoas {
    /// The sky.
    pub sky: AoasSky,
    /// What `--style` named (a preset or a file), for [`SkySource::describe`].
    pub style_name: String,
}

impl Aoas {
    /// The AOAS sky for `params`: the style `--style` names (default `physical`), with its day
    /// cycle replaced by `--sun-zenith`/`--sun-azimuth` when given. `--turbidity` is refused.
    ///
    /// # Errors
    /// A [`ParamError`] naming the argument (or the style file's key) and its valid range.
    pub fn new(params: &SkyParams) -> Result<Self, ParamError> {
        let kind = ModelKind::Aoas;
        params.check_applies_to(kind)?;
        let style_name = params.style.clone().unwrap_or_else(|| "physical".into());
        let (scattering, mut style) = style_file::load(&style_name)?;
        match (params.sun_zenith_deg, params.sun_azimuth_deg) {
            (Some(zenith), azimuth) => {
                let sun = Sun::new(radians(zenith), radians(azimuth.unwrap_or(0.0)))
                    .map_err(|e| param_error(kind, e))?;
                style.day_cycle = DayCycle::Sun(sun);
            }
            (None, Some(_)) => {
                return Err(ParamError(
                    "--sun-azimuth needs --sun-zenith for --model aoas (without both, the style's day cycle places the sun)".into(),
                ));
            }
            (None, None) => {}
        }
        let sky = AoasSky::new(&scattering, &style).map_err(|e| match e {
            SkyError::SunBelowHorizon { .. } if params.sun_zenith_deg.is_some() => {
                param_error(kind, e)
            }
            other => ParamError(format!(
                "--style {style_name}: {}",
                describe(other, str::to_owned, " = ")
            )),
        })?;
        Ok(Self { sky, style_name })
    }
}

impl SkySource for Aoas {
    fn describe(&self) -> String {
        let sun = self.sky.sun();
        format!(
            "aoas: style {}, sun zenith {:.2} deg, azimuth {:.2} deg, {} samples",
            self.style_name,
            sun.zenith().to_degrees(),
            sun.azimuth().to_degrees(),
            self.sky.scattering().samples
        )
    }

    fn shader_params(&self) -> Option<Result<(sky_gpu::Model, Vec<f32>), sky_gpu::UnsupportedSky>> {
        let params = sky_gpu::models::aoas::params(&self.sky);
        Some(params.map(|p| (sky_gpu::Model::Aoas, p.to_vec())))
    }

    fn rgb_batch(&self, dirs: &[Vec3], out: &mut [Vec3]) {
        dispatch::fastest(
            #[inline(always)]
            || self.sky.rgb_batch(dirs, out),
        );
    }
}
