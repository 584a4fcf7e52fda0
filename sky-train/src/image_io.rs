//! Images in and out: OpenEXR (linear float RGB) and PNG (sRGB-encoded), written atomically.

use std::io::{BufWriter, Write};
use std::path::Path;

use anyhow::{Context, Result, bail};
use sky_core::Vec3;
use sky_core::color;

use crate::args::ParamError;

/// A linear RGB image, row-major, top row first.
#[derive(Debug, Clone, PartialEq)]
pub struct RgbImage {
    /// Width in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
    /// `width * height` linear sRGB pixels.
    pub pixels: Vec<Vec3>,
}

impl RgbImage {
    /// The pixel at column `x`, row `y`.
    #[must_use]
    pub fn get(&self, x: usize, y: usize) -> Vec3 {
        self.pixels[y * self.width + x]
    }
}

pub use crate::output_path::write_atomically;

/// The image formats `--out` accepts, by extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// OpenEXR, linear float RGB.
    Exr,
    /// PNG, 8-bit sRGB.
    Png,
}

impl Format {
    /// The format named by `path`'s extension.
    ///
    /// # Errors
    /// A [`ParamError`] naming `--out` when the extension is neither `.exr` nor `.png`.
    pub fn from_path(path: &Path) -> Result<Self, ParamError> {
        match path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase)
            .as_deref()
        {
            Some("exr") => Ok(Self::Exr),
            Some("png") => Ok(Self::Png),
            _ => Err(ParamError(format!(
                "--out {}: the file name must end in .exr (linear float) or .png (sRGB)",
                path.display()
            ))),
        }
    }
}

/// Writes `img` as OpenEXR with three 32-bit float channels R, G, B (linear sRGB primaries).
///
/// # Errors
/// On any I/O or encoding error; nothing is left at `path` then.
pub fn write_exr(path: &Path, img: &RgbImage) -> Result<()> {
    use exr::prelude::*;
    let channels = SpecificChannels::rgb(|pos: Vec2<usize>| {
        let p = img.get(pos.x(), pos.y());
        (p.x, p.y, p.z)
    });
    let image = Image::from_channels((img.width, img.height), channels);
    write_atomically(path, |file| {
        // The encoder seeks back to write its offset tables: a FIFO or a device written
        // directly gets the whole file encoded in memory first.
        if file.metadata()?.is_file() {
            image
                .write()
                .non_parallel()
                .to_buffered(BufWriter::new(file))
                .context("OpenEXR encoding failed")
        } else {
            let mut bytes = std::io::Cursor::new(Vec::new());
            image
                .write()
                .non_parallel()
                .to_buffered(&mut bytes)
                .context("OpenEXR encoding failed")?;
            Ok(file.write_all(bytes.get_ref())?)
        }
    })
}

/// Writes `img` as an 8-bit sRGB PNG after multiplying by `scale` (values above 1 clip).
///
/// # Errors
/// On any I/O or encoding error; nothing is left at `path` then.
pub fn write_png(path: &Path, img: &RgbImage, scale: f32) -> Result<()> {
    let width = u32::try_from(img.width).context("image too wide for PNG")?;
    let height = u32::try_from(img.height).context("image too tall for PNG")?;
    let bytes: Vec<u8> = img
        .pixels
        .iter()
        .flat_map(|p| (*p * scale).to_array())
        .map(encode_8bit)
        .collect();
    write_png_srgb8(path, width, height, &bytes)
}

/// Writes `width` × `height` pixels of 8-bit sRGB (`r, g, b` row by row) as PNG, atomically.
///
/// # Errors
/// `bytes` of the wrong length, or a failed write.
pub fn write_png_srgb8(path: &Path, width: u32, height: u32, bytes: &[u8]) -> Result<()> {
    if bytes.len() != 3 * width as usize * height as usize {
        bail!(
            "{}: {} bytes are not {width} x {height} RGB pixels",
            path.display(),
            bytes.len()
        );
    }
    write_atomically(path, |file| {
        let mut encoder = png::Encoder::new(BufWriter::new(file), width, height);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        encoder.set_source_srgb(png::SrgbRenderingIntent::Perceptual);
        let mut writer = encoder.write_header()?;
        writer.write_image_data(bytes)?;
        writer.finish()?;
        Ok(())
    })
}

#[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)] // in [0, 255.5)
fn encode_8bit(linear: f32) -> u8 {
    (color::srgb_encode(linear) * 255.0 + 0.5) as u8
}

/// The largest image read (an OpenEXR frame by [`read_exr`], a capture mask): 8192 × 4096
/// pixels (2²⁵), which take 384 MiB as linear RGB f32. A file's header can claim any size (an
/// OpenEXR data window is two pairs of 32-bit corners) whatever the file's length, so the size
/// is checked from the header before anything of the image is allocated.
pub const MAX_IMAGE_PIXELS: usize = 8192 * 4096;

/// The longest image file read (an OpenEXR frame, a capture mask): the largest image
/// ([`MAX_IMAGE_PIXELS`]) as four uncompressed 32-bit channels (512 MiB), and 64 MiB for
/// headers and offset tables.
pub const MAX_IMAGE_FILE_BYTES: u64 = MAX_IMAGE_PIXELS as u64 * 16 + (64 << 20);

/// Checks that an image of `width` × `height` pixels is at most [`MAX_IMAGE_PIXELS`].
///
/// # Errors
/// When it is larger, naming the size, the limit and the memory it would take.
pub fn check_image_size(width: usize, height: usize) -> Result<()> {
    let pixels = width.saturating_mul(height);
    if pixels > MAX_IMAGE_PIXELS {
        #[allow(clippy::cast_precision_loss)] // a size in GiB for the message
        let gib = pixels as f64 * 12.0 / f64::from(1u32 << 30);
        bail!(
            "the header claims {width}x{height} pixels ({gib:.1} GiB as RGB f32), more than the \
             largest image read, 8192x4096 pixels ({} in all)",
            MAX_IMAGE_PIXELS
        );
    }
    Ok(())
}

/// Reads an OpenEXR file's R, G, B channels (any sample type) as linear RGB; images larger
/// than [`MAX_IMAGE_PIXELS`] are refused from their header, before their pixels are allocated.
///
/// # Errors
/// When the file cannot be read, is not OpenEXR, is too large, or lacks R, G or B.
pub fn read_exr(path: &Path) -> Result<RgbImage> {
    let file = crate::csv_input::open(path, MAX_IMAGE_FILE_BYTES)
        .with_context(|| format!("cannot open {}", path.display()))?;
    read_exr_from(std::io::BufReader::new(file))
        .with_context(|| format!("cannot read OpenEXR file {}", path.display()))
}

/// [`read_exr`] from a reader positioned at the start of an OpenEXR file.
///
/// # Errors
/// As [`read_exr`].
pub fn read_exr_from(mut reader: impl std::io::Read + std::io::Seek + Send) -> Result<RgbImage> {
    use exr::prelude::*;
    let meta = exr::meta::MetaData::read_from_buffered(&mut reader, false)?;
    for header in &meta.headers {
        check_image_size(header.layer_size.width(), header.layer_size.height())?;
    }
    reader.rewind()?;
    let image = read()
        .no_deep_data()
        .largest_resolution_level()
        .rgba_channels(
            |resolution, _| RgbImage {
                width: resolution.width(),
                height: resolution.height(),
                pixels: vec![Vec3::ZERO; resolution.width() * resolution.height()],
            },
            |img: &mut RgbImage, pos, (r, g, b, _a): (f32, f32, f32, f32)| {
                img.pixels[pos.y() * img.width + pos.x()] = Vec3::new(r, g, b);
            },
        )
        .first_valid_layer()
        .all_attributes()
        .from_buffered(reader)?;
    Ok(image.layer_data.channel_data.pixels)
}

/// Reads the text file `path` of at most `max_bytes` bytes through the bounded reader
/// ([`crate::csv_input::read_text`]: a regular file, lines of at most 4096 bytes).
///
/// # Errors
/// When the file cannot be read, is not a regular file, is longer, has a longer line or is
/// not UTF-8; the message names the file.
pub fn read_text(path: &Path, max_bytes: u64) -> Result<String> {
    let source = format!("cannot read {}", path.display());
    Ok(crate::csv_input::read_text(path, &source, max_bytes)?)
}

/// Writes `text` to `path` atomically.
///
/// # Errors
/// On any I/O error.
pub fn write_text(path: &Path, text: &str) -> Result<()> {
    write_atomically(path, |file| Ok(file.write_all(text.as_bytes())?))
}
