//! The spherical-harmonics lighting of sky-core (`sky_core::sh::ShSky`) as a sky source.

use sky_core::sh::ShSky;
use sky_core::{Sun, Vec3};

use super::{ModelKind, ParamError, SkyParams, SkySource, param_error};

/// [`ShSky`] as a [`SkySource`]: the radiance of the SH expansion in each direction.
#[derive(Debug, Clone)]
pub struct Sh {
    sky: ShSky,
    sun: Sun,
    turbidity: f32,
    bands: usize,
    ringing_filter: bool,
}

impl Sh {
    /// The SH lighting of the Preetham sky for `params`: the sun zenith is required, the azimuth
    /// defaults to 0, the turbidity to 3, the bands to 7 and the ringing filter to on.
    ///
    /// # Errors
    /// A [`ParamError`] when a parameter is missing or refused, or sky-core rejects one.
    #[allow(clippy::cast_possible_truncation)]
    pub fn new(params: &SkyParams) -> Result<Self, ParamError> {
        let kind = ModelKind::Sh;
        params.check_applies_to(kind)?;
        let sun = params.required_sun(kind)?;
        let turbidity = params.turbidity.unwrap_or(3.0) as f32;
        let bands = params.bands.unwrap_or(7);
        let ringing_filter = params.ringing_filter.unwrap_or(true);
        let sky = if ringing_filter {
            ShSky::new(sun, turbidity, bands)
        } else {
            ShSky::new_unfiltered(sun, turbidity, bands)
        }
        .map_err(|e| param_error(kind, e))?;
        Ok(Self {
            sky,
            sun,
            turbidity,
            bands,
            ringing_filter,
        })
    }

    /// The sky-core SH lighting.
    #[must_use]
    pub fn sky(&self) -> &ShSky {
        &self.sky
    }
}

impl SkySource for Sh {
    fn describe(&self) -> String {
        format!(
            "sh (Preetham, {} bands, {}): sun zenith {:.2} deg, azimuth {:.2} deg, turbidity {}",
            self.bands,
            if self.ringing_filter {
                "ringing filter"
            } else {
                "unfiltered"
            },
            self.sun.zenith().to_degrees(),
            self.sun.azimuth().to_degrees(),
            self.turbidity
        )
    }

    fn shader_params(&self) -> Option<Result<(sky_gpu::Model, Vec<f32>), sky_gpu::UnsupportedSky>> {
        let params = sky_gpu::models::sh::params(&self.sky);
        Some(Ok((sky_gpu::Model::Sh, params.to_vec())))
    }

    fn rgb_batch(&self, dirs: &[Vec3], out: &mut [Vec3]) {
        for (o, d) in out.iter_mut().zip(dirs) {
            *o = self.sky.radiance(*d);
        }
    }
}
