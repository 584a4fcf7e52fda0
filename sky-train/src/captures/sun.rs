//! Finding the sun in a captured frame (seed 000 §III-D: "the zenith angle of the sun in each
//! image is calculated automatically by finding the pixel with highest color value").
//!
//! A single argmax is only as good as one pixel, and in a real capture the sun is clipped: a
//! plateau of equal values. So the sun is the **centroid of the bright region**: the pixels
//! connected to the brightest one whose luminance is at least half of it, each weighted by its
//! solid angle times its luminance above that threshold (clipped pixels weigh the same, the
//! partly covered pixels at the edge less), summed as unit vectors so that the seam at azimuth
//! 0 / 2π needs no special case. Its angular radius is the farthest pixel centre of the region
//! plus half a pixel diagonal.

use sky_core::Vec3;
use sky_core::geom::{self, Equirect};

/// The sun found in a frame, in the frame's own (camera) coordinates.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SunEstimate {
    /// Unit direction of the centroid.
    pub direction: Vec3,
    /// Zenith angle, radians.
    pub zenith: f64,
    /// Azimuth in the image, radians (sky-core's convention: column 0 at 0, growing with x).
    pub azimuth: f64,
    /// Angular radius of the bright region, radians.
    pub radius: f64,
    /// The brightest luminance over the sky's median luminance.
    pub contrast: f64,
}

/// Why no sun was found.
#[derive(Debug, Clone, PartialEq)]
pub enum NoSun {
    /// The brightest pixel is not much brighter than the sky.
    TooDim {
        /// Brightest over median luminance.
        contrast: f64,
    },
    /// The bright region is too large to be the sun (overcast or overexposed).
    TooLarge {
        /// Its angular radius in degrees.
        radius_deg: f64,
    },
    /// The bright region's centre is below the horizon.
    BelowHorizon,
}

impl std::fmt::Display for NoSun {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::TooDim { contrast } => write!(
                f,
                "no visible sun: the brightest pixel is only {contrast:.1} times the sky's median \
                 (at least {MIN_CONTRAST} expected)"
            ),
            Self::TooLarge { radius_deg } => write!(
                f,
                "no visible sun: the brightest region has a radius of {radius_deg:.1} degrees \
                 (at most {MAX_RADIUS_DEG} expected; overcast or overexposed?)"
            ),
            Self::BelowHorizon => write!(
                f,
                "no visible sun: the brightest region is below the horizon"
            ),
        }
    }
}

/// The brightest pixel must be at least this many times the sky's median luminance.
pub const MIN_CONTRAST: f64 = 25.0;
/// The bright region's angular radius must be at most this, degrees.
pub const MAX_RADIUS_DEG: f64 = 15.0;

/// Finds the sun in `luminance` (row-major over `grid`, the whole sphere), looking at the upper
/// hemisphere only.
///
/// # Errors
/// [`NoSun`] when no sun is visible.
pub fn find(luminance: &[f32], grid: &Equirect) -> Result<SunEstimate, NoSun> {
    let (w, h) = (grid.width() as usize, grid.height() as usize);
    let rows = h.div_ceil(2);
    let sky = &luminance[..rows * w];
    let (mut best, mut peak) = (0, f32::NEG_INFINITY);
    for (i, &l) in sky.iter().enumerate() {
        if l > peak {
            (best, peak) = (i, l);
        }
    }
    let mut sorted: Vec<f32> = sky.iter().copied().filter(|l| l.is_finite()).collect();
    let mid = sorted.len() / 2;
    let median = if sorted.is_empty() {
        0.0
    } else {
        *sorted.select_nth_unstable_by(mid, f32::total_cmp).1
    };
    let contrast = f64::from(peak) / f64::from(median).max(f64::MIN_POSITIVE);
    if contrast.is_nan() || contrast < MIN_CONTRAST {
        return Err(NoSun::TooDim { contrast });
    }
    // Flood fill of the region at or above half the peak, 4-connected, wrapping in azimuth.
    let threshold = 0.5 * peak;
    let mut inside = vec![false; rows * w];
    let mut stack = vec![best];
    inside[best] = true;
    let mut sum = [0.0f64; 3];
    let mut region = Vec::new();
    while let Some(p) = stack.pop() {
        region.push(p);
        let (x, y) = (p % w, p / w);
        let dir = pixel_direction(grid, x, y);
        let weight = f64::from(grid.solid_angle(to_u32(y))) * f64::from(sky[p] - threshold);
        for c in 0..3 {
            sum[c] += weight * f64::from(dir[c]);
        }
        let mut visit = |q: usize| {
            if !inside[q] && sky[q] >= threshold {
                inside[q] = true;
                stack.push(q);
            }
        };
        visit(y * w + (x + 1) % w);
        visit(y * w + (x + w - 1) % w);
        if y > 0 {
            visit(p - w);
        }
        if y + 1 < rows {
            visit(p + w);
        }
    }
    let norm = (sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2]).sqrt();
    #[allow(clippy::cast_possible_truncation)]
    let direction = Vec3::new(
        (sum[0] / norm) as f32,
        (sum[1] / norm) as f32,
        (sum[2] / norm) as f32,
    );
    let pixel = std::f64::consts::PI / f64::from(grid.height());
    let radius = region
        .iter()
        .map(|&p| {
            f64::from(geom::angle_between(
                direction,
                pixel_direction(grid, p % w, p / w),
            ))
        })
        .fold(0.0, f64::max)
        + pixel * std::f64::consts::FRAC_1_SQRT_2;
    if radius.to_degrees() > MAX_RADIUS_DEG {
        return Err(NoSun::TooLarge {
            radius_deg: radius.to_degrees(),
        });
    }
    if direction.z <= 0.0 {
        return Err(NoSun::BelowHorizon);
    }
    let (zenith, azimuth) = geom::zenith_azimuth(direction);
    Ok(SunEstimate {
        direction,
        zenith: f64::from(zenith),
        azimuth: f64::from(azimuth),
        radius,
        contrast,
    })
}

fn to_u32(k: usize) -> u32 {
    u32::try_from(k).unwrap_or(u32::MAX)
}

/// The direction through the centre of pixel (`x`, `y`).
pub(crate) fn pixel_direction(grid: &Equirect, x: usize, y: usize) -> Vec3 {
    grid.direction(to_u32(x), to_u32(y))
}

#[cfg(test)]
mod tests {
    use super::*;
    use sky_core::geom::Extent;

    /// A dim sky with a clipped disc of radius 3° at a known position between pixel centres.
    #[test]
    fn centroid_of_a_clipped_disc_is_sub_pixel_accurate() {
        let grid = Equirect::new(256, 128, Extent::Sphere).expect("grid");
        let sun = geom::direction(1.0, 2.0);
        let lum: Vec<f32> = (0..128u32)
            .flat_map(|y| (0..256u32).map(move |x| (x, y)))
            .map(|(x, y)| {
                let a = geom::angle_between(grid.direction(x, y), sun);
                if a < 3f32.to_radians() { 1000.0 } else { 1.0 }
            })
            .collect();
        let found = find(&lum, &grid).expect("sun");
        let err = geom::angle_between(found.direction, sun).to_degrees();
        // A pixel is 1.4°: the centroid must do much better than the argmax.
        assert!(err < 0.35, "{err} degrees off");
        assert!((found.radius.to_degrees() - 3.0).abs() < 1.5);
    }

    #[test]
    fn a_sky_without_a_bright_spot_has_no_sun() {
        let grid = Equirect::new(64, 32, Extent::Sphere).expect("grid");
        let lum: Vec<f32> = (0..64 * 32).map(|i| 1.0 + (i % 7) as f32).collect();
        assert!(matches!(find(&lum, &grid), Err(NoSun::TooDim { .. })));
    }
}
