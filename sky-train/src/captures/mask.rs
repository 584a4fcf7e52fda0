//! Which pixels of a frame are sky (seed 000 §III-D: "Valid sky pixels are currently selected by
//! segmenting the sky from any other content, such as trees or buildings ... pixels tagged as
//! belonging to the sun are not used in training via thresholding").
//!
//! A pixel is used when it is above the horizon, finite, sky by the mask, and outside the sun's
//! exclusion disc:
//!
//! * **Mask image** (manifest `mask = "…"`): a PNG of the frames' size, white (≥ 128) = sky.
//! * **Skyline estimate** when there is no mask. Per column, the reference level is the median
//!   luminance between 45° and 80° elevation (assumed open sky); scanning down from 45° to the
//!   horizon, the first pixel darker than [`SKYLINE_FRACTION`] of it is the skyline, and it and
//!   everything below it is not sky (holes in a tree line below the skyline are given up). The
//!   skyline is then raised by one pixel and taken as the highest of each column and its two
//!   neighbours, so the mixed pixels along a silhouette's edge are left out. This assumes
//!   obstacles lower than 45° and darker than a fifth of the sky above them, which holds for
//!   daytime captures of buildings and trees against a clear sky; anything else wants a mask.
//! * **Sun disc**: pixels within [`SUN_EXCLUSION`] times the bright region's radius (see
//!   [`super::sun`]) plus one pixel: the clipped disc and the lens glare around it.

use std::path::Path;

use anyhow::{Context, Result, bail};

/// A pixel darker than this fraction of the sky above it is below the skyline.
pub const SKYLINE_FRACTION: f32 = 0.2;
/// The sun's exclusion radius in units of its bright region's radius.
pub const SUN_EXCLUSION: f64 = 1.6;

/// A sky mask read from a PNG: `true` = sky.
#[derive(Debug, Clone, PartialEq)]
pub struct SkyMask {
    /// Width in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
    /// Row-major, `true` where the pixel is sky.
    pub sky: Vec<bool>,
}

impl SkyMask {
    /// Reads a mask image (8- or 16-bit grey, grey + alpha, RGB or RGBA PNG; the first channel
    /// decides).
    ///
    /// # Errors
    /// When the file cannot be read or is not a PNG (the message names the file).
    pub fn read(path: &Path) -> Result<Self> {
        let file = crate::csv_input::open(path, crate::image_io::MAX_IMAGE_FILE_BYTES)
            .with_context(|| format!("mask {}: cannot open", path.display()))?;
        // The png crate's own limit (64 MiB of decoded bytes by default) would refuse the mask
        // of a frame of the largest size; the size is checked from the header instead.
        let mut decoder = png::Decoder::new_with_limits(
            std::io::BufReader::new(file),
            png::Limits {
                bytes: crate::image_io::MAX_IMAGE_PIXELS * 8,
            },
        );
        decoder.set_transformations(png::Transformations::EXPAND | png::Transformations::STRIP_16);
        let mut reader = decoder
            .read_info()
            .with_context(|| format!("mask {}: not a PNG image", path.display()))?;
        let (w, h) = (reader.info().width as usize, reader.info().height as usize);
        crate::image_io::check_image_size(w, h)
            .with_context(|| format!("mask {}", path.display()))?;
        let mut buf = vec![0; reader.output_buffer_size().unwrap_or(0)];
        let info = reader
            .next_frame(&mut buf)
            .with_context(|| format!("mask {}: truncated or corrupt PNG", path.display()))?;
        let channels = info.color_type.samples();
        let (width, height) = (info.width as usize, info.height as usize);
        let sky = buf[..info.buffer_size()]
            .chunks(channels)
            .map(|p| p[0] >= 128)
            .collect();
        Ok(Self { width, height, sky })
    }

    /// Checks the mask against a frame's size.
    ///
    /// # Errors
    /// When the sizes differ (the message names both files and sizes).
    pub fn check_size(&self, mask: &Path, frame: &Path, width: usize, height: usize) -> Result<()> {
        if (self.width, self.height) != (width, height) {
            bail!(
                "mask {}: {}x{} pixels, but frame {} is {width}x{height}: the mask must have the frames' size",
                mask.display(),
                self.width,
                self.height,
                frame.display()
            );
        }
        Ok(())
    }
}

/// The skyline estimate: `true` where a pixel of the upper hemisphere is sky, from the frame's
/// luminance (row-major, `width` × `height`, the whole sphere). See the module docs.
#[must_use]
pub fn skyline(luminance: &[f32], width: usize, height: usize) -> Vec<bool> {
    let rows = height / 2; // rows above the horizon
    // Row j's elevation is 90° − 180° (j + ½) / height.
    let elevation = |j: usize| {
        #[allow(clippy::cast_precision_loss)]
        let e = 90.0 - 180.0 * (j as f64 + 0.5) / height as f64;
        e
    };
    let reference_rows: Vec<usize> = (0..rows)
        .filter(|&j| (45.0..80.0).contains(&elevation(j)))
        .collect();
    let scan_from = (0..rows).find(|&j| elevation(j) < 45.0).unwrap_or(rows);
    // The first non-sky row of each column (rows if the column is open to the horizon).
    let mut first_blocked = vec![rows; width];
    let mut column = Vec::with_capacity(reference_rows.len());
    for (x, blocked) in first_blocked.iter_mut().enumerate() {
        column.clear();
        column.extend(
            reference_rows
                .iter()
                .map(|&j| luminance[j * width + x])
                .filter(|l| l.is_finite()),
        );
        if column.is_empty() {
            continue;
        }
        let mid = column.len() / 2;
        let reference = *column.select_nth_unstable_by(mid, f32::total_cmp).1;
        let limit = SKYLINE_FRACTION * reference;
        if let Some(j) = (scan_from..rows).find(|&j| luminance[j * width + x] < limit) {
            *blocked = j;
        }
    }
    // Raise by a pixel, widen to the neighbouring columns.
    let mut sky = vec![false; width * height];
    for x in 0..width {
        let lowest = [(x + width - 1) % width, x, (x + 1) % width]
            .iter()
            .map(|&c| first_blocked[c])
            .min()
            .unwrap_or(rows);
        let open = if lowest < rows {
            lowest.saturating_sub(1)
        } else {
            rows
        };
        for j in 0..open {
            sky[j * width + x] = true;
        }
    }
    sky
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn skyline_follows_a_dark_silhouette() {
        let (w, h) = (64, 32);
        // Sky brightening towards the horizon; a wall 4 rows high (rows 12-15) in columns 10-19.
        let lum: Vec<f32> = (0..h)
            .flat_map(|j| (0..w).map(move |x| (x, j)))
            .map(|(x, j)| {
                if j >= 16 {
                    0.01
                } else if (10..20).contains(&x) && j >= 12 {
                    0.02
                } else {
                    1.0 + j as f32 * 0.1
                }
            })
            .collect();
        let sky = skyline(&lum, w, h);
        assert!(sky[5 * w + 15] && sky[10 * w + 15]);
        assert!(!sky[11 * w + 15] && !sky[12 * w + 15] && !sky[13 * w + 15]);
        assert!(sky[15 * w + 30] && !sky[16 * w + 30]);
        // The neighbouring column is widened, the one beyond is open.
        assert!(!sky[11 * w + 9] && sky[13 * w + 8]);
    }
}
