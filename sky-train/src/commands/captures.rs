//! `sky-train captures …`: the command line of captured skies.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::Result;
use clap::{Args, Subcommand};

use crate::args::{
    ParamError, clock, date, duration_minutes, finite, latitude, longitude, seconds,
};
use crate::captures::load::{self, LoadConfig};
use crate::captures::synthesize::{self, SynthConfig};
use crate::captures::{Sequence, interpolate, manifest, validate};
use crate::export::{self, TrainedOn};
use crate::output_path::{self, Folder};

/// The `captures` subcommands.
#[derive(Subcommand)]
pub enum CapturesCommand {
    /// Train one neural sky on a folder of latitude-longitude OpenEXR captures (seed 000
    /// §III-D), run the leave-one-out cross-validation of §IV-A (per-frame and mean NRMSE,
    /// irradiance, and linear blending of the neighbouring captures for comparison), and write
    /// the weights.
    Train(TrainArgs),
    /// Render the trained sky every --step between the first and the last capture, one OpenEXR
    /// file per step (seed 000 Figs. 1, 9).
    Interpolate(InterpolateArgs),
    /// Write a capture-like sequence of the Hosek-Wilkie sky with its manifest: exposure varying
    /// between frames, sensor noise, a clipped sun, a skyline, a slight camera rotation.
    Synthesize(SynthesizeArgs),
    /// A PNG strip like seed 000's Fig. 1: captures on the top row with gaps, the trained sky
    /// filling every column of the bottom row.
    Strip(StripArgs),
}

/// `captures train`'s arguments.
#[derive(Args)]
pub struct TrainArgs {
    /// The folder of frames (and optionally `captures.toml`).
    #[arg(long, value_name = "DIR")]
    pub input: PathBuf,
    /// The weight file to write (default: DIR/sky.weights).
    #[arg(long, value_name = "FILE")]
    pub out: Option<PathBuf>,
    /// Skip the leave-one-out cross-validation (one training instead of frames + 1).
    #[arg(long)]
    pub no_cross_validation: bool,
    /// Training samples per frame (64 to 1000000).
    #[arg(long, default_value_t = 2048, value_parser = clap::value_parser!(u32).range(64..=1_000_000))]
    pub samples: u32,
    /// Random seed (initial weights and sampling).
    #[arg(long, default_value_t = 1)]
    pub seed: u32,
    /// Wall-time budget per training, seconds (1 to 86400).
    #[arg(long, default_value_t = 60.0, value_parser = seconds)]
    pub max_seconds: f64,
    /// Iteration budget per training (1 to 100000).
    #[arg(long, default_value_t = 150, value_parser = clap::value_parser!(u32).range(1..=100_000))]
    pub max_iterations: u32,
}

/// `captures interpolate`'s arguments.
#[derive(Args)]
pub struct InterpolateArgs {
    /// The weight file written by `captures train`.
    #[arg(long, value_name = "FILE")]
    pub weights: PathBuf,
    /// The folder of captures the weights were trained on (for the sun's positions).
    #[arg(long, value_name = "DIR")]
    pub input: PathBuf,
    /// Time between output frames: `1min`, `30s`, `0.5min`, `1h` (1 s to 24 h).
    #[arg(long, default_value = "1min", value_parser = duration_minutes)]
    pub step: f64,
    /// Time between captures that have no times in a manifest.
    #[arg(long, default_value = "15min", value_parser = duration_minutes)]
    pub interval: f64,
    /// The folder to write `interp_NNNN.exr` to (created if missing).
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// Output width in pixels (height = width / 2; default: the captures' width).
    #[arg(long, value_parser = clap::value_parser!(u32).range(16..=16384))]
    pub width: Option<u32>,
    /// The most frames to write (1 to 1,000,000): a --step that would give more is refused
    /// before anything is rendered.
    #[arg(long, value_name = "N", default_value_t = DEFAULT_MAX_FRAMES, value_parser = clap::value_parser!(u32).range(1..=1_000_000))]
    pub max_frames: u32,
}

/// `captures interpolate --max-frames`' default: a day of minutes is 1,440 frames; a thousand
/// 1024 x 512 OpenEXR frames are about 6 GB.
pub const DEFAULT_MAX_FRAMES: u32 = 1000;

/// `captures synthesize`'s arguments.
#[derive(Args)]
pub struct SynthesizeArgs {
    /// The folder to write the frames and `captures.toml` to (created if missing).
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// Latitude in degrees, north positive (-90 to 90).
    #[arg(long, default_value_t = 48.21, allow_negative_numbers = true, value_parser = latitude)]
    pub lat: f64,
    /// Longitude in degrees, east positive (-180 to 180).
    #[arg(long, default_value_t = 16.37, allow_negative_numbers = true, value_parser = longitude)]
    pub lon: f64,
    /// The UTC date, YYYY-MM-DD.
    #[arg(long, default_value = "2026-06-21", value_parser = date)]
    pub date: (i32, u32, u32),
    /// First frame, HH:MM UTC (default: the first step with the sun high enough).
    #[arg(long, value_name = "HH:MM", value_parser = clock)]
    pub start: Option<u32>,
    /// Number of frames (default: every step while the sun is high enough).
    #[arg(long, value_parser = clap::value_parser!(u32).range(2..=1440))]
    pub frames: Option<u32>,
    /// Minutes between frames (1 to 240).
    #[arg(long, default_value_t = 15, value_parser = clap::value_parser!(u32).range(1..=240))]
    pub step: u32,
    /// Frame width in pixels (even, 16 to 16384; height = width / 2).
    #[arg(long, default_value_t = 1024)]
    pub width: usize,
    /// Hosek-Wilkie turbidity (1 to 10).
    #[arg(long, default_value_t = 3.0)]
    pub turbidity: f64,
    /// Lowest sun elevation of a frame in degrees (the skyline reaches 8).
    #[arg(long, default_value_t = 12.0, allow_negative_numbers = true, value_parser = finite)]
    pub min_elevation: f64,
    /// Random seed (exposure, noise, skyline, camera offsets).
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
}

/// `captures strip`'s arguments.
#[derive(Args)]
pub struct StripArgs {
    /// The folder of captures.
    #[arg(long, value_name = "DIR")]
    pub input: PathBuf,
    /// The weight file written by `captures train`.
    #[arg(long, value_name = "FILE")]
    pub weights: PathBuf,
    /// The PNG to write.
    #[arg(long, value_name = "FILE")]
    pub out: PathBuf,
    /// How many captures (from the first).
    #[arg(long, default_value_t = 6, value_parser = clap::value_parser!(u32).range(2..=100))]
    pub captures: u32,
    /// Network frames in each gap.
    #[arg(long, default_value_t = 2, value_parser = clap::value_parser!(u32).range(0..=20))]
    pub between: u32,
    /// Thumbnail width in pixels (height = width / 4: the upper hemisphere).
    #[arg(long, default_value_t = 128, value_parser = clap::value_parser!(u32).range(16..=1024))]
    pub thumb_width: u32,
}

/// Runs a `captures` subcommand, reporting to `output`.
///
/// # Errors
/// Bad input (naming the file and the problem) or a failed write.
pub fn run(command: &CapturesCommand, output: &mut dyn Write) -> Result<()> {
    match command {
        CapturesCommand::Train(args) => train(args, output),
        CapturesCommand::Interpolate(args) => {
            output_path::folder("--out", &args.out)?;
            if let Some(w) = args.width {
                interpolate::check_width(w as usize)?;
            }
            let started = Instant::now();
            let weights = super::weight_file("--weights", &args.weights)?;
            let seq = load_for_suns(&args.input)?;
            let loaded = started.elapsed().as_secs_f64();
            let steps = interpolate::steps(&seq, args.step, args.interval)?;
            if steps.len() > args.max_frames as usize {
                return Err(ParamError(format!(
                    "--step {} min would write {} frames to --out {} for {} captures, more than --max-frames {}: give a longer --step or a larger --max-frames",
                    crate::csv_output::compact(args.step),
                    steps.len(),
                    args.out.display(),
                    seq.frames.len(),
                    args.max_frames
                ))
                .into());
            }
            let width = args.width.map_or(seq.width, |w| w as usize);
            let rendering = Instant::now();
            let paths = interpolate::write_steps(&weights, &steps, width, &args.out, true)?;
            writeln!(
                output,
                "wrote {} frames of {width}x{} to {} in {:.2} s (reading the {} captures for the sun's positions: {loaded:.2} s more)",
                paths.len(),
                width / 2,
                args.out.display(),
                rendering.elapsed().as_secs_f64(),
                seq.frames.len()
            )?;
            Ok(())
        }
        CapturesCommand::Synthesize(args) => {
            output_path::folder("--out", &args.out)?;
            let config = SynthConfig {
                latitude: args.lat,
                longitude: args.lon,
                date: args.date,
                start_minutes: args.start,
                frames: args.frames.map(|n| n as usize),
                step_minutes: args.step,
                width: args.width,
                turbidity: args.turbidity,
                min_elevation_deg: args.min_elevation,
                seed: args.seed,
            };
            let frames = synthesize::synthesize(&config, &args.out, true)?;
            writeln!(
                output,
                "wrote {} frames of {}x{} and {} to {} ({} to {})",
                frames.len(),
                args.width,
                args.width / 2,
                manifest::MANIFEST,
                args.out.display(),
                frames[0].time.rfc3339(),
                frames[frames.len() - 1].time.rfc3339()
            )?;
            Ok(())
        }
        CapturesCommand::Strip(args) => {
            output_path::file_ending("--out", &args.out, &["png"])?;
            let weights = super::weight_file("--weights", &args.weights)?;
            let seq = load_for_suns(&args.input)?;
            let image = interpolate::strip(
                &seq,
                &weights,
                args.captures as usize,
                args.between as usize,
                args.thumb_width as usize,
            )?;
            crate::image_io::write_png(&args.out, &image, 1.0)?;
            writeln!(output, "wrote {}", args.out.display())?;
            Ok(())
        }
    }
}

/// The captures of `dir` read for their suns only (few samples).
fn load_for_suns(dir: &Path) -> Result<Sequence, ParamError> {
    load_input(
        dir,
        &LoadConfig {
            samples_per_frame: 64,
            ..LoadConfig::default()
        },
    )
}

/// The captures of `--input` `dir`: a folder, manifest or frame that cannot be read or is
/// refused is bad input (exit status 2).
fn load_input(dir: &Path, config: &LoadConfig) -> Result<Sequence, ParamError> {
    load::load(dir, config).map_err(|e| ParamError(format!("--input {e:#}")))
}

fn train(args: &TrainArgs, output: &mut dyn Write) -> Result<()> {
    if !args.input.is_dir() {
        return Err(ParamError(format!("--input {}: not a folder", args.input.display())).into());
    }
    let path = args
        .out
        .clone()
        .unwrap_or_else(|| args.input.join("sky.weights"));
    output_path::file("--out", &path, Folder::Existing)?;
    let started = Instant::now();
    let load_config = LoadConfig {
        samples_per_frame: args.samples as usize,
        seed: u64::from(args.seed),
        ..LoadConfig::default()
    };
    let seq = load_input(&args.input, &load_config)?;
    let loaded = started.elapsed().as_secs_f64();
    let examples: usize = seq.frames.iter().map(|f| f.views.len()).sum();
    writeln!(
        output,
        "read {} frames of {}x{} in {loaded:.2} s: {examples} examples",
        seq.frames.len(),
        seq.width,
        seq.height
    )?;
    for f in &seq.frames {
        writeln!(
            output,
            "  {:<24} {}  sun zenith {:6.2} deg{}  image azimuth {:6.2} deg  sun radius {:.2} deg  exposure {:.4}",
            f.name(),
            f.time.map_or_else(|| "-".to_string(), |t| t.rfc3339()),
            f.sun_zenith.to_degrees(),
            f.solar_zenith.map_or_else(String::new, |_| format!(
                " (found in the image: {:.2})",
                f.sun.zenith.to_degrees()
            )),
            f.sun.azimuth.to_degrees(),
            f.sun.radius.to_degrees(),
            f.exposure
        )?;
    }
    let mut config = validate::config();
    config.seed = u64::from(args.seed);
    config.max_seconds = args.max_seconds;
    config.max_iterations = args.max_iterations as usize;
    let training = Instant::now();
    let trained = validate::train_frames(&seq, &config, None)?;
    writeln!(
        output,
        "trained 6-12-3 on all {} frames: {} iterations, {:.2} s training, {:.2} s with reading (training NRMSE {:.5})",
        seq.frames.len(),
        trained.iterations,
        training.elapsed().as_secs_f64(),
        started.elapsed().as_secs_f64(),
        trained.validation_nrmse
    )?;
    let (lo, hi) = seq.sun_zenith_range();
    let margin = 2f64.to_radians();
    let trained_on = TrainedOn {
        source: "captures".into(),
        uses_turbidity: false,
        turbidity_range: (0.0, 0.0),
        sun_zenith_range: (
            (lo - margin).max(0.0),
            (hi + margin).min(std::f64::consts::FRAC_PI_2),
        ),
    };
    let weights = export::to_weights_of::<12>(&trained, &trained_on, args.seed)?;
    export::write_weights(&path, &weights)?;
    writeln!(output, "wrote {}", path.display())?;
    if !args.no_cross_validation {
        let cv = validate::cross_validate(&seq, &config)?;
        write!(output, "{}", cv.report())?;
        writeln!(
            output,
            "cross-validation: {} trainings in {:.1} s",
            seq.frames.len(),
            cv.seconds
        )?;
    }
    Ok(())
}
