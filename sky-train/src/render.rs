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
    rows(source, width, height, |i, j| {
        let to_u32 = |k: usize| u32::try_from(k).unwrap_or(u32::MAX);
        grid.direction(to_u32(i), to_u32(j))
    })
}

/// Renders `source` into a `width` × `height` image whose pixel (`i`, `j`) looks along
/// `direction(i, j)`, rows in parallel, each row one batch.
fn rows(
    source: &dyn SkySource,
    width: usize,
    height: usize,
    direction: impl Fn(usize, usize) -> Vec3 + Sync,
) -> RgbImage {
    let mut pixels = vec![Vec3::ZERO; width * height];
    pixels
        .par_chunks_mut(width.max(1))
        .enumerate()
        .for_each(|(j, row)| {
            let dirs: Vec<Vec3> = (0..width).map(|i| direction(i, j)).collect();
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

/// A pinhole camera in sky-core's frame (+z up, azimuth from +x towards +y), angles in radians.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Camera {
    /// Azimuth of the view's centre.
    pub azimuth: f32,
    /// Elevation of the view's centre above the horizon.
    pub elevation: f32,
    /// Horizontal field of view, below π.
    pub horizontal_fov: f32,
}

impl Camera {
    /// The direction through the centre of pixel (`i`, `j`) of a `width` × `height` image (rows
    /// from the top), not normalised.
    #[must_use]
    #[allow(clippy::cast_precision_loss)] // pixel counts are far below 2^24
    pub fn direction(&self, i: usize, j: usize, width: usize, height: usize) -> Vec3 {
        let forward =
            sky_core::geom::direction(core::f32::consts::FRAC_PI_2 - self.elevation, self.azimuth);
        let right = forward.cross(Vec3::Z).normalize();
        let up = right.cross(forward);
        let half = (0.5 * self.horizontal_fov).tan();
        let x = (2.0 * (i as f32 + 0.5) / width as f32 - 1.0) * half;
        let y =
            (1.0 - 2.0 * (j as f32 + 0.5) / height as f32) * half * height as f32 / width as f32;
        forward + right * x + up * y
    }
}

/// Renders `source` through `camera` into a `width` × `height` image, rows in parallel.
#[must_use]
pub fn perspective(
    source: &dyn SkySource,
    camera: &Camera,
    width: usize,
    height: usize,
) -> RgbImage {
    rows(source, width, height, |i, j| {
        camera.direction(i, j, width, height)
    })
}

/// The factor that maps the median luminance of the image's non-black pixels to `target`: an
/// exposure that a bright sun in the frame does not darken. 1 for a black image.
#[must_use]
pub fn median_exposure(img: &RgbImage, target: f32) -> f32 {
    let mut lum: Vec<f32> = img
        .pixels
        .iter()
        .map(|p| color::luminance(*p))
        .filter(|l| *l > 0.0)
        .collect();
    if lum.is_empty() {
        return 1.0;
    }
    let mid = lum.len() / 2;
    let (_, median, _) = lum.select_nth_unstable_by(mid, f32::total_cmp);
    target / *median
}
