//! Neural skies of sky-core: the shipped weights or any weight file.

use sky_core::Vec3;
use sky_core::neural::{NeuralSky, NeuralWeights};

use super::{ModelKind, ParamError, SkyParams, SkySource, param_error};
use crate::dispatch;

/// A [`sky_core::NeuralSky`] as a [`SkySource`].
pub struct Neural {
    sky: NeuralSky<12>,
    label: String,
}

impl Neural {
    /// The neural sky of `weights` for `params`; `kind` names the model in error messages.
    ///
    /// # Errors
    /// A [`ParamError`] when the sun or turbidity lies outside the weights' trained ranges.
    #[allow(clippy::cast_possible_truncation)]
    pub fn new(
        weights: &NeuralWeights<12>,
        kind: ModelKind,
        params: &SkyParams,
    ) -> Result<Self, ParamError> {
        params.check_applies_to(kind)?;
        let sun = params.required_sun(kind)?;
        let turbidity = params.turbidity.unwrap_or(3.0);
        let sky =
            NeuralSky::new(weights, sun, turbidity as f32).map_err(|e| param_error(kind, e))?;
        Ok(Self {
            sky,
            label: format!(
                "{kind} (6-12-3 network trained on {}): sun zenith {:.2} deg, azimuth {:.2} deg, turbidity {}",
                weights.source_name(),
                sun.zenith().to_degrees(),
                sun.azimuth().to_degrees(),
                turbidity
            ),
        })
    }
}

impl SkySource for Neural {
    fn describe(&self) -> String {
        self.label.clone()
    }

    fn shader_params(&self) -> Option<Result<(sky_gpu::Model, Vec<f32>), sky_gpu::UnsupportedSky>> {
        let params = sky_gpu::models::neural::params(&self.sky);
        Some(Ok((sky_gpu::Model::Neural, params)))
    }

    fn rgb_batch(&self, dirs: &[Vec3], out: &mut [Vec3]) {
        dispatch::neural_batch(&self.sky, dirs, out);
    }
}
