//! The Preetham sky of sky-core.

use sky_core::color::Xyy;
use sky_core::{PreethamSky, Vec3};

use crate::dispatch;

use super::{ModelKind, ParamError, SkyParams, SkySource, param_error};

/// [`sky_core::PreethamSky`] as a [`SkySource`].
#[derive(Debug, Clone, Copy)]
pub struct Preetham(pub PreethamSky);

impl Preetham {
    /// The Preetham sky for `params` (the sun zenith is required, the azimuth defaults to 0 and
    /// the turbidity to 3; parameters of other models are refused).
    ///
    /// # Errors
    /// A [`ParamError`] when a parameter is missing or refused, or sky-core rejects one.
    #[allow(clippy::cast_possible_truncation)]
    pub fn new(params: &SkyParams) -> Result<Self, ParamError> {
        let kind = ModelKind::Preetham;
        params.check_applies_to(kind)?;
        let sun = params.required_sun(kind)?;
        PreethamSky::new(sun, params.turbidity.unwrap_or(3.0) as f32)
            .map(Self)
            .map_err(|e| param_error(kind, e))
    }
}

impl SkySource for Preetham {
    fn describe(&self) -> String {
        let sun = self.0.sun();
        format!(
            "preetham: sun zenith {:.2} deg, azimuth {:.2} deg, turbidity {}",
            sun.zenith().to_degrees(),
            sun.azimuth().to_degrees(),
            self.0.turbidity()
        )
    }

    fn shader_params(&self) -> Option<Result<(sky_gpu::Model, Vec<f32>), sky_gpu::UnsupportedSky>> {
        let params = sky_gpu::models::preetham::params(&self.0);
        Some(Ok((sky_gpu::Model::Preetham, params.to_vec())))
    }

    fn rgb_batch(&self, dirs: &[Vec3], out: &mut [Vec3]) {
        dispatch::fastest(
            #[inline(always)]
            || self.0.rgb_batch(dirs, out),
        );
    }

    fn xyy_batch(&self, dirs: &[Vec3], out: &mut [Xyy]) {
        dispatch::fastest(
            #[inline(always)]
            || self.0.xyy_batch(dirs, out),
        );
    }
}
