//! The Preetham sky of sky-core.

use sky_core::color::Xyy;
use sky_core::{PreethamSky, Sun, Vec3};

use crate::dispatch;

use super::{ModelKind, ParamError, SkyParams, SkySource, not_for, param_error, radians};

/// [`sky_core::PreethamSky`] as a [`SkySource`].
#[derive(Debug, Clone, Copy)]
pub struct Preetham(pub PreethamSky);

impl Preetham {
    /// The Preetham sky for `params` (the sun zenith is required, the azimuth defaults to 0 and
    /// the turbidity to 3; a style is refused).
    ///
    /// # Errors
    /// A [`ParamError`] when a parameter is missing or refused, or sky-core rejects one.
    #[allow(clippy::cast_possible_truncation)]
    pub fn new(params: &SkyParams) -> Result<Self, ParamError> {
        let kind = ModelKind::Preetham;
        if params.style.is_some() {
            return Err(not_for(kind, "--style", "aoas"));
        }
        let Some(zenith) = params.sun_zenith_deg else {
            return Err(ParamError(
                "--sun-zenith <DEG> is required for --model preetham".into(),
            ));
        };
        let err = |e| param_error(kind, e);
        let sun = Sun::new(
            radians(zenith),
            radians(params.sun_azimuth_deg.unwrap_or(0.0)),
        )
        .map_err(err)?;
        PreethamSky::new(sun, params.turbidity.unwrap_or(3.0) as f32)
            .map(Self)
            .map_err(err)
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
