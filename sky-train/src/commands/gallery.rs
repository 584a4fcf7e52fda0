//! `sky-train gallery`: the default skies (Preetham: sun positions x turbidities; AOAS: every
//! style preset) rendered to a folder.

use std::io::Write;
use std::path::PathBuf;

use anyhow::{Context, Result};
use clap::Args;
use sky_core::Vec3;
use sky_core::color;

use super::{ExtentArg, ImageArgs};
use crate::image_io;
use crate::render;
use crate::sources::{self, ModelKind, SkyParams};

/// `gallery`'s arguments.
#[derive(Args)]
pub struct GalleryArgs {
    /// Output folder (created if missing).
    #[arg(long, value_name = "DIR", default_value = "out")]
    pub out: PathBuf,
    /// Image width in pixels (4 to 16384: the contact sheet shows the upper hemisphere,
    /// width / 4 rows high).
    #[arg(long, value_name = "W", default_value_t = 512, value_parser = clap::value_parser!(u32).range(4..=16384))]
    pub width: u32,
}

/// Renders the gallery into `--out` and lists the files written on `output`.
///
/// # Errors
/// A folder that cannot be created, a failed write.
pub fn run(args: &GalleryArgs, output: &mut dyn Write) -> Result<()> {
    crate::output_path::folder("--out", &args.out)?;
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
