//! The command line: argument parsing and the subcommands, callable in-process (the binary is a
//! thin wrapper; tests drive [`execute`] directly).

use std::io::{BufRead, BufWriter, Write};
use std::path::{Path, PathBuf};

use crate::image_io::{self, Format};
use crate::sources::{self, ModelKind, SkyParams};
use crate::{bench, render};
use anyhow::{Context, Result, bail};
use clap::{Args, Parser, Subcommand, ValueEnum};
use sky_core::Vec3;
use sky_core::color::Xyy;
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
    /// `view_zenith_deg,view_azimuth_deg,Y,x,y,R,G,B` to stdout (Y in cd/m², RGB linear sRGB on
    /// the same scale).
    Sample(SkyArgs),
    /// Print ns/direction of each evaluator over a hemisphere grid, single-threaded, with ratios.
    Bench(BenchArgs),
    /// Render a set of default skies (sun positions x turbidities) to a folder: the main job.
    Gallery(GalleryArgs),
    /// Fit a model's spherical-harmonics coefficients as polynomials in sun zenith and
    /// turbidity (seed 001) and write them as a Rust table for sky-core.
    FitSh(FitShArgs),
}

/// The arguments that select one sky.
#[derive(Args, Clone)]
pub struct SkyArgs {
    /// The sky model.
    #[arg(long, value_enum, default_value_t = ModelKind::Preetham)]
    model: ModelKind,
    /// Sun zenith angle in degrees (0 = overhead, 90 = on the horizon).
    #[arg(long, value_name = "DEG", allow_negative_numbers = true)]
    sun_zenith: f64,
    /// Sun azimuth in degrees, measured from +x towards +y (any finite value).
    #[arg(long, value_name = "DEG", default_value_t = 0.0, allow_negative_numbers = true, value_parser = finite)]
    sun_azimuth: f64,
    /// Atmospheric turbidity (preetham: 2 to 6).
    #[arg(
        long,
        value_name = "T",
        default_value_t = 3.0,
        allow_negative_numbers = true
    )]
    turbidity: f64,
    /// Spherical-harmonics bands, 1 to 7 (--model sh only).
    #[arg(long, value_name = "N", default_value_t = 7)]
    bands: usize,
    /// Leave out the ringing filter of seed 001, eq. 5 (--model sh only).
    #[arg(long)]
    no_ringing_filter: bool,
}

impl SkyArgs {
    fn params(&self) -> SkyParams {
        SkyParams {
            sun_zenith_deg: self.sun_zenith,
            sun_azimuth_deg: self.sun_azimuth,
            turbidity: self.turbidity,
            bands: self.bands,
            ringing_filter: !self.no_ringing_filter,
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
            let source = sources::build(args.sky.model, &args.sky.params())?;
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
            Ok(())
        }
        Command::Gallery(args) => gallery(&args, output),
        Command::FitSh(args) => fit_sh(&args, output),
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

fn sample(args: &SkyArgs, input: &mut dyn BufRead, output: &mut dyn Write) -> Result<()> {
    let source = sources::build(args.model, &args.params())?;
    let mut rows: Vec<(String, String)> = Vec::new();
    let mut dirs: Vec<Vec3> = Vec::new();
    for (n, line) in input.lines().enumerate() {
        let line = line.context("cannot read stdin")?;
        let line = line.trim();
        if line.is_empty() {
            continue;
        }
        let mut fields = line.split(',').map(str::trim);
        let (Some(z), Some(a), None) = (fields.next(), fields.next(), fields.next()) else {
            bail!(
                "stdin line {}: expected `view_zenith_deg,view_azimuth_deg`, got `{line}`",
                n + 1
            );
        };
        match (z.parse::<f64>(), a.parse::<f64>()) {
            (Ok(zv), Ok(av)) if zv.is_finite() && av.is_finite() => {
                if !(0.0..=180.0).contains(&zv) {
                    bail!(
                        "stdin line {}: view_zenith_deg = {zv} is outside [0, 180]",
                        n + 1
                    );
                }
                dirs.push(geom::direction(sources::radians(zv), sources::radians(av)));
                rows.push((z.to_owned(), a.to_owned()));
            }
            _ if rows.is_empty() && n == 0 => {} // a header line
            _ => bail!(
                "stdin line {}: view_zenith_deg and view_azimuth_deg must be finite numbers, got `{line}`",
                n + 1
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
                sun_zenith_deg: sun_zenith,
                sun_azimuth_deg: 90.0,
                turbidity,
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
