//! `sky-train render`: an equirectangular image of one sky, OpenEXR or PNG.

use std::path::PathBuf;

use anyhow::Result;
use clap::Args;

use super::{ImageArgs, SkyArgs};
use crate::image_io::{self, Format};
use crate::output_path::{self, Folder};
use crate::render;

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

/// Renders the sky of `args` to its `--out` file and names both on stderr. The file's type and
/// folder are checked before the sky is built (the physical model's precomputation takes a
/// minute).
///
/// # Errors
/// Bad parameters or an `--out` that cannot be written as a [`crate::args::ParamError`], a
/// failed write.
pub fn run(args: &RenderArgs) -> Result<()> {
    let format = Format::from_path(&args.out)?;
    output_path::file("--out", &args.out, Folder::Existing)?;
    let grid = args.image.grid()?;
    let source = args.sky.source()?;
    let img = render::equirect(&*source, &grid);
    match format {
        Format::Exr => image_io::write_exr(&args.out, &img)?,
        Format::Png => {
            let scale = render::auto_exposure(&img, &grid) * args.image.exposure.exp2();
            image_io::write_png(&args.out, &img, scale)?;
        }
    }
    eprintln!("{}: {}", source.describe(), args.out.display());
    Ok(())
}
