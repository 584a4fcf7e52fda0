//! Sky models the host can sample, behind one trait.
//!
//! Each source evaluates whole slices of directions at once (the fast path of every model), in
//! sky-core's conventions: +z up, luminance in cd/m², linear sRGB on the same scale.

mod aoas;
mod cie;
mod daylight;
mod hosek;
mod neural;
mod perez;
mod physical;
mod preetham;
mod sh;

use std::fmt;

use sky_core::color::{self, Xyy};
use sky_core::{Photometry, Vec3};

use crate::args::describe;
pub use crate::args::{ParamError, radians};
pub use aoas::Aoas;
pub use cie::Cie;
pub use daylight::Daylight;
pub use hosek::Hosek;
pub use neural::Neural;
pub use perez::Perez;
pub use physical::{Physical, PhysicalOptions};
pub use preetham::Preetham;
pub use sh::Sh;

/// A sky model evaluated over many view directions.
pub trait SkySource: Send + Sync {
    /// A one-line description: the model and its parameters.
    fn describe(&self) -> String;

    /// Linear sRGB for each direction of `dirs`, into the same index of `out`.
    fn rgb_batch(&self, dirs: &[Vec3], out: &mut [Vec3]);

    /// Luminance (cd/m²) and chromaticity for each direction. By default derived from
    /// [`rgb_batch`](Self::rgb_batch); models whose native output is xyY override it.
    fn xyy_batch(&self, dirs: &[Vec3], out: &mut [Xyy]) {
        let mut rgb = vec![Vec3::ZERO; dirs.len().min(out.len())];
        self.rgb_batch(dirs, &mut rgb);
        for (o, c) in out.iter_mut().zip(rgb) {
            *o = color::xyz_to_xyy(color::linear_srgb_to_xyz(c));
        }
    }

    /// The sky's GPU shader model and its parameters packed as that shader reads them
    /// (sky-gpu); `None` for models without a shader.
    fn shader_params(&self) -> Option<Result<(sky_gpu::Model, Vec<f32>), sky_gpu::UnsupportedSky>> {
        None
    }
}

/// The models the command line can name with `--model`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum ModelKind {
    /// The Perez/Preetham analytic sky (sky-core).
    Preetham,
    /// The Hosek-Wilkie sky (hw-skymodel, ground albedo 0.5).
    Hosek,
    /// The neural sky shipped in sky-core, trained on the Preetham sky.
    NeuralPreetham,
    /// The neural sky shipped in sky-core, trained on the Hosek-Wilkie sky.
    NeuralHosek,
    /// A neural sky from a weight file (`--weights FILE`).
    Neural,
    /// The AOAS single-scattering skydome with a style (sky-core, seed 004).
    Aoas,
    /// The spherical-harmonics lighting of the Preetham sky, reconstructed from sky-core's
    /// polynomial tables (seed 001; `--bands`, `--no-ringing-filter`).
    Sh,
    /// A CIE standard general sky, ISO 15469:2004 (sky-core; `--cie-type`, `--diffuse-lux` or
    /// `--zenith-luminance`).
    Cie,
    /// The Perez all-weather sky of a measurement (sky-core; `--ghi`, optionally `--dhi`, or
    /// `--global-lux`).
    Perez,
    /// The physically based spectral atmosphere (sky-train's `physical`: multiple scattering,
    /// ozone, aerosol, the Earth's shadow; sun zenith 0-108 deg; `--aod` or `--turbidity`,
    /// `--ozone-du`, `--albedo`, ...).
    Physical,
    /// sky-core's clear-sky daylight sky, the physical atmosphere distilled into networks (sun
    /// zenith 0-180 deg, below -18 deg elevation the -18 deg sky; `--aod`).
    Daylight,
}

impl ModelKind {
    /// The sun zenith angles the model accepts, in degrees.
    #[must_use]
    pub fn sun_zenith_range_deg(self) -> (f64, f64) {
        match self {
            Self::Preetham
            | Self::Hosek
            | Self::NeuralPreetham
            | Self::NeuralHosek
            | Self::Aoas
            | Self::Sh
            | Self::Cie
            | Self::Perez => (0.0, 90.0),
            Self::Neural | Self::Daylight => (0.0, 180.0),
            Self::Physical => (0.0, crate::physical::sky::MAX_SUN_ZENITH_DEG),
        }
    }

    /// Whether the model has a turbidity (AOAS's atmosphere is set by its style instead).
    #[must_use]
    pub fn uses_turbidity(self) -> bool {
        !matches!(self, Self::Aoas | Self::Cie | Self::Perez | Self::Daylight)
    }

    /// The turbidities the model accepts.
    #[must_use]
    pub fn turbidity_range(self) -> (f64, f64) {
        match self {
            Self::Preetham | Self::NeuralPreetham => (2.0, 6.0),
            // The SH tables are fitted over 2.5..=6 (seed 001 leaves out 2-2.5).
            Self::Sh => (2.5, 6.0),
            Self::Hosek | Self::NeuralHosek => (1.0, 10.0),
            Self::Neural => (0.0, f64::INFINITY),
            Self::Physical => crate::physical::atmosphere::TURBIDITY_RANGE,
            // AOAS has no turbidity (its atmosphere is set by its style), nor have the weather
            // skies (set by their type or measurement) and the daylight sky (`--aod`).
            Self::Aoas | Self::Cie | Self::Perez | Self::Daylight => (0.0, 0.0),
        }
    }
}

impl fmt::Display for ModelKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Self::Preetham => "preetham",
            Self::Hosek => "hosek",
            Self::NeuralPreetham => "neural-preetham",
            Self::NeuralHosek => "neural-hosek",
            Self::Neural => "neural",
            Self::Aoas => "aoas",
            Self::Sh => "sh",
            Self::Cie => "cie",
            Self::Perez => "perez",
            Self::Physical => "physical",
            Self::Daylight => "daylight",
        })
    }
}

/// The parameters that select one sky: the sun, the atmosphere, the style. Which ones a model
/// needs, and which it refuses, is the model's business ([`build`]).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SkyParams {
    /// Sun zenith angle in degrees (required by preetham; for aoas it replaces the style's day
    /// cycle).
    pub sun_zenith_deg: Option<f64>,
    /// Sun azimuth in degrees (sky-core's convention: from +x towards +y); 0 when absent.
    pub sun_azimuth_deg: Option<f64>,
    /// Atmospheric turbidity (preetham only; 3 when absent).
    pub turbidity: Option<f64>,
    /// A style preset name or a style file in TOML (aoas only; `physical` when absent).
    pub style: Option<String>,
    /// Spherical-harmonics bands, 1 to 7 (sh only; 7 when absent).
    pub bands: Option<usize>,
    /// Whether the ringing filter of seed 001 eq. 5 is applied (sh only; on when absent).
    pub ringing_filter: Option<bool>,
    /// The CIE standard general sky type, 1-15 (cie only; required).
    pub cie_type: Option<u8>,
    /// The diffuse horizontal illuminance a CIE sky is scaled to, lux (cie only).
    pub diffuse_lux: Option<f64>,
    /// The zenith luminance a CIE sky is scaled to, cd/m² (cie only).
    pub zenith_luminance: Option<f64>,
    /// Measured global horizontal irradiance, W/m² (perez only).
    pub ghi: Option<f64>,
    /// Measured diffuse horizontal irradiance, W/m² (perez only, with `ghi`).
    pub dhi: Option<f64>,
    /// Measured global horizontal illuminance, lux (perez only).
    pub global_lux: Option<f64>,
    /// The day of the year of the measurement, for the extraterrestrial irradiance (perez).
    pub day_of_year: Option<u32>,
    /// The atmosphere and cache of the physical model (physical only).
    pub physical: PhysicalOptions,
}

impl SkyParams {
    /// A sky given by its sun and turbidity, without a style.
    #[must_use]
    pub fn sun_and_turbidity(sun_zenith_deg: f64, sun_azimuth_deg: f64, turbidity: f64) -> Self {
        Self {
            sun_zenith_deg: Some(sun_zenith_deg),
            sun_azimuth_deg: Some(sun_azimuth_deg),
            turbidity: Some(turbidity),
            ..Self::default()
        }
    }

    /// The sky of `model` for a sun and turbidity; the turbidity is left out for models without
    /// one.
    #[must_use]
    pub fn for_model(
        model: ModelKind,
        sun_zenith_deg: f64,
        sun_azimuth_deg: f64,
        turbidity: f64,
    ) -> Self {
        Self {
            turbidity: model.uses_turbidity().then_some(turbidity),
            ..Self::sun_and_turbidity(sun_zenith_deg, sun_azimuth_deg, turbidity)
        }
    }

    /// The sun of a model that requires `--sun-zenith`.
    pub(crate) fn required_sun(&self, kind: ModelKind) -> Result<sky_core::Sun, ParamError> {
        let Some(zenith) = self.sun_zenith_deg else {
            return Err(ParamError(format!(
                "--sun-zenith <DEG> is required for --model {kind}"
            )));
        };
        sky_core::Sun::new(
            radians(zenith),
            radians(self.sun_azimuth_deg.unwrap_or(0.0)),
        )
        .map_err(|e| param_error(kind, e))
    }
}

/// Builds the sky `kind` for `params`.
///
/// # Errors
/// A [`ParamError`] naming the command-line argument, its value and the valid range.
pub fn build(kind: ModelKind, params: &SkyParams) -> Result<Box<dyn SkySource>, ParamError> {
    match kind {
        ModelKind::Preetham => Ok(Box::new(Preetham::new(params)?)),
        ModelKind::Hosek => Ok(Box::new(Hosek::new(params)?)),
        ModelKind::NeuralPreetham => Ok(Box::new(Neural::new(
            &sky_core::neural::pretrained::PREETHAM,
            kind,
            params,
        )?)),
        ModelKind::NeuralHosek => Ok(Box::new(Neural::new(
            &sky_core::neural::pretrained::HOSEK,
            kind,
            params,
        )?)),
        ModelKind::Neural => Err(ParamError(
            "--model neural needs --weights FILE (a weight file written by `sky-train train`)"
                .into(),
        )),
        ModelKind::Aoas => Ok(Box::new(Aoas::new(params)?)),
        ModelKind::Sh => Ok(Box::new(Sh::new(params)?)),
        ModelKind::Cie => Ok(Box::new(Cie::new(params)?)),
        ModelKind::Perez => Ok(Box::new(Perez::new(params)?)),
        ModelKind::Physical => Ok(Box::new(Physical::new(params)?)),
        ModelKind::Daylight => Ok(Box::new(Daylight::new(params)?)),
    }
}

impl SkyParams {
    /// Refuses the parameters `kind` does not take: `--style` (aoas only), `--turbidity` (every
    /// model but aoas), `--bands` and `--no-ringing-filter` (sh only).
    pub(crate) fn check_applies_to(&self, kind: ModelKind) -> Result<(), ParamError> {
        let refuse = |flag: &str, models: &str| {
            Err(ParamError(format!(
                "{flag} does not apply to --model {kind} (only to --model {models})"
            )))
        };
        if self.style.is_some() && kind != ModelKind::Aoas {
            return refuse("--style", "aoas");
        }
        if self.turbidity.is_some() && !kind.uses_turbidity() {
            return refuse("--turbidity", "preetham, hosek, neural*, sh, physical");
        }
        if self.bands.is_some() && kind != ModelKind::Sh {
            return refuse("--bands", "sh");
        }
        if self.ringing_filter.is_some() && kind != ModelKind::Sh {
            return refuse("--no-ringing-filter", "sh");
        }
        let cie = [
            ("--cie-type", self.cie_type.is_some()),
            ("--diffuse-lux", self.diffuse_lux.is_some()),
            ("--zenith-luminance", self.zenith_luminance.is_some()),
        ];
        if let Some((flag, _)) = cie
            .iter()
            .find(|(_, given)| *given && kind != ModelKind::Cie)
        {
            return refuse(flag, "cie");
        }
        let perez = [
            ("--ghi", self.ghi.is_some()),
            ("--dhi", self.dhi.is_some()),
            ("--global-lux", self.global_lux.is_some()),
        ];
        if let Some((flag, _)) = perez
            .iter()
            .find(|(_, given)| *given && kind != ModelKind::Perez)
        {
            return refuse(flag, "perez");
        }
        // The daylight sky takes the physical atmosphere's optical depth alone.
        let daylight = PhysicalOptions {
            aod: None,
            ..self.physical.clone()
        };
        let (given, models) = match kind {
            ModelKind::Physical => (None, ""),
            ModelKind::Daylight => (daylight.first_flag(), "physical"),
            _ => match self.physical.first_flag() {
                Some("--aod") => (Some("--aod"), "physical, daylight"),
                flag => (flag, "physical"),
            },
        };
        if let Some(flag) = given {
            return refuse(flag, models);
        }
        Ok(())
    }
}

/// Rewrites a sky-core error in the command line's terms (argument names, degrees).
pub(crate) fn param_error(kind: ModelKind, e: sky_core::SkyError) -> ParamError {
    use sky_core::SkyError as E;
    let (lo, hi) = kind.sun_zenith_range_deg();
    let msg = match e {
        // The model's range narrowed by the one the sky refused the sun by (a weight file's
        // own domain for `neural`).
        E::OutOfRange {
            parameter: "sun zenith [rad]",
            value,
            min,
            max,
        } => format!(
            "--sun-zenith {} deg is outside the valid range [{}, {}] deg for --model {kind}",
            value.to_degrees(),
            lo.max(centi_degrees(min)),
            hi.min(centi_degrees(max))
        ),
        E::SunBelowHorizon { zenith: value } => format!(
            "--sun-zenith {} deg is outside the valid range [{lo}, {hi}] deg for --model {kind}",
            value.to_degrees()
        ),
        other => format!(
            "{} for --model {kind}",
            describe(other, |p| flag(p).to_owned(), " ")
        ),
    };
    ParamError(msg)
}

/// An angle in radians in degrees to 0.01 (the f32 radians of 60 deg are 59.999996 deg).
fn centi_degrees(radians: f32) -> f64 {
    (f64::from(radians).to_degrees() * 100.0).round() / 100.0
}

fn flag(parameter: &str) -> &str {
    match parameter {
        "turbidity" => "--turbidity",
        "sun zenith" => "--sun-zenith",
        "sun azimuth" => "--sun-azimuth",
        "SH bands" => "--bands",
        "CIE sky type" => "--cie-type",
        "diffuse illuminance" => "--diffuse-lux",
        "zenith luminance" => "--zenith-luminance",
        "global irradiance" => "--ghi",
        "diffuse irradiance" => "--dhi",
        "global illuminance" => "--global-lux",
        "aerosol optical depth" => "--aod",
        other => other,
    }
}

/// Linear sRGB of a sky-core model with a photometric scale, direction by direction.
fn photometric_rgb_batch<S: Photometry>(sky: &S, dirs: &[Vec3], out: &mut [Vec3]) {
    for (o, d) in out.iter_mut().zip(dirs) {
        *o = color::xyz_to_linear_srgb(sky.xyz(*d));
    }
}
