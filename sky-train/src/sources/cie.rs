//! The CIE standard general sky of sky-core (ISO 15469:2004 / CIE S 011/E:2003).

use sky_core::{CieSky, Vec3};

use super::{ModelKind, ParamError, SkyParams, SkySource, param_error, photometric_rgb_batch};

/// The diffuse horizontal illuminance a CIE sky is scaled to when neither `--diffuse-lux` nor
/// `--zenith-luminance` is given, lux.
pub(super) const DEFAULT_DIFFUSE_LUX: f64 = 10_000.0;

/// [`sky_core::CieSky`] as a [`SkySource`] (D65 chromaticity everywhere).
#[derive(Debug, Clone, Copy)]
pub struct Cie(pub CieSky);

impl Cie {
    /// The CIE sky for `params`: `--cie-type` (1-15) and the sun are required; the level is
    /// `--zenith-luminance` or `--diffuse-lux` (default 10,000 lx).
    ///
    /// # Errors
    /// A [`ParamError`] when a parameter is missing, refused or out of range.
    #[allow(clippy::cast_possible_truncation)]
    pub fn new(params: &SkyParams) -> Result<Self, ParamError> {
        let kind = ModelKind::Cie;
        params.check_applies_to(kind)?;
        let sun = params.required_sun(kind)?;
        let Some(sky_type) = params.cie_type else {
            return Err(ParamError(
                "--cie-type <1-15> is required for --model cie".into(),
            ));
        };
        let sky = match (params.zenith_luminance, params.diffuse_lux) {
            (Some(_), Some(_)) => {
                return Err(ParamError(
                    "--zenith-luminance and --diffuse-lux are alternatives: give one".into(),
                ));
            }
            (Some(lz), None) => CieSky::new(sky_type, sun, lz as f32),
            (None, e) => CieSky::from_diffuse_illuminance(
                sky_type,
                sun,
                e.unwrap_or(DEFAULT_DIFFUSE_LUX) as f32,
            ),
        };
        sky.map(Self).map_err(|e| param_error(kind, e))
    }
}

impl SkySource for Cie {
    fn describe(&self) -> String {
        let sun = self.0.sun();
        format!(
            "cie type {}: sun zenith {:.2} deg, azimuth {:.2} deg, zenith luminance {:.1} cd/m2",
            self.0.sky_type(),
            sun.zenith().to_degrees(),
            sun.azimuth().to_degrees(),
            sky_core::Photometry::zenith_luminance(&self.0)
        )
    }

    fn rgb_batch(&self, dirs: &[Vec3], out: &mut [Vec3]) {
        photometric_rgb_batch(&self.0, dirs, out);
    }
}
