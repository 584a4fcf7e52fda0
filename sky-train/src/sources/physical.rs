//! The physically based spectral atmosphere ([`crate::physical`]) as a [`SkySource`]:
//! luminance in cd/m² and linear sRGB on the same scale, from its XYZ radiance per direction.

use std::path::PathBuf;
use std::sync::Arc;

use sky_core::Vec3;
use sky_core::color::{self, Xyy};

use crate::physical::atmosphere::Preset;
use crate::physical::{Atmosphere, PhysicalSky, Resolution, cache};

use super::{ModelKind, ParamError, SkyParams, SkySource};

/// The physical model's command-line options (each `None` takes the preset's value, the
/// default preset's without `--atmosphere`).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct PhysicalOptions {
    /// `--atmosphere`: the named atmosphere the other options change.
    pub preset: Option<Preset>,
    /// `--aod`: aerosol optical depth at 550 nm (excludes `--turbidity`).
    pub aod: Option<f64>,
    /// `--angstrom`: Ångström exponent.
    pub angstrom: Option<f64>,
    /// `--aerosol-ssa`: aerosol single-scattering albedo.
    pub aerosol_ssa: Option<f64>,
    /// `--aerosol-g`: Henyey-Greenstein asymmetry.
    pub aerosol_g: Option<f64>,
    /// `--ozone-du`: ozone column, Dobson units.
    pub ozone_du: Option<f64>,
    /// `--albedo`: ground albedo.
    pub albedo: Option<f64>,
    /// `--elevation`: the site's elevation, m (the ground's altitude: the air above it).
    pub site_elevation_m: Option<f64>,
    /// The atmosphere the options change when no `--atmosphere` preset is named: a site's
    /// month ([`crate::site`]); `None` takes the default preset's.
    pub base: Option<Atmosphere>,
    /// `--cache-dir`: where precomputed atmospheres are kept (default [`cache::default_dir`]).
    pub cache_dir: Option<PathBuf>,
}

impl PhysicalOptions {
    /// The first option given, by its flag (for refusing it on other models).
    #[must_use]
    pub fn first_flag(&self) -> Option<&'static str> {
        [
            (self.preset.is_some(), "--atmosphere"),
            (self.aod.is_some(), "--aod"),
            (self.angstrom.is_some(), "--angstrom"),
            (self.aerosol_ssa.is_some(), "--aerosol-ssa"),
            (self.aerosol_g.is_some(), "--aerosol-g"),
            (self.ozone_du.is_some(), "--ozone-du"),
            (self.albedo.is_some(), "--albedo"),
            (self.cache_dir.is_some(), "--cache-dir"),
        ]
        .into_iter()
        .find_map(|(given, flag)| given.then_some(flag))
    }

    /// The atmosphere these options and `turbidity` describe, validated: the preset with each
    /// option given in place of its value (`turbidity` in place of the optical depth).
    ///
    /// # Errors
    /// A [`ParamError`] naming the flag and its valid range; both `--aod` and `--turbidity`.
    pub fn atmosphere(&self, turbidity: Option<f64>) -> Result<Atmosphere, ParamError> {
        let out_of_range = |e: crate::physical::AtmosphereError| ParamError(e.to_string());
        let preset = match (self.preset, self.base) {
            (Some(p), _) => p.atmosphere(),
            (None, Some(site)) => site,
            (None, None) => Preset::default().atmosphere(),
        };
        let base = match (turbidity, self.aod) {
            (Some(_), Some(_)) => {
                return Err(ParamError(
                    "--aod and --turbidity exclude each other (turbidity sets the aerosol optical depth)"
                        .into(),
                ));
            }
            (Some(t), None) => preset.with_turbidity(t).map_err(out_of_range)?,
            (None, aod) => Atmosphere {
                aod_550: aod.unwrap_or(preset.aod_550),
                ..preset
            },
        };
        let atm = Atmosphere {
            angstrom: self.angstrom.unwrap_or(base.angstrom),
            aerosol_ssa: self.aerosol_ssa.unwrap_or(base.aerosol_ssa),
            aerosol_g: self.aerosol_g.unwrap_or(base.aerosol_g),
            ozone_du: self.ozone_du.unwrap_or(base.ozone_du),
            ground_albedo: self.albedo.unwrap_or(base.ground_albedo),
            site_elevation_m: self.site_elevation_m.unwrap_or(base.site_elevation_m),
            ..base
        };
        atm.validate().map_err(out_of_range)?;
        Ok(atm)
    }

    /// The precomputed atmosphere for `turbidity` and these options: from the cache when it
    /// holds it, else computed (a progress bar on stderr) and stored there.
    ///
    /// # Errors
    /// A [`ParamError`] for a bad parameter or a cache directory that cannot be created.
    pub fn load(
        &self,
        turbidity: Option<f64>,
    ) -> Result<Arc<crate::physical::PhysicalAtmosphere>, ParamError> {
        let atm = self.atmosphere(turbidity)?;
        let dir = cache::CacheDir::new(self.cache_dir.as_deref());
        // The folder is checked before the precomputation, only when it must be written.
        cache::load_or_build_in(&atm, &Resolution::default(), Some(&dir), true).map_err(|e| {
            match e.downcast::<ParamError>() {
                Ok(bad) => bad,
                Err(e) => ParamError(format!("{}: {e:#}", dir.shown())),
            }
        })
    }
}

/// [`PhysicalSky`] as a [`SkySource`].
#[derive(Debug, Clone)]
pub struct Physical(pub PhysicalSky);

impl Physical {
    /// The physical sky for `params`: `--sun-zenith` required (0 to 108 deg), azimuth 0 by
    /// default, the atmosphere from `--turbidity` or `--aod` and the other options.
    ///
    /// # Errors
    /// A [`ParamError`] naming the argument and its valid range.
    pub fn new(params: &SkyParams) -> Result<Self, ParamError> {
        let kind = ModelKind::Physical;
        params.check_applies_to(kind)?;
        let Some(zenith) = params.sun_zenith_deg else {
            return Err(ParamError(format!(
                "--sun-zenith <DEG> is required for --model {kind}"
            )));
        };
        let azimuth = params.sun_azimuth_deg.unwrap_or(0.0);
        // The sun first: a bad angle is refused before any precomputation.
        let (lo, hi) = kind.sun_zenith_range_deg();
        if !(lo..=hi).contains(&zenith) {
            return Err(ParamError(format!(
                "--sun-zenith {zenith} deg is outside the valid range [{lo}, {hi}] deg for --model {kind}"
            )));
        }
        let atm = params.physical.load(params.turbidity)?;
        atm.sky(zenith, azimuth)
            .map(Self)
            .map_err(|e| ParamError(e.to_string()))
    }
}

fn xyz(sky: &PhysicalSky, d: Vec3) -> Vec3 {
    let c = sky.radiance_xyzm([f64::from(d.x), f64::from(d.y), f64::from(d.z)]);
    #[allow(clippy::cast_possible_truncation)]
    Vec3::new(c[0] as f32, c[1] as f32, c[2] as f32)
}

impl SkySource for Physical {
    fn describe(&self) -> String {
        let a = &self.0.atmosphere().atmosphere;
        format!(
            "physical: sun zenith {:.2} deg, azimuth {:.2} deg, AOD(550) {:.3}, Angstrom {}, SSA {}, g {}, ozone {} DU, albedo {}, site elevation {} m",
            self.0.sun_zenith_deg(),
            self.0.sun_azimuth_deg(),
            a.aod_550,
            a.angstrom,
            a.aerosol_ssa,
            a.aerosol_g,
            a.ozone_du,
            a.ground_albedo,
            a.site_elevation_m
        )
    }

    fn rgb_batch(&self, dirs: &[Vec3], out: &mut [Vec3]) {
        // Components outside the sRGB gamut (the deep blue of twilight can be) are clipped at 0.
        for (o, d) in out.iter_mut().zip(dirs) {
            *o = color::xyz_to_linear_srgb(xyz(&self.0, *d)).max(Vec3::ZERO);
        }
    }

    fn xyy_batch(&self, dirs: &[Vec3], out: &mut [Xyy]) {
        for (o, d) in out.iter_mut().zip(dirs) {
            *o = color::xyz_to_xyy(xyz(&self.0, *d));
        }
    }
}
