//! Rendering a sky source to images.

use rayon::prelude::*;
use sky_core::Vec3;
use sky_core::color;
use sky_core::geom::Equirect;

use crate::image_io::RgbImage;
use crate::sources::SkySource;

/// Renders `source` over the equirectangular `grid`, rows in parallel.
#[must_use]
pub fn equirect(source: &dyn SkySource, grid: &Equirect) -> RgbImage {
    let (width, height) = (grid.width() as usize, grid.height() as usize);
    let mut pixels = vec![Vec3::ZERO; width * height];
    pixels
        .par_chunks_mut(width)
        .zip(0..grid.height())
        .for_each(|(row, j)| {
            let dirs: Vec<Vec3> = (0..grid.width()).map(|i| grid.direction(i, j)).collect();
            source.rgb_batch(&dirs, row);
        });
    RgbImage {
        width,
        height,
        pixels,
    }
}

/// The factor that maps the image's mean luminance above the horizon, weighted by solid angle,
/// to middle grey (0.18): the automatic exposure of PNG output. 1 for a black image.
#[must_use]
pub fn auto_exposure(img: &RgbImage, grid: &Equirect) -> f32 {
    let (mut sum, mut weight) = (0.0f64, 0.0f64);
    for (j, row) in img.pixels.chunks(img.width).enumerate() {
        let j = u32::try_from(j).unwrap_or(u32::MAX);
        if grid.zenith(j) > core::f32::consts::FRAC_PI_2 {
            break;
        }
        let w = f64::from(grid.solid_angle(j));
        for p in row {
            sum += w * f64::from(color::luminance(*p).max(0.0));
            weight += w;
        }
    }
    let mean = if weight > 0.0 { sum / weight } else { 0.0 };
    #[allow(clippy::cast_possible_truncation)]
    if mean > 0.0 {
        (0.18 / mean) as f32
    } else {
        1.0
    }
}
