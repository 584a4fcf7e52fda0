//! `sky-train render`: an equirectangular image of one sky, OpenEXR or PNG.

use std::path::{Path, PathBuf};

use anyhow::Result;
use clap::Args;

use super::{ImageArgs, SkyArgs};
use crate::image_io::{self, Format};
use crate::render;
use crate::sources::SkySource;

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

/// Renders the sky of `args` to its `--out` file and names both on stderr.
///
/// # Errors
/// Bad parameters as a [`crate::args::ParamError`], an unknown file type, a failed write.
pub fn run(args: &RenderArgs) -> Result<()> {
    let source = args.sky.source()?;
    let path = render_to(&*source, &args.image, &args.out)?;
    eprintln!("{}: {}", source.describe(), path.display());
    Ok(())
}

fn render_to(source: &dyn SkySource, image: &ImageArgs, out: &Path) -> Result<PathBuf> {
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
