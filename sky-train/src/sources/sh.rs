//! The spherical-harmonics lighting of sky-core (`sky_core::sh::ShSky`) as a sky source.

use sky_core::Vec3;
use sky_core::sh::ShSky;

use super::{ModelKind, ParamError, SkyParams, SkySource, param_error, sun};

/// [`ShSky`] as a [`SkySource`]: the radiance of the SH expansion in each direction.
#[derive(Debug, Clone)]
pub struct Sh {
    sky: ShSky,
    params: SkyParams,
}

impl Sh {
    /// The SH lighting of the Preetham sky for `params` (sun, turbidity, bands, filter).
    ///
    /// # Errors
    /// A [`ParamError`] when sky-core rejects a parameter.
    #[allow(clippy::cast_possible_truncation)]
    pub fn new(params: &SkyParams) -> Result<Self, ParamError> {
        let sun = sun(ModelKind::Sh, params)?;
        let t = params.turbidity as f32;
        let sky = if params.ringing_filter {
            ShSky::new(sun, t, params.bands)
        } else {
            ShSky::new_unfiltered(sun, t, params.bands)
        }
        .map_err(|e| param_error(ModelKind::Sh, e))?;
        Ok(Self {
            sky,
            params: *params,
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
        let p = &self.params;
        format!(
            "sh (Preetham, {} bands, {}): sun zenith {:.2} deg, azimuth {:.2} deg, turbidity {}",
            p.bands,
            if p.ringing_filter {
                "ringing filter"
            } else {
                "unfiltered"
            },
            p.sun_zenith_deg,
            p.sun_azimuth_deg,
            p.turbidity
        )
    }

    fn rgb_batch(&self, dirs: &[Vec3], out: &mut [Vec3]) {
        for (o, d) in out.iter_mut().zip(dirs) {
            *o = self.sky.radiance(*d);
        }
    }
}
