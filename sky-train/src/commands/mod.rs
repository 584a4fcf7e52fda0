//! The subcommands of `sky-train`, one module each: its arguments (a clap `Args` struct) and its
//! `run`. [`crate::cli`] parses the command line and dispatches to them; the argument groups
//! several subcommands share, [`SkyArgs`] and [`ImageArgs`], are here; the value parsers they
//! all use are in [`crate::args`].

pub mod bench;
pub mod captures;
pub mod cct;
pub mod daylight;
pub mod daylight_planes;
pub mod daylight_plot;
pub mod daylight_sky;
pub mod daylight_tables;
pub mod eval;
pub mod export;
pub mod fit_aod;
pub mod fit_sh;
pub mod gallery;
pub mod locus_table;
pub mod render;
pub mod sample;
pub mod schedule;
pub mod showcase;
pub mod site;
pub mod size_study;
pub mod spectrum;
pub mod train;

use std::path::{Path, PathBuf};

use anyhow::Result;
use clap::{Args, ValueEnum};
use sky_core::geom::{Equirect, Extent};
use sky_core::neural::NeuralWeights;

use crate::args::{elevation, finite, latitude, longitude};
use crate::sources::{self, ModelKind, ParamError, SkyParams};

/// The arguments that select one sky.
#[derive(Args, Clone)]
pub struct SkyArgs {
    /// The sky model.
    #[arg(long, value_enum, default_value_t = ModelKind::Preetham)]
    model: ModelKind,
    /// Sun zenith angle in degrees (0 = overhead, 90 = on the horizon). Required for preetham;
    /// for aoas it replaces the style's day cycle.
    #[arg(long, value_name = "DEG", allow_negative_numbers = true)]
    sun_zenith: Option<f64>,
    /// Sun azimuth in degrees, measured from +x towards +y (any finite value; default 0).
    #[arg(long, value_name = "DEG", allow_negative_numbers = true, value_parser = finite)]
    sun_azimuth: Option<f64>,
    /// Atmospheric turbidity (preetham: 2 to 6; hosek: 1 to 10; neural: the trained range;
    /// default 3; not for aoas).
    #[arg(long, value_name = "T", allow_negative_numbers = true)]
    turbidity: Option<f64>,
    /// Weight file of `--model neural` (written by `sky-train train`).
    #[arg(long, value_name = "FILE")]
    weights: Option<PathBuf>,
    /// The style (aoas only): a preset (physical, sunrise, sunset, grey, yellow, blue, coral,
    /// smiley, heart, turbulent, ambiguous) or a style file in TOML. Default: physical.
    #[arg(long, value_name = "PRESET|FILE")]
    style: Option<String>,
    /// Spherical-harmonics bands, 1 to 7 (sh only; default 7).
    #[arg(long, value_name = "N")]
    bands: Option<usize>,
    /// Leave out the ringing filter of seed 001, eq. 5 (sh only).
    #[arg(long)]
    no_ringing_filter: bool,
    /// The sun from a UTC time (RFC 3339, e.g. 2026-06-21T10:00:00Z) and a place (--lat,
    /// --lon, --elevation), instead of --sun-zenith/--sun-azimuth; also dates a perez reading.
    #[arg(long, value_name = "UTC")]
    time: Option<String>,
    /// Latitude in degrees, north positive (-90 to 90), with --time.
    #[arg(long, value_name = "DEG", allow_negative_numbers = true, value_parser = latitude)]
    lat: Option<f64>,
    /// Longitude in degrees, east positive (-180 to 180), with --time.
    #[arg(long, value_name = "DEG", allow_negative_numbers = true, value_parser = longitude)]
    lon: Option<f64>,
    /// Elevation of the place in metres (-500 to 10000; default 0), with --time; for --model
    /// physical also the ground's altitude, the air above it (-500 to 6000).
    #[arg(long, value_name = "M", allow_negative_numbers = true, value_parser = elevation)]
    elevation: Option<f64>,
    /// CIE standard general sky type, 1 (overcast) to 15 (cloudless, turbid) (cie only).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u8).range(1..=15))]
    cie_type: Option<u8>,
    /// Diffuse horizontal illuminance the CIE sky is scaled to, lux, 0 to 1e9 (cie only;
    /// default 10000).
    #[arg(long, value_name = "LUX", value_parser = cie_diffuse_lux)]
    diffuse_lux: Option<f64>,
    /// Zenith luminance the CIE sky is scaled to, cd/m2, 0 to 1e10 (cie only; instead of
    /// --diffuse-lux).
    #[arg(long, value_name = "CD", value_parser = cie_zenith_luminance)]
    zenith_luminance: Option<f64>,
    /// Measured global horizontal irradiance, W/m2 (perez only; split by Erbs et al. 1982
    /// without --dhi).
    #[arg(long, value_name = "W", allow_negative_numbers = true, value_parser = finite)]
    ghi: Option<f64>,
    /// Measured diffuse horizontal irradiance, W/m2 (perez only, with --ghi).
    #[arg(long, value_name = "W", allow_negative_numbers = true, value_parser = finite)]
    dhi: Option<f64>,
    /// Measured global horizontal illuminance, lux (perez only, instead of --ghi).
    #[arg(long, value_name = "LUX", allow_negative_numbers = true, value_parser = finite)]
    global_lux: Option<f64>,
    #[command(flatten)]
    atmosphere: AtmosphereArgs,
}

/// `--diffuse-lux`: 0 to [`sky_core::cie::MAX_DIFFUSE_ILLUMINANCE`] lux.
fn cie_diffuse_lux(s: &str) -> Result<f64, String> {
    let max = f64::from(sky_core::cie::MAX_DIFFUSE_ILLUMINANCE);
    crate::args::in_range(s, 0.0, max, "an illuminance (lux)")
}

/// `--zenith-luminance`: 0 to [`sky_core::cie::MAX_ZENITH_LUMINANCE`] cd/m2.
fn cie_zenith_luminance(s: &str) -> Result<f64, String> {
    let max = f64::from(sky_core::cie::MAX_ZENITH_LUMINANCE);
    crate::args::in_range(s, 0.0, max, "a luminance (cd/m2)")
}

/// The atmosphere of `--model physical`: a preset (docs/daylight.md), each flag in place of
/// one of its values.
#[derive(Args, Clone, Default)]
pub struct AtmosphereArgs {
    /// The atmosphere the other flags change (physical only; default record): record, the
    /// clear-sky record's (AOD fitted to USNO Circular 171, `fit-aod`); clean, today's clean
    /// clear continental sky (OPAC continental average, AOD 0.151).
    #[arg(long, value_enum, value_name = "PRESET")]
    atmosphere: Option<crate::physical::atmosphere::Preset>,
    /// Aerosol optical depth at 550 nm, 0 to 5 (physical; default the preset's; excludes
    /// --turbidity, which maps Preetham's turbidity to it); daylight: 0.05 to 0.8 (default
    /// 0.38, sky-core's tables).
    #[arg(
        long,
        value_name = "TAU",
        allow_negative_numbers = true,
        conflicts_with = "turbidity"
    )]
    aod: Option<f64>,
    /// Angstrom exponent of the aerosol, 0 to 3 (physical only; default 1.3).
    #[arg(long, value_name = "ALPHA", allow_negative_numbers = true)]
    angstrom: Option<f64>,
    /// Aerosol single-scattering albedo, 0 to 1 (physical only; default 0.925).
    #[arg(long, value_name = "W", allow_negative_numbers = true)]
    aerosol_ssa: Option<f64>,
    /// Aerosol Henyey-Greenstein asymmetry, -0.95 to 0.95 (physical only; default 0.703).
    #[arg(long, value_name = "G", allow_negative_numbers = true)]
    aerosol_g: Option<f64>,
    /// Total ozone column in Dobson units, 0 to 1000 (physical only; default 300).
    #[arg(long, value_name = "DU", allow_negative_numbers = true)]
    ozone_du: Option<f64>,
    /// Lambertian ground albedo, 0 to 1 (physical only; default 0.2).
    #[arg(long, value_name = "A", allow_negative_numbers = true)]
    albedo: Option<f64>,
    /// Folder of precomputed atmospheres (physical only; default $SKY_TRAIN_CACHE_DIR, else
    /// $XDG_CACHE_HOME/sky-train, else ~/.cache/sky-train).
    #[arg(long, value_name = "DIR")]
    cache_dir: Option<PathBuf>,
}

impl AtmosphereArgs {
    /// The physical model's options.
    #[must_use]
    pub fn options(&self) -> sources::PhysicalOptions {
        sources::PhysicalOptions {
            preset: self.atmosphere,
            aod: self.aod,
            angstrom: self.angstrom,
            aerosol_ssa: self.aerosol_ssa,
            aerosol_g: self.aerosol_g,
            ozone_du: self.ozone_du,
            albedo: self.albedo,
            site_elevation_m: None,
            base: None,
            cache_dir: self.cache_dir.clone(),
        }
    }
}

/// The site whose month's clear atmosphere (`sky-train site`) `daylight` and `spectrum` use
/// unless `--atmosphere` or a constituent's flag says otherwise.
#[derive(Args, Clone, Default)]
pub struct ClimateArgs {
    /// Latitude of the site, degrees north (-90 to 90; physical only, with --lon and --date):
    /// the atmosphere of the site's month (`sky-train site`) instead of the record preset.
    #[arg(long, value_name = "DEG", allow_negative_numbers = true, value_parser = latitude, requires = "lon")]
    lat: Option<f64>,
    /// Longitude of the site, degrees east (-180 to 180; with --lat).
    #[arg(long, value_name = "DEG", allow_negative_numbers = true, value_parser = longitude, requires = "lat")]
    lon: Option<f64>,
    /// Elevation of the site in metres (-500 to 6000; physical only): the ground's altitude,
    /// the air above it the US Standard Atmosphere's (default: 0, or with --lat/--lon the
    /// 1-degree grid's).
    #[arg(long, value_name = "M", allow_negative_numbers = true)]
    elevation: Option<f64>,
}

impl ClimateArgs {
    /// `options` with this site's month as the atmosphere they change (the month of `date`),
    /// and the elevation given.
    ///
    /// # Errors
    /// A [`ParamError`]: --lat/--lon without --date, a value out of its range.
    pub fn apply(
        &self,
        mut options: sources::PhysicalOptions,
        date: Option<(i32, u32, u32)>,
    ) -> Result<sources::PhysicalOptions, ParamError> {
        options.site_elevation_m = self.elevation;
        if let (Some(lat), Some(lon)) = (self.lat, self.lon) {
            let Some((_, month, _)) = date else {
                return Err(ParamError(
                    "--lat/--lon take the site's month from --date: give --date".into(),
                ));
            };
            options.base =
                Some(crate::site::site_month(lat, lon, self.elevation, month)?.atmosphere());
        }
        Ok(options)
    }

    /// Whether any of the site's flags was given (for refusing them on other models).
    #[must_use]
    pub fn given(&self) -> bool {
        self.lat.is_some() || self.lon.is_some() || self.elevation.is_some()
    }
}

/// Reports on `output` that `path` was written. The work is done by then: a report that
/// cannot be written (stdout closed or full) is said on stderr, unless the reader went away
/// (a closed pipe), and is not an error.
pub(crate) fn report_written(output: &mut dyn std::io::Write, path: &Path) {
    if let Err(e) = writeln!(output, "wrote {}", path.display())
        && e.kind() != std::io::ErrorKind::BrokenPipe
    {
        eprintln!(
            "sky-train: wrote {} (cannot write this to stdout: {e})",
            path.display()
        );
    }
}

/// The 6-12-3 weight file given to `flag`, read and decoded: a file that cannot be read or
/// does not decode is bad input (exit status 2), named by the flag.
fn weight_file(flag: &str, path: &Path) -> Result<NeuralWeights<12>, ParamError> {
    crate::export::read_weights::<12>(path).map_err(|e| ParamError(format!("{flag} {e:#}")))
}

/// A sun's zenith and azimuth in degrees and the day of the year, each when known.
type SunAndDay = (Option<f64>, Option<f64>, Option<u32>);

impl SkyArgs {
    /// The sky these arguments name.
    fn source(&self) -> Result<Box<dyn sources::SkySource>> {
        match (&self.weights, self.model) {
            (Some(path), ModelKind::Neural) => {
                let weights = weight_file("--weights", path)?;
                Ok(Box::new(sources::Neural::new(
                    &weights,
                    ModelKind::Neural,
                    &self.params()?,
                )?))
            }
            (Some(_), model) => Err(ParamError(format!(
                "--weights applies to --model neural only, not --model {model}"
            ))
            .into()),
            (None, model) => Ok(sources::build(model, &self.params()?)?),
        }
    }

    fn params(&self) -> Result<SkyParams, ParamError> {
        let (sun_zenith_deg, sun_azimuth_deg, day_of_year) = self.sun()?;
        Ok(SkyParams {
            sun_zenith_deg,
            sun_azimuth_deg,
            turbidity: self.turbidity,
            style: self.style.clone(),
            bands: self.bands,
            ringing_filter: self.no_ringing_filter.then_some(false),
            cie_type: self.cie_type,
            diffuse_lux: self.diffuse_lux,
            zenith_luminance: self.zenith_luminance,
            ghi: self.ghi,
            dhi: self.dhi,
            global_lux: self.global_lux,
            day_of_year,
            physical: sources::PhysicalOptions {
                site_elevation_m: self.elevation,
                ..self.atmosphere.options()
            },
        })
    }

    /// The sun's zenith and azimuth in degrees (sky-core's azimuth convention) and the day of
    /// the year: from --time and the place, or from --sun-zenith/--sun-azimuth.
    fn sun(&self) -> Result<SunAndDay, ParamError> {
        let err = ParamError;
        let Some(time) = &self.time else {
            if self.lat.is_some() || self.lon.is_some() || self.elevation.is_some() {
                return Err(err("--lat/--lon/--elevation need --time".into()));
            }
            return Ok((self.sun_zenith, self.sun_azimuth, None));
        };
        if self.sun_zenith.is_some() || self.sun_azimuth.is_some() {
            return Err(err(
                "--time and --sun-zenith/--sun-azimuth are alternatives: give one".into(),
            ));
        }
        let (Some(lat), Some(lon)) = (self.lat, self.lon) else {
            return Err(err("--time needs --lat and --lon".into()));
        };
        let site = sky_core::solar::Site::new(lat, lon, self.elevation.unwrap_or(0.0))
            .map_err(|e| err(format!("--lat/--lon/--elevation: {e}")))?;
        let t = crate::captures::manifest::UnixTime::parse(time)
            .map_err(|e| err(format!("--time {e:#}")))?;
        let p = t
            .sun_position(&site)
            .map_err(|e| err(format!("--time {e:#}")))?;
        let (y, m, d, ..) = t.to_civil();
        let day = sky_core::solar::UtcTime::new(y, m, d, 0, 0, 0.0)
            .map_err(|e| err(format!("--time {time}: {e}")))?
            .day_of_year();
        Ok((
            Some(p.zenith_deg()),
            Some(sky_core::solar::compass_to_azimuth(p.azimuth_deg())),
            Some(day),
        ))
    }
}

/// The part of the sphere an image covers.
#[derive(Clone, Copy, ValueEnum)]
pub enum ExtentArg {
    /// The whole sphere: height = width / 2, zenith 0..180 deg (the sky is black below).
    Sphere,
    /// The upper hemisphere: height = width / 4, zenith 0..90 deg.
    Hemisphere,
}

/// The arguments that shape an image.
#[derive(Args)]
pub struct ImageArgs {
    /// Image width in pixels (2 to 16384).
    #[arg(long, value_name = "W", default_value_t = 1024, value_parser = clap::value_parser!(u32).range(2..=16384))]
    width: u32,
    /// Which part of the sphere the image covers.
    #[arg(long, value_enum, default_value_t = ExtentArg::Sphere)]
    extent: ExtentArg,
    /// PNG only: exposure in stops relative to automatic exposure (which maps the mean sky
    /// luminance to middle grey).
    #[arg(long, value_name = "EV", default_value_t = 0.0, allow_negative_numbers = true, value_parser = exposure)]
    exposure: f32,
}

impl ImageArgs {
    fn grid(&self) -> Result<Equirect> {
        let (extent, height) = match self.extent {
            ExtentArg::Sphere => (Extent::Sphere, self.width / 2),
            ExtentArg::Hemisphere => (Extent::UpperHemisphere, (self.width / 4).max(1)),
        };
        Ok(Equirect::new(self.width, height, extent)?)
    }
}

#[allow(clippy::cast_possible_truncation)]
fn exposure(s: &str) -> Result<f32, String> {
    match s.parse::<f64>() {
        Ok(v) if (-30.0..=30.0).contains(&v) => Ok(v as f32),
        _ => Err("expected a number of stops in [-30, 30]".into()),
    }
}
