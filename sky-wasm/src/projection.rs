//! The pixel grids the demo draws: an equal-area fisheye of the upper hemisphere and an
//! equirectangular panorama. Directions follow sky-core's conventions (+z up, +x east, +y north).

use sky_core::geom::{Equirect, Extent};
use sky_core::{SkyError, Vec3};

/// The image shapes a [`Projection`] can have.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// The upper hemisphere in the disc inscribed in the image, seen from below like an all-sky
    /// camera or a sky chart: the zenith in the centre, the horizon on the rim, north (+y) up and
    /// east (+x) left. Lambert's azimuthal equal-area projection scaled so that the horizon lies
    /// on the rim: a point at distance ρ (the rim at 1) from the centre has zenith angle θ with
    /// ρ = √2 sin(θ/2), so cos θ = 1 − ρ² and sin θ = ρ √(2 − ρ²). Every pixel covers the same
    /// solid angle, π/(disc area in pixels) steradians, and no trigonometry is needed per pixel.
    Fisheye,
    /// The upper hemisphere as sky-core's [`Equirect`] grid: azimuth 0 to 2π from left to right,
    /// zenith angle 0 (top) to π/2 (bottom).
    Panorama,
    /// The unit normals of a sphere filling the image (the disc inscribed in it), seen from the
    /// south looking north: image right is east (+x), image up is the zenith (+z); the visible
    /// hemisphere faces south (−y).
    Sphere,
}

/// The view directions of an image's pixels: computed once, reused for every frame.
#[derive(Debug, Clone)]
pub struct Projection {
    kind: Kind,
    width: u32,
    height: u32,
    /// Unit view direction of each pixel that shows the sky.
    directions: Vec<Vec3>,
    /// The pixel index (row-major) of each direction.
    pixels: Vec<u32>,
}

impl Projection {
    /// A `width` × `height` image of kind `kind`.
    ///
    /// # Errors
    /// [`SkyError::OutOfRange`] when `width` or `height` is 0 or above [`Self::MAX_SIZE`].
    pub fn new(kind: Kind, width: u32, height: u32) -> Result<Self, SkyError> {
        let sizes = [("image width [px]", width), ("image height [px]", height)];
        if let Some((parameter, value)) = sizes
            .into_iter()
            .find(|&(_, v)| !(1..=Self::MAX_SIZE).contains(&v))
        {
            #[allow(clippy::cast_precision_loss)] // only printed
            let (value, max) = (value as f32, Self::MAX_SIZE as f32);
            return Err(SkyError::OutOfRange {
                parameter,
                value,
                min: 1.0,
                max,
            });
        }
        let grid = Equirect::new(width, height, Extent::UpperHemisphere)?;
        let mut p = Self {
            kind,
            width,
            height,
            directions: Vec::new(),
            pixels: Vec::new(),
        };
        match kind {
            Kind::Fisheye => p.fill_disc(|u, v, rho2| {
                let s = (2.0 - rho2).sqrt();
                // East (+x) to the left of the image: x = −u.
                Vec3::new(-u * s, v * s, 1.0 - rho2)
            }),
            Kind::Sphere => p.fill_disc(|u, v, rho2| Vec3::new(u, -(1.0 - rho2).sqrt(), v)),
            Kind::Panorama => p.fill_panorama(&grid),
        }
        Ok(p)
    }

    /// The largest width or height accepted (a 4096 × 4096 image is 64 MB of RGBA).
    pub const MAX_SIZE: u32 = 4096;

    /// The pixels of the disc inscribed in the image, each with the direction `f(u, v, ρ²)` of
    /// its centre's coordinates (u right, v up, the rim at ρ = 1).
    #[allow(clippy::cast_precision_loss)] // pixel coordinates below 2^12: exact
    fn fill_disc(&mut self, f: impl Fn(f32, f32, f32) -> Vec3) {
        let (w, h) = (self.width as f32, self.height as f32);
        let radius = 0.5 * w.min(h);
        for j in 0..self.height {
            let v = (0.5 * h - (j as f32 + 0.5)) / radius;
            for i in 0..self.width {
                let u = (i as f32 + 0.5 - 0.5 * w) / radius;
                let rho2 = u * u + v * v;
                if rho2 <= 1.0 {
                    self.directions.push(f(u, v, rho2));
                    self.pixels.push(j * self.width + i);
                }
            }
        }
    }

    fn fill_panorama(&mut self, grid: &Equirect) {
        for j in 0..self.height {
            for i in 0..self.width {
                self.directions.push(grid.direction(i, j));
                self.pixels.push(j * self.width + i);
            }
        }
    }

    /// The image's shape.
    #[must_use]
    pub fn kind(&self) -> Kind {
        self.kind
    }

    /// Image width and height in pixels.
    #[must_use]
    pub fn size(&self) -> (u32, u32) {
        (self.width, self.height)
    }

    /// Number of pixels in the image.
    #[must_use]
    pub fn pixel_count(&self) -> usize {
        self.width as usize * self.height as usize
    }

    /// The unit view direction of each pixel that shows the sky.
    #[must_use]
    pub fn directions(&self) -> &[Vec3] {
        &self.directions
    }

    /// The row-major pixel index of each of [`directions`](Self::directions).
    #[must_use]
    pub fn pixels(&self) -> &[u32] {
        &self.pixels
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fisheye_directions_are_unit_and_cover_the_hemisphere() {
        let p = Projection::new(Kind::Fisheye, 64, 48).expect("valid size");
        let n = p.directions().len();
        // The inscribed disc of radius 24 px holds about π 24² pixels.
        let disc = core::f32::consts::PI * 24.0 * 24.0;
        #[allow(clippy::cast_precision_loss)]
        let ratio = n as f32 / disc;
        assert!((ratio - 1.0).abs() < 0.02, "{n} pixels vs disc {disc}");
        for d in p.directions() {
            assert!((d.length() - 1.0).abs() < 1e-6, "{d}");
            assert!(d.z >= 0.0, "{d}");
        }
    }

    #[test]
    fn fisheye_is_a_sky_chart_and_equal_area() {
        let p = Projection::new(Kind::Fisheye, 101, 101).expect("valid size");
        let at = |i: u32, j: u32| {
            let k = p.pixels().iter().position(|&q| q == j * 101 + i);
            p.directions()[k.expect("inside the disc")]
        };
        assert!(at(50, 50).z > 0.9999, "centre is the zenith");
        assert!(
            at(50, 0).y > 0.99 * at(50, 0).length() - 0.2,
            "top is north"
        );
        assert!(at(0, 50).x > 0.95, "left is east");
        // Equal area: the fraction of pixels within zenith angle θ is 1 − cos θ (the
        // hemisphere's solid angle fraction), e.g. 0.5 within 60°.
        let within = p.directions().iter().filter(|d| d.z >= 0.5).count();
        #[allow(clippy::cast_precision_loss)]
        let fraction = within as f32 / p.directions().len() as f32;
        assert!((fraction - 0.5).abs() < 0.01, "{fraction}");
    }

    #[test]
    fn sphere_normals_face_the_viewer() {
        let p = Projection::new(Kind::Sphere, 33, 33).expect("valid size");
        let centre = p.pixels().iter().position(|&q| q == 16 * 33 + 16);
        let n = p.directions()[centre.expect("inside")];
        assert!(n.y < -0.999, "the centre faces south: {n}");
        for d in p.directions() {
            assert!((d.length() - 1.0).abs() < 1e-5 && d.y <= 0.0, "{d}");
        }
    }

    #[test]
    fn panorama_rows_run_from_the_zenith_to_the_horizon() {
        let p = Projection::new(Kind::Panorama, 64, 16).expect("valid size");
        assert_eq!(p.directions().len(), 64 * 16);
        assert!(p.directions()[0].z > 0.99, "top row near the zenith");
        assert!(
            p.directions()[63 * 16].z < 0.05,
            "bottom row near the horizon"
        );
    }

    #[test]
    fn sizes_out_of_range_are_errors_naming_the_parameter() {
        for (w, h) in [(0, 4), (4, 0), (4097, 4)] {
            let e = Projection::new(Kind::Fisheye, w, h).expect_err("invalid size");
            assert!(e.to_string().contains("width") || e.to_string().contains("height"));
        }
    }
}
