//! The Hosek-Wilkie sky (Hosek & Wilkie 2012, RGB version) through the `hw-skymodel` crate,
//! with ground albedo 0.5 in every channel as in seed 000 §IV-A.

use sky_core::{Sun, Vec3, geom};

use super::{ModelKind, ParamError, SkyParams, SkySource, param_error};

/// Ground albedo used for every Hosek-Wilkie sky (seed 000: {0.5, 0.5, 0.5}).
pub(crate) const ALBEDO: f32 = 0.5;

/// A Hosek-Wilkie sky. Radiance is hw-skymodel's RGB output (its own radiometric units);
/// below the horizon it is 0.
pub struct Hosek {
    state: hw_skymodel::rgb::SkyState,
    sun: Sun,
    turbidity: f32,
}

impl Hosek {
    /// The Hosek-Wilkie sky for `params` (turbidity 1-10, sun zenith 0-90°).
    ///
    /// # Errors
    /// A [`ParamError`] naming the argument and its valid range.
    #[allow(clippy::cast_possible_truncation)]
    pub fn new(params: &SkyParams) -> Result<Self, ParamError> {
        let kind = ModelKind::Hosek;
        params.check_applies_to(kind)?;
        let err = |e| param_error(kind, e);
        let sun = params.required_sun(kind)?;
        let turbidity = params.turbidity.unwrap_or(3.0) as f32;
        if !(1.0..=10.0).contains(&turbidity) {
            return Err(err(sky_core::SkyError::OutOfRange {
                parameter: "turbidity",
                value: turbidity,
                min: 1.0,
                max: 10.0,
            }));
        }
        let elevation = core::f32::consts::FRAC_PI_2 - sun.zenith();
        if elevation < 0.0 {
            return Err(err(sky_core::SkyError::SunBelowHorizon {
                zenith: sun.zenith(),
            }));
        }
        let state = hw_skymodel::rgb::SkyState::new(&hw_skymodel::rgb::SkyParams {
            elevation,
            turbidity,
            albedo: [ALBEDO; 3],
        })
        .map_err(|e| ParamError(format!("hw-skymodel: {e}")))?;
        Ok(Self {
            state,
            sun,
            turbidity,
        })
    }

    /// RGB radiance towards `dir` (unit vector); 0 below the horizon (z < −1e-6: as for
    /// sky-core's Preetham sky, the f32 nearest π/2 still counts as the horizon).
    #[must_use]
    pub fn rgb(&self, dir: Vec3) -> Vec3 {
        use hw_skymodel::rgb::Channel;
        if dir.z < -1e-6 {
            return Vec3::ZERO;
        }
        let theta = geom::zenith_azimuth(dir).0;
        let gamma = geom::angle_between(dir, self.sun.direction());
        Vec3::new(
            self.state.radiance(theta, gamma, Channel::R),
            self.state.radiance(theta, gamma, Channel::G),
            self.state.radiance(theta, gamma, Channel::B),
        )
    }
}

impl SkySource for Hosek {
    fn describe(&self) -> String {
        format!(
            "hosek (hw-skymodel, albedo {ALBEDO}): sun zenith {:.2} deg, azimuth {:.2} deg, turbidity {}",
            self.sun.zenith().to_degrees(),
            self.sun.azimuth().to_degrees(),
            self.turbidity
        )
    }

    fn rgb_batch(&self, dirs: &[Vec3], out: &mut [Vec3]) {
        for (o, d) in out.iter_mut().zip(dirs) {
            *o = self.rgb(*d);
        }
    }
}
