//! The Preetham sky of sky-core.

use sky_core::color::Xyy;
use sky_core::{PreethamSky, Vec3};

use crate::dispatch;

use super::{ModelKind, ParamError, SkyParams, SkySource, param_error, sun};

/// [`sky_core::PreethamSky`] as a [`SkySource`].
#[derive(Debug, Clone, Copy)]
pub struct Preetham(pub PreethamSky);

impl Preetham {
    /// The Preetham sky for `params`.
    ///
    /// # Errors
    /// A [`ParamError`] when sky-core rejects a parameter.
    #[allow(clippy::cast_possible_truncation)]
    pub fn new(params: &SkyParams) -> Result<Self, ParamError> {
        let sun = sun(ModelKind::Preetham, params)?;
        PreethamSky::new(sun, params.turbidity as f32)
            .map(Self)
            .map_err(|e| param_error(ModelKind::Preetham, e))
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
