//! The command line: argument parsing and the subcommands, callable in-process (the binary is a
//! thin wrapper; tests drive [`execute`] directly).

use std::io::{BufRead, BufWriter, Write};
use std::path::{Path, PathBuf};

use crate::image_io::{self, Format};
use crate::sources::{self, ModelKind, SkyParams};
use crate::train::{self, TrainConfig};
use crate::{bench, export, render};
use anyhow::{Context, Result, bail};
use clap::{Args, Parser, Subcommand, ValueEnum};
use sky_core::Vec3;
use sky_core::color::{self, Xyy};
use sky_core::geom::{self, Equirect, Extent};

/// The `sky-train` command line.
#[derive(Parser)]
#[command(
    name = "sky-train",
    version,
    about = "Render, sample and benchmark the sky models."
)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Subcommand)]
pub enum Command {
    /// Render an equirectangular image of a sky to OpenEXR (linear float RGB) or PNG (sRGB).
    Render(RenderArgs),
    /// Evaluate a sky at view directions read from stdin (`view_zenith_deg,view_azimuth_deg`
    /// lines; a header line is allowed) and write CSV
    /// `view_zenith_deg,view_azimuth_deg,Y,x,y,R,G,B` to stdout (RGB linear sRGB and Y on the
    /// same scale: cd/m² for preetham, O'Neil's relative units for aoas).
    Sample(SkyArgs),
    /// Print ns/direction of each evaluator over a hemisphere grid, single-threaded, with ratios.
    Bench(BenchArgs),
    /// Render a set of default skies (Preetham: sun positions x turbidities; AOAS: every style
    /// preset) to a folder (the first part of `showcase`).
    Gallery(GalleryArgs),
    /// The main job: the gallery, then a Preetham neural sky trained from scratch and compared
    /// with seed 000's Tables 1-2, weights and images written to the folder.
    Showcase(ShowcaseArgs),
    /// Train a neural sky on a model (seed 000 §III) and write its weight file.
    Train(TrainArgs),
    /// Evaluate a neural sky on seed 000's test protocol: Tables 1 and 2 beside the paper's,
    /// and reference / network / difference images like Figs. 6-7.
    Eval(EvalArgs),
    /// Write the Rust source of a weight file for compile-time embedding in sky-core.
    Export(ExportArgs),
    /// Seed 000's 6-12-3 network against 6-6-3, 6-24-3, 6-48-3 and 6-12-12-3, each trained the
    /// same way: mean NRMSE and irradiance on the paper's protocol, bytes, ns/direction (a
    /// Markdown table on stdout).
    SizeStudy(SizeStudyArgs),
    /// Fuzz sky-core's weight-file decoder with mutated files for a bounded time.
    FuzzWeights(FuzzArgs),
    /// Fit a model's spherical-harmonics coefficients as polynomials in sun zenith and
    /// turbidity (seed 001) and write them as a Rust table for sky-core.
    FitSh(FitShArgs),
    /// A lighting controller's day: every --step minutes of a UTC date, the sun's position
    /// (NREL SPA), the clear sky's CCT, Duv and horizontal illuminance, and the levels of an
    /// example RGBW luminaire, as CSV on stdout.
    ///
    /// Columns: utc (RFC 3339); sun_zenith_deg: the topocentric GEOMETRIC zenith angle (no
    /// refraction; the sky models use it); sun_azimuth_deg: from north, clockwise, east = 90;
    /// sun_elevation_deg = 90 - zenith; apparent_zenith_deg: refraction-corrected for 1013.25 hPa
    /// and 15 C; cct_k and duv (CIE 1960 uv distance from the Planckian locus, positive above
    /// it as in ANSI C78.377) of the horizontal illuminance; horizontal_lux: from the sky
    /// alone (no direct sun, no ground), Preetham's model by day and a fitted twilight decay
    /// below the horizon; red, green, blue, white: levels in [0, 1] of an RGBW luminaire (red
    /// 300 lm at x,y 0.700,0.295; green 600 lm at 0.170,0.700; blue 100 lm at 0.135,0.060;
    /// white 900 lm at 0.4369,0.4041) reproducing that colour, at full output at
    /// --full-scale-lux.
    Schedule(ScheduleArgs),
    /// Captured skies (seed 000 §III-D, §IV-A, §IV-B): train a neural sky on a sequence of
    /// HDR environment maps, fill the gaps between them, synthesize test sequences.
    Captures {
        /// What to do with captures.
        #[command(subcommand)]
        command: crate::captures::command::CapturesCommand,
    },
    /// Read CIE 1931 `x,y` lines on stdin (a header line is allowed) and write
    /// `x,y,cct_k,duv`: correlated colour temperature (1000-100000 K) and Duv (positive above
    /// the Planckian locus, ANSI C78.377).
    Cct,
}

/// `schedule`'s arguments.
#[derive(Args)]
pub struct ScheduleArgs {
    /// Latitude in degrees, north positive (-90 to 90).
    #[arg(long, value_name = "DEG", allow_negative_numbers = true, value_parser = latitude)]
    pub lat: f64,
    /// Longitude in degrees, east positive (-180 to 180).
    #[arg(long, value_name = "DEG", allow_negative_numbers = true, value_parser = longitude)]
    pub lon: f64,
    /// The UTC date, YYYY-MM-DD (years 1 to 2999).
    #[arg(long, value_name = "YYYY-MM-DD", value_parser = date)]
    pub date: (i32, u32, u32),
    /// Minutes between rows, from 00:00 UTC (1 to 1440).
    #[arg(long, value_name = "MIN", default_value_t = 10, value_parser = clap::value_parser!(u32).range(1..=1440))]
    pub step: u32,
    /// Elevation of the site in metres above sea level (-500 to 10000).
    #[arg(long, value_name = "M", default_value_t = 0.0, allow_negative_numbers = true, value_parser = elevation)]
    pub elevation: f64,
    /// Atmospheric turbidity of the clear sky (2 to 6).
    #[arg(long, value_name = "T", default_value_t = 3.0, value_parser = schedule_turbidity)]
    pub turbidity: f32,
    /// Horizontal illuminance in lux at which the luminaire gives its full output (1 to 200000).
    #[arg(long, value_name = "LUX", default_value_t = 10_000.0, value_parser = full_scale_lux)]
    pub full_scale_lux: f32,
}

fn in_range(s: &str, min: f64, max: f64, what: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(v) if (min..=max).contains(&v) => Ok(v),
        _ => Err(format!("expected {what} in [{min}, {max}]")),
    }
}

fn latitude(s: &str) -> Result<f64, String> {
    in_range(s, -90.0, 90.0, "a latitude in degrees")
}

fn longitude(s: &str) -> Result<f64, String> {
    in_range(s, -180.0, 180.0, "a longitude in degrees")
}

fn elevation(s: &str) -> Result<f64, String> {
    in_range(s, -500.0, 10_000.0, "an elevation in metres")
}

#[allow(clippy::cast_possible_truncation)]
fn schedule_turbidity(s: &str) -> Result<f32, String> {
    in_range(s, 2.0, 6.0, "a turbidity").map(|v| v as f32)
}

#[allow(clippy::cast_possible_truncation)]
fn full_scale_lux(s: &str) -> Result<f32, String> {
    in_range(s, 1.0, 200_000.0, "an illuminance in lux").map(|v| v as f32)
}

fn date(s: &str) -> Result<(i32, u32, u32), String> {
    crate::controller::parse_date(s).map_err(|e| e.0)
}

/// `size-study`'s arguments.
#[derive(Args)]
pub struct SizeStudyArgs {
    /// The sky model to learn (preetham or hosek).
    #[arg(long, default_value = "preetham")]
    pub model: ModelKind,
    /// Training wall-time budget per network, seconds (1 to 86400).
    #[arg(long, default_value_t = 300.0, value_parser = seconds)]
    pub seconds: f64,
    /// Random seed (initial weights, view jitter).
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Hidden layouts to train, e.g. `6 12 24 48 12,12` (each one of those).
    #[arg(long, num_args = 1.., value_delimiter = ' ', default_values = ["6", "12", "24", "48", "12,12"])]
    pub layouts: Vec<String>,
    /// LM weight of each sky's irradiance residual (0 to 100; 0 = NRMSE only), as for `train`.
    #[arg(long, default_value_t = 1.0, value_parser = irradiance_weight)]
    pub irradiance_weight: f64,
}

/// `fuzz-weights`' arguments.
#[derive(Args)]
pub struct FuzzArgs {
    /// How long to fuzz, in seconds (1 to 86400).
    #[arg(long, default_value_t = 10.0, value_parser = seconds)]
    pub seconds: f64,
    /// Random seed of the mutations.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
}

/// `eval`'s arguments.
#[derive(Args)]
pub struct EvalArgs {
    /// The network: a shipped one, or `neural` with `--weights`.
    #[arg(long, value_enum, default_value_t = ModelKind::NeuralPreetham)]
    pub model: ModelKind,
    /// Weight file of `--model neural`.
    #[arg(long, value_name = "FILE")]
    pub weights: Option<PathBuf>,
    /// Folder for the comparison images (created if missing).
    #[arg(long, value_name = "DIR", default_value = "out")]
    pub out: PathBuf,
}

/// `export`'s arguments.
#[derive(Args)]
pub struct ExportArgs {
    /// The weight file.
    #[arg(long, value_name = "FILE")]
    pub weights: PathBuf,
    /// The constant's name (e.g. PREETHAM).
    #[arg(long)]
    pub name: String,
    /// The Rust file to write (atomically).
    #[arg(long, value_name = "FILE")]
    pub out: PathBuf,
    /// What to write: the f32 weights (`NeuralWeights`, for `NeuralSky`) or the weights
    /// quantised to Q7.24 (`FixedNeuralWeights`, for `FixedNeuralSky` on parts without an FPU).
    #[arg(long, value_enum, default_value_t = ExportFormat::F32)]
    pub format: ExportFormat,
}

/// `export --format`.
#[derive(Clone, Copy, ValueEnum)]
pub enum ExportFormat {
    /// `NeuralWeights<12>` in f32.
    F32,
    /// `FixedNeuralWeights<12>` in Q7.24.
    Fixed,
}

/// `train`'s arguments.
#[derive(Args)]
pub struct TrainArgs {
    /// The sky model to learn.
    #[arg(long, value_enum, default_value_t = ModelKind::Preetham)]
    pub model: ModelKind,
    /// Hidden layer sizes, comma-separated (1 to 255 each; `12` is the paper's network).
    #[arg(long, value_delimiter = ',', default_value = "12", value_parser = clap::value_parser!(u16).range(1..=255))]
    pub hidden: Vec<u16>,
    /// The optimiser.
    #[arg(long, value_enum, default_value_t = train::Optimizer::Lm)]
    pub optimizer: train::Optimizer,
    /// Random seed.
    #[arg(long, default_value_t = 1)]
    pub seed: u32,
    /// Wall-time budget in seconds (1 to 86400).
    #[arg(long, default_value_t = 60.0, value_parser = seconds)]
    pub max_seconds: f64,
    /// Iteration budget (LM steps or backprop epochs, 1 to 1000000).
    #[arg(long, default_value_t = 400, value_parser = clap::value_parser!(u32).range(1..=1_000_000))]
    pub max_iterations: u32,
    /// Stop once the validation NRMSE reaches this (0 = train to the budget or convergence).
    #[arg(long, default_value_t = 0.0)]
    pub target_nrmse: f64,
    /// Checkpoint file: resumed from when it exists, rewritten after every iteration.
    #[arg(long, value_name = "FILE")]
    pub checkpoint: Option<PathBuf>,
    /// Start from a 6-12-3 weight file (its network and its input/output scaling) instead of
    /// random weights: continues an earlier training on new samples or budgets.
    #[arg(long, value_name = "FILE")]
    pub init_weights: Option<PathBuf>,
    /// Weight file to write (single hidden layer only). Written atomically.
    #[arg(long, value_name = "FILE")]
    pub out: Option<PathBuf>,
    /// Training turbidities, comma-separated (default: the model's range in steps of 1, as in
    /// seed 000 §III-D).
    #[arg(long, value_delimiter = ',', value_name = "T,T,...")]
    pub turbidities: Option<Vec<f64>>,
    /// Training sun zeniths, uniform over [0, 90] deg inclusive (2 to 1000).
    #[arg(long, default_value_t = 20, value_parser = clap::value_parser!(u16).range(2..=1000))]
    pub sun_zeniths: u16,
    /// LM weight of each sky's irradiance residual (0 to 100; 0 = NRMSE only).
    #[arg(long, default_value_t = 1.0, value_parser = irradiance_weight)]
    pub irradiance_weight: f64,
    /// View strata per training sky: zenith x azimuth (each 1 to 1000).
    #[arg(long, default_value = "10x20", value_parser = strata)]
    pub views: (usize, usize),
}

fn irradiance_weight(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(v) if (0.0..=100.0).contains(&v) => Ok(v),
        _ => Err("expected a weight in [0, 100]".into()),
    }
}

fn strata(s: &str) -> Result<(usize, usize), String> {
    let parse = |v: &str| {
        v.trim()
            .parse::<usize>()
            .ok()
            .filter(|n| (1..=1000).contains(n))
    };
    match s.split_once('x').map(|(a, b)| (parse(a), parse(b))) {
        Some((Some(a), Some(b))) => Ok((a, b)),
        _ => Err("expected ZxA with each in [1, 1000], e.g. 10x20".into()),
    }
}

fn seconds(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(v) if (1.0..=86400.0).contains(&v) => Ok(v),
        _ => Err("expected seconds in [1, 86400]".into()),
    }
}

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
}

impl SkyArgs {
    /// The sky these arguments name.
    fn source(&self) -> Result<Box<dyn sources::SkySource>> {
        match (&self.weights, self.model) {
            (Some(path), ModelKind::Neural) => {
                let weights = export::read_weights::<12>(path)
                    .map_err(|e| sources::ParamError(format!("--weights {e:#}")))?;
                Ok(Box::new(sources::Neural::new(
                    &weights,
                    ModelKind::Neural,
                    &self.params(),
                )?))
            }
            (Some(_), model) => Err(sources::ParamError(format!(
                "--weights applies to --model neural only, not --model {model}"
            ))
            .into()),
            (None, model) => Ok(sources::build(model, &self.params())?),
        }
    }

    fn params(&self) -> SkyParams {
        SkyParams {
            sun_zenith_deg: self.sun_zenith,
            sun_azimuth_deg: self.sun_azimuth,
            turbidity: self.turbidity,
            style: self.style.clone(),
            bands: self.bands,
            ringing_filter: self.no_ringing_filter.then_some(false),
        }
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

/// `render`'s arguments.
#[derive(Args)]
pub struct RenderArgs {
    #[command(flatten)]
    sky: SkyArgs,
    #[command(flatten)]
    image: ImageArgs,
    /// Output file: .exr (linear float RGB) or .png (sRGB). Written atomically.
    #[arg(long, value_name = "FILE")]
    out: PathBuf,
}

/// `bench`'s arguments.
#[derive(Args)]
pub struct BenchArgs {
    /// Grid width (directions per row).
    #[arg(long, default_value_t = 1024, value_parser = clap::value_parser!(u32).range(1..=16384))]
    width: u32,
    /// Grid height (rows over the upper hemisphere).
    #[arg(long, default_value_t = 512, value_parser = clap::value_parser!(u32).range(1..=16384))]
    height: u32,
    /// Timed runs per evaluator (the median is reported).
    #[arg(long, default_value_t = 15, value_parser = clap::value_parser!(u32).range(1..=1000))]
    runs: u32,
}

/// `gallery`'s arguments.
#[derive(Args)]
pub struct GalleryArgs {
    /// Output folder (created if missing).
    #[arg(long, value_name = "DIR", default_value = "out")]
    out: PathBuf,
    /// Image width in pixels (2 to 16384).
    #[arg(long, value_name = "W", default_value_t = 512, value_parser = clap::value_parser!(u32).range(2..=16384))]
    width: u32,
}

/// `showcase`'s arguments.
#[derive(Args)]
pub struct ShowcaseArgs {
    /// Output folder (created if missing).
    #[arg(long, value_name = "DIR", default_value = "out")]
    out: PathBuf,
    /// Training budget in wall seconds (1 to 86400).
    #[arg(long, default_value_t = 60.0, value_parser = seconds)]
    seconds: f64,
}

/// `fit-sh`'s arguments.
#[derive(Args)]
pub struct FitShArgs {
    /// The sky model to fit (any model; it is treated as a black box).
    #[arg(long, value_enum, default_value_t = ModelKind::Preetham)]
    model: ModelKind,
    /// Polynomial degree in sun zenith of bands 0-4 (0 to 30; the paper: 13).
    #[arg(long, value_name = "D", default_value_t = 18)]
    degree_theta: usize,
    /// Polynomial degree in turbidity of bands 0-4 (0 to 30; the paper: 7).
    #[arg(long, value_name = "D", default_value_t = 13)]
    degree_turbidity: usize,
    /// Polynomial degree in sun zenith of bands 5-6 (0 to 30; the paper: 13).
    #[arg(long, value_name = "D", default_value_t = 12)]
    degree_theta_high: usize,
    /// Polynomial degree in turbidity of bands 5-6 (0 to 30; the paper: 7).
    #[arg(long, value_name = "D", default_value_t = 6)]
    degree_turbidity_high: usize,
    /// Chebyshev sample points in sun zenith (more than the degrees).
    #[arg(long, value_name = "N", default_value_t = 38)]
    nodes_theta: usize,
    /// Chebyshev sample points in turbidity (more than the degrees).
    #[arg(long, value_name = "N", default_value_t = 28)]
    nodes_turbidity: usize,
    /// Smallest turbidity fitted (the paper's 2.5; the fit worsens fast below).
    #[arg(long, value_name = "T", default_value_t = 2.5)]
    turbidity_min: f32,
    /// Largest turbidity fitted.
    #[arg(long, value_name = "T", default_value_t = 6.0)]
    turbidity_max: f32,
    /// The generated Rust file (written atomically); default `out/sh/<model>_table.rs`.
    #[arg(long, value_name = "FILE")]
    out: Option<PathBuf>,
    /// Also measure the errors (eqs. 2-3) off the fit grid and write the table, the chart and
    /// the worst-case renders into this folder.
    #[arg(long, value_name = "DIR")]
    report: Option<PathBuf>,
}

fn fit_sh(args: &FitShArgs, output: &mut dyn Write) -> Result<()> {
    use crate::sh::{Degrees, FitConfig, ShFit, export, report};
    if args.model == ModelKind::Sh {
        bail!("--model sh is the fitted representation itself; fit the model it approximates");
    }
    let config = FitConfig {
        low: Degrees {
            theta: args.degree_theta,
            tau: args.degree_turbidity,
        },
        high: Degrees {
            theta: args.degree_theta_high,
            tau: args.degree_turbidity_high,
        },
        nodes_theta: args.nodes_theta,
        nodes_tau: args.nodes_turbidity,
        turbidity: [args.turbidity_min, args.turbidity_max],
        ..FitConfig::shipped(args.model)
    };
    let start = std::time::Instant::now();
    let fit = ShFit::run(&config)?;
    let out = args.out.clone().unwrap_or_else(|| {
        PathBuf::from("out/sh").join(format!(
            "{}_table.rs",
            args.model.to_string().replace('-', "_")
        ))
    });
    if let Some(dir) = out.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    }
    image_io::write_text(&out, &export::rust_source(&fit))?;
    writeln!(
        output,
        "fit-sh {}: {} skies projected (at most {} x {} quadrature nodes), symmetry residual {:.1e}, \
         condition number {:.4} (raw monomials {:.2e}), {:.1} s",
        args.model,
        fit.samples,
        fit.max_rows,
        2 * fit.max_rows,
        fit.asymmetry,
        fit.condition,
        fit.condition_monomial,
        start.elapsed().as_secs_f64()
    )?;
    writeln!(output, "  wrote {}", out.display())?;
    if let Some(dir) = &args.report {
        // The paper's uniform degrees, for comparison.
        let paper = ShFit::run(&FitConfig {
            turbidity: config.turbidity,
            ..FitConfig::paper(args.model)
        })?;
        let (errors, paper_errors, paths) = report::write(&fit, Some(&paper), dir)?;
        writeln!(
            output,
            "errors (eqs. 2-3) over {} skies off the fit grid:",
            errors.skies
        )?;
        write!(output, "{}", report::markdown(&fit, &errors))?;
        if let Some(p) = paper_errors {
            writeln!(output, "with the paper's degrees (13, 7) for every band:")?;
            write!(output, "{}", report::markdown(&paper, &p))?;
        }
        for p in paths {
            writeln!(output, "  wrote {}", p.display())?;
        }
    }
    Ok(())
}

fn finite(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        _ => Err("expected a finite number".into()),
    }
}

#[allow(clippy::cast_possible_truncation)]
fn exposure(s: &str) -> Result<f32, String> {
    match s.parse::<f64>() {
        Ok(v) if (-30.0..=30.0).contains(&v) => Ok(v as f32),
        _ => Err("expected a number of stops in [-30, 30]".into()),
    }
}

/// Runs `command`, reading `sample`'s input from `input` and writing its CSV to `output`.
///
/// # Errors
/// Bad parameters as a [`sources::ParamError`] (exit status 2), anything else as a plain error.
pub fn execute(command: Command, input: &mut dyn BufRead, output: &mut dyn Write) -> Result<()> {
    match command {
        Command::Render(args) => {
            let source = args.sky.source()?;
            let path = render_to(&*source, &args.image, &args.out)?;
            eprintln!("{}: {}", source.describe(), path.display());
            Ok(())
        }
        Command::Sample(args) => sample(&args, input, output),
        Command::Bench(args) => {
            let dirs = bench::hemisphere_directions(args.width, args.height);
            let results = bench::run(&dirs, args.runs as usize)?;
            write!(
                output,
                "{}",
                bench::report(&results, args.width, args.height)
            )?;
            let sh = bench::sh_reconstruction(args.runs as usize)?;
            write!(output, "{}", bench::sh_report(&sh))?;
            let cct = bench::cct(args.runs as usize)?;
            write!(output, "{}", bench::cct_report(&cct))?;
            Ok(())
        }
        Command::Gallery(args) => gallery(&args, output),
        Command::Showcase(args) => showcase(&args, output),
        Command::Train(args) => train_command(&args, output),
        Command::Eval(args) => eval_command(&args, output),
        Command::SizeStudy(args) => {
            if !matches!(args.model, ModelKind::Preetham | ModelKind::Hosek) {
                bail!(
                    "--model {}: the size study trains on preetham or hosek",
                    args.model
                );
            }
            let layouts = args
                .layouts
                .iter()
                .map(|l| {
                    l.split(',')
                        .map(|h| h.trim().parse::<usize>())
                        .collect::<Result<Vec<_>, _>>()
                        .map_err(|_| {
                            anyhow::anyhow!("--layouts `{l}`: expected sizes like 12 or 12,12")
                        })
                })
                .collect::<Result<Vec<_>>>()?;
            let rows = crate::study::run(
                args.model,
                &layouts,
                args.seconds,
                args.seed,
                args.irradiance_weight,
                true,
            )?;
            write!(output, "{}", crate::study::table(args.model, &rows))?;
            Ok(())
        }
        Command::FuzzWeights(args) => {
            let stats = crate::fuzz::fuzz_weights(
                std::time::Duration::from_secs_f64(args.seconds),
                args.seed,
            )?;
            writeln!(
                output,
                "fuzz-weights: {} inputs, {} accepted, no panic, every accepted file round-trips",
                stats.inputs, stats.accepted
            )?;
            Ok(())
        }
        Command::Schedule(args) => {
            let config = crate::controller::ScheduleConfig {
                latitude: args.lat,
                longitude: args.lon,
                elevation: args.elevation,
                date: args.date,
                step_minutes: args.step,
                turbidity: args.turbidity,
                full_scale_lux: args.full_scale_lux,
            };
            let mut out = BufWriter::new(output);
            crate::controller::schedule(&config, &mut out)?;
            out.flush()?;
            Ok(())
        }
        Command::Cct => {
            let mut out = BufWriter::new(output);
            crate::controller::cct_lines(input, &mut out)?;
            out.flush()?;
            Ok(())
        }
        Command::Export(args) => {
            let weights = export::read_weights::<12>(&args.weights)?;
            let text = match args.format {
                ExportFormat::F32 => export::pretrained_source(&weights, &args.name, &args.weights),
                ExportFormat::Fixed => {
                    export::pretrained_fixed_source(&weights, &args.name, &args.weights)?
                }
            };
            image_io::write_text(&args.out, &text)?;
            writeln!(output, "wrote {}", args.out.display())?;
            Ok(())
        }
        Command::FitSh(args) => fit_sh(&args, output),
        Command::Captures { command } => crate::captures::command::execute(&command, output),
    }
}

fn render_to(source: &dyn sources::SkySource, image: &ImageArgs, out: &Path) -> Result<PathBuf> {
    let format = Format::from_path(out)?;
    let grid = image.grid()?;
    let img = render::equirect(source, &grid);
    match format {
        Format::Exr => image_io::write_exr(out, &img)?,
        Format::Png => {
            let scale = render::auto_exposure(&img, &grid) * image.exposure.exp2();
            image_io::write_png(out, &img, scale)?;
        }
    }
    Ok(out.to_path_buf())
}

/// The non-blank lines of `input` as (1-based line number, first field, second field), each
/// line exactly two comma-separated fields named by `columns` (e.g. `x,y`) in the error.
pub(crate) fn stdin_pairs(
    input: &mut dyn BufRead,
    columns: &str,
) -> Result<Vec<(usize, String, String)>> {
    let mut pairs = Vec::new();
    for (n, line) in input.lines().enumerate() {
        let line = line.context("cannot read stdin")?;
        let line = line.trim();
        if line.is_empty() {
            continue;
        }
        let mut fields = line.split(',').map(str::trim);
        let (Some(a), Some(b), None) = (fields.next(), fields.next(), fields.next()) else {
            bail!("stdin line {}: expected `{columns}`, got `{line}`", n + 1);
        };
        pairs.push((n + 1, a.to_owned(), b.to_owned()));
    }
    Ok(pairs)
}

fn sample(args: &SkyArgs, input: &mut dyn BufRead, output: &mut dyn Write) -> Result<()> {
    let source = args.source()?;
    let mut rows: Vec<(String, String)> = Vec::new();
    let mut dirs: Vec<Vec3> = Vec::new();
    for (n, z, a) in stdin_pairs(input, "view_zenith_deg,view_azimuth_deg")? {
        match (z.parse::<f64>(), a.parse::<f64>()) {
            (Ok(zv), Ok(av)) if zv.is_finite() && av.is_finite() => {
                if !(0.0..=180.0).contains(&zv) {
                    bail!("stdin line {n}: view_zenith_deg = {zv} is outside [0, 180]");
                }
                dirs.push(geom::direction(sources::radians(zv), sources::radians(av)));
                rows.push((z, a));
            }
            _ if rows.is_empty() && n == 1 => {} // a header line
            _ => bail!(
                "stdin line {n}: view_zenith_deg and view_azimuth_deg must be finite numbers, got `{z},{a}`"
            ),
        }
    }
    let mut xyy = vec![Xyy::default(); dirs.len()];
    let mut rgb = vec![Vec3::ZERO; dirs.len()];
    source.xyy_batch(&dirs, &mut xyy);
    source.rgb_batch(&dirs, &mut rgb);
    let mut out = BufWriter::new(output);
    writeln!(out, "view_zenith_deg,view_azimuth_deg,Y,x,y,R,G,B")?;
    for ((z, a), (c, p)) in rows.iter().zip(xyy.iter().zip(&rgb)) {
        writeln!(
            out,
            "{z},{a},{},{},{},{},{},{}",
            c.luminance, c.x, c.y, p.x, p.y, p.z
        )?;
    }
    out.flush()?;
    Ok(())
}

fn gallery(args: &GalleryArgs, output: &mut dyn Write) -> Result<()> {
    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("cannot create --out {}", args.out.display()))?;
    let image = ImageArgs {
        width: args.width,
        extent: ExtentArg::Sphere,
        exposure: 0.0,
    };
    let grid = image.grid()?;
    const TURBIDITIES: [f64; 3] = [2.0, 4.0, 6.0];
    const SUN_ZENITHS: [f64; 4] = [10.0, 45.0, 70.0, 85.0];
    // A contact sheet of the upper hemispheres: one row per turbidity, one column per sun
    // zenith, each sky at its own automatic exposure.
    let (w, h) = (grid.width() as usize, grid.height() as usize / 2);
    let mut sheet = image_io::RgbImage {
        width: w * SUN_ZENITHS.len(),
        height: h * TURBIDITIES.len(),
        pixels: vec![Vec3::ZERO; w * h * SUN_ZENITHS.len() * TURBIDITIES.len()],
    };
    let mut written = Vec::new();
    for (row, turbidity) in TURBIDITIES.into_iter().enumerate() {
        for (col, sun_zenith) in SUN_ZENITHS.into_iter().enumerate() {
            let params = SkyParams {
                sun_zenith_deg: Some(sun_zenith),
                sun_azimuth_deg: Some(90.0),
                turbidity: Some(turbidity),
                ..SkyParams::default()
            };
            let source = sources::build(ModelKind::Preetham, &params)?;
            let img = render::equirect(&*source, &grid);
            let scale = render::auto_exposure(&img, &grid);
            let stem = args
                .out
                .join(format!("preetham_sun{sun_zenith:02}_t{turbidity}"));
            let exr = stem.with_extension("exr");
            image_io::write_exr(&exr, &img)?;
            let png = stem.with_extension("png");
            image_io::write_png(&png, &img, scale)?;
            written.extend([exr, png]);
            for y in 0..h {
                let dst = (row * h + y) * sheet.width + col * w;
                for (d, s) in sheet.pixels[dst..dst + w]
                    .iter_mut()
                    .zip(&img.pixels[y * w..])
                {
                    *d = *s * scale;
                }
            }
        }
    }
    let sheet_path = args.out.join("preetham_sheet.png");
    image_io::write_png(&sheet_path, &sheet, 1.0)?;
    written.push(sheet_path);
    let strip_path = args.out.join("aoas_presets.png");
    image_io::write_png(&strip_path, &aoas_presets(args.width)?, 1.0)?;
    written.push(strip_path);
    writeln!(
        output,
        "wrote {} files (rows: turbidity {TURBIDITIES:?}; columns: sun zenith {SUN_ZENITHS:?} deg):",
        written.len()
    )?;
    for p in &written {
        writeln!(output, "  {}", p.display())?;
    }
    Ok(())
}

fn train_command(args: &TrainArgs, output: &mut dyn Write) -> Result<()> {
    let mut config = TrainConfig::new(args.model);
    config.hidden = args.hidden.iter().map(|&h| usize::from(h)).collect();
    config.optimizer = args.optimizer;
    config.seed = u64::from(args.seed);
    config.sampling.seed = u64::from(args.seed);
    if let Some(t) = &args.turbidities {
        let (lo, hi) = args.model.turbidity_range();
        if let Some(bad) = t.iter().find(|t| !(lo..=hi).contains(*t)) {
            return Err(sources::ParamError(format!(
                "--turbidities {bad} is outside the valid range [{lo}, {hi}] for --model {}",
                args.model
            ))
            .into());
        }
        config.sampling.turbidities.clone_from(t);
    }
    config.sampling.sun_zeniths = usize::from(args.sun_zeniths);
    config.irradiance_weight = args.irradiance_weight;
    (config.sampling.view_zeniths, config.sampling.view_azimuths) = args.views;
    config.max_seconds = args.max_seconds;
    config.max_iterations = args.max_iterations as usize;
    config.target_nrmse = args.target_nrmse;
    config.checkpoint.clone_from(&args.checkpoint);
    if let Some(path) = &args.init_weights {
        config.init = Some(export::from_weights(&export::read_weights::<12>(path)?)?);
    } else {
        // Timed from scratch only.
        config.milestone = train::Milestone::paper(args.model)?;
    }
    let started = std::time::Instant::now();
    let set = train::dataset::DataSet::training(args.model, &config.sampling)?;
    let sampling = started.elapsed().as_secs_f64();
    let validation = train::validation_set(args.model)?;
    let trained = train::train(&config, &set, validation.as_slice())?;
    let wall = started.elapsed().as_secs_f64();
    writeln!(
        output,
        "trained {:?} on {} ({} examples) with {:?}: {} iterations, {:.1} s training, {:.1} s wall in all",
        trained.net.sizes,
        args.model,
        trained.examples,
        args.optimizer,
        trained.iterations,
        trained.seconds,
        wall
    )?;
    writeln!(output, "validation NRMSE {:.5}", trained.validation_nrmse)?;
    if config.milestone.is_some() {
        writeln!(output, "{}", milestone_line(&config, &trained, sampling))?;
    }
    let test = train::dataset::paper_test_set(args.model)?;
    writeln!(
        output,
        "test NRMSE (seed 000 protocol) {:.5}",
        trained.mean_nrmse(&test)
    )?;
    if let Some(path) = &args.out {
        if config.hidden == [12] {
            let weights = export::to_weights::<12>(&trained, args.model, args.seed)?;
            export::write_weights(path, &weights)?;
            writeln!(output, "wrote {}", path.display())?;
        } else {
            bail!(
                "--out writes 6-12-3 networks only; this run trained {:?}",
                trained.net.sizes
            );
        }
    }
    Ok(())
}

fn eval_command(args: &EvalArgs, output: &mut dyn Write) -> Result<()> {
    use sky_core::neural::{NeuralWeights, pretrained};
    let weights: NeuralWeights<12> = match (args.model, &args.weights) {
        (ModelKind::NeuralPreetham, None) => pretrained::PREETHAM,
        (ModelKind::NeuralHosek, None) => pretrained::HOSEK,
        (ModelKind::Neural, Some(path)) => export::read_weights::<12>(path)?,
        (ModelKind::Neural, None) => bail!("--model neural needs --weights FILE"),
        (model, _) => bail!(
            "--model {model}: eval takes neural-preetham, neural-hosek or neural --weights FILE"
        ),
    };
    let reference = match weights.source_name() {
        "preetham" => ModelKind::Preetham,
        "hosek" => ModelKind::Hosek,
        "aoas" => ModelKind::Aoas,
        other => bail!("the weights were trained on `{other}`, which eval has no reference for"),
    };
    let network = |p: &SkyParams| -> Result<Box<dyn sources::SkySource>> {
        Ok(Box::new(sources::Neural::new(&weights, args.model, p)?))
    };
    let evaluation = crate::eval::evaluate(reference, &network)?;
    write!(output, "{}", evaluation.report())?;
    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("cannot create --out {}", args.out.display()))?;
    // The skies of seed 000's Figs. 6 (Preetham, θ = 0.48π, t = 4) and 7 (Hosek, θ = 0.3π, t = 2).
    let (figure, zenith, turbidity) = match reference {
        ModelKind::Hosek => ("fig7", 0.3 * 180.0, 2.0),
        _ => ("fig6", 0.48 * 180.0, 4.0),
    };
    let params = SkyParams::sun_and_turbidity(zenith, 90.0, turbidity);
    let path = args.out.join(format!(
        "{figure}_{reference}_reference_network_difference.png"
    ));
    crate::eval::write_comparison(&path, reference, &*network(&params)?, &params, 512)?;
    writeln!(output, "wrote {}", path.display())?;
    Ok(())
}

/// When training reached seed 000's Table 1 NRMSE on its test protocol (the paper: 291 s),
/// counted from scratch: `sampling` seconds of making the training set, then training.
fn milestone_line(config: &TrainConfig, trained: &train::Trained, sampling: f64) -> String {
    let Some(m) = &config.milestone else {
        return String::new();
    };
    let when = trained.milestone.map_or_else(
        || "not reached".to_string(),
        |(s, i)| {
            format!(
                "reached after {:.1} s wall from scratch ({sampling:.1} s sampling, {s:.1} s and {i} iterations training)",
                sampling + s
            )
        },
    );
    format!(
        "seed 000 Table 1 NRMSE {} on its test protocol ({} images; the paper trained 291 s): {when}",
        m.nrmse,
        m.images.len()
    )
}

fn showcase(args: &ShowcaseArgs, output: &mut dyn Write) -> Result<()> {
    gallery(
        &GalleryArgs {
            out: args.out.clone(),
            width: 512,
        },
        output,
    )?;
    let model = ModelKind::Preetham;
    let mut config = TrainConfig::new(model);
    config.max_seconds = args.seconds;
    config.milestone = train::Milestone::paper(model)?;
    writeln!(
        output,
        "\ntraining a 6-12-3 neural sky on {model} from scratch (Levenberg-Marquardt, {} s budget)...",
        args.seconds
    )?;
    let sampling = std::time::Instant::now();
    let set = train::dataset::DataSet::training(model, &config.sampling)?;
    let sampling = sampling.elapsed().as_secs_f64();
    let validation = train::validation_set(model)?;
    let trained = train::train(&config, &set, validation.as_slice())?;
    writeln!(
        output,
        "{} iterations in {:.1} s; validation NRMSE {:.5}",
        trained.iterations, trained.seconds, trained.validation_nrmse,
    )?;
    writeln!(output, "{}", milestone_line(&config, &trained, sampling))?;
    let weights = export::to_weights::<12>(&trained, model, 1)?;
    let path = args.out.join("neural-preetham.skyn");
    export::write_weights(&path, &weights)?;
    writeln!(output, "wrote {}", path.display())?;
    let network = |p: &SkyParams| -> Result<Box<dyn sources::SkySource>> {
        Ok(Box::new(sources::Neural::new(
            &weights,
            ModelKind::Neural,
            p,
        )?))
    };
    let evaluation = crate::eval::evaluate(model, &network)?;
    write!(output, "{}", evaluation.report())?;
    let params = SkyParams::sun_and_turbidity(0.48 * 180.0, 90.0, 4.0);
    let path = args
        .out
        .join("fig6_preetham_reference_network_difference.png");
    crate::eval::write_comparison(&path, model, &*network(&params)?, &params, 512)?;
    writeln!(output, "wrote {}", path.display())?;
    Ok(())
}

/// The AOAS presets laid out like the figures of seed 004, each through a perspective camera at
/// its own (median) exposure, luminance compressed by Reinhard's L/(1 + L) so that the sun's
/// glow keeps its hue: day cycle (Fig. 12: sunrise, noon, sunset), sky hue (Fig. 11: grey,
/// yellow, blue, coral), sky pattern (Figs. 1, 9, 10: smiley, heart, turbulent, ambiguous).
/// Tiles are `width` / 2 pixels wide, the horizon along their bottom; a camera faces the sun
/// when it is low, and due north (where the presets draw their clouds) otherwise, except the
/// last of the top row: noon again, facing the sun.
fn aoas_presets(width: u32) -> Result<image_io::RgbImage> {
    use sky_core::aoas::Preset as P;
    // (preset, whether the camera faces the sun whatever its height)
    const ROWS: [[(P, bool); 4]; 3] = [
        [
            (P::Sunrise, true),
            (P::Physical, false),
            (P::Sunset, true),
            (P::Physical, true),
        ],
        [
            (P::Grey, false),
            (P::Yellow, false),
            (P::Blue, false),
            (P::Coral, false),
        ],
        [
            (P::Smiley, false),
            (P::Heart, false),
            (P::Turbulent, false),
            (P::Ambiguous, false),
        ],
    ];
    let columns = ROWS[0].len();
    let w = (width as usize / 2).max(8);
    let h = w * 5 / 8;
    let mut sheet = image_io::RgbImage {
        width: w * columns,
        height: h * ROWS.len(),
        pixels: vec![Vec3::ZERO; w * h * columns * ROWS.len()],
    };
    for (row, presets) in ROWS.iter().enumerate() {
        for (col, &(preset, face_sun)) in presets.iter().enumerate() {
            let params = SkyParams {
                style: Some(preset.name().into()),
                ..SkyParams::default()
            };
            let source = sources::Aoas::new(&params)?;
            let sun = source.sky.sun();
            let low = face_sun || sun.zenith() > 75f32.to_radians();
            let horizontal_fov = 100f32.to_radians();
            #[allow(clippy::cast_precision_loss)] // small sizes
            let half_vertical = ((0.5 * horizontal_fov).tan() * h as f32 / w as f32).atan();
            let camera = render::Camera {
                azimuth: if low {
                    sun.azimuth()
                } else {
                    core::f32::consts::FRAC_PI_2
                },
                elevation: half_vertical - 1f32.to_radians(),
                horizontal_fov,
            };
            let img = render::perspective(&source, &camera, w, h);
            let scale = render::median_exposure(&img, 0.8);
            for y in 0..h {
                let dst = (row * h + y) * sheet.width + col * w;
                for (d, s) in sheet.pixels[dst..dst + w]
                    .iter_mut()
                    .zip(&img.pixels[y * w..])
                {
                    let c = *s * scale;
                    *d = c / (1.0 + color::luminance(c));
                }
            }
        }
    }
    Ok(sheet)
}
