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
    /// preset) to a folder: the main job.
    Gallery(GalleryArgs),
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
    /// Atmospheric turbidity (preetham only: 2 to 6; default 3).
    #[arg(long, value_name = "T", allow_negative_numbers = true)]
    turbidity: Option<f64>,
    /// The style (aoas only): a preset (physical, sunrise, sunset, grey, yellow, blue, coral,
    /// smiley, heart, turbulent, ambiguous) or a style file in TOML. Default: physical.
    #[arg(long, value_name = "PRESET|FILE")]
    style: Option<String>,
}

impl SkyArgs {
    fn params(&self) -> SkyParams {
        SkyParams {
            sun_zenith_deg: self.sun_zenith,
            sun_azimuth_deg: self.sun_azimuth,
            turbidity: self.turbidity,
            style: self.style.clone(),
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
            Ok(())
        }
        Command::Gallery(args) => gallery(&args, output),
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
                sun_zenith_deg: Some(sun_zenith),
                sun_azimuth_deg: Some(90.0),
                turbidity: Some(turbidity),
                style: None,
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
