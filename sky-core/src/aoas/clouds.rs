//! Cloud shapes (seed 004, §3.3 "Cloud Shape for the Sky Pattern"): clouds drawn around
//! user-given sparse points or polylines, fading out linearly with the distance from them.

use glam::Vec3;

use crate::error::{SkyError, check_range};
use crate::math;

/// The largest cloud radius and fade width accepted, in radians.
pub const MAX_CLOUD_ANGLE: f32 = core::f32::consts::FRAC_PI_2;
/// The smallest fade width accepted, in radians (0.06°): the fade divides by it.
pub const MIN_CLOUD_FADE: f32 = 1e-3;

/// One straight piece of a cloud: a segment between two points of the unit sphere around the
/// viewer (a point cloud is a segment of length 0), with its radius and fade.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Segment {
    start: Vec3,
    /// end − start.
    along: Vec3,
    /// 1 / |end − start|², or 0 for a point.
    inv_len2: f32,
    /// Chord distance at which the density reaches 0.
    outer: f32,
    /// 1 / (outer − inner), with inner the chord of the radius.
    inv_fade: f32,
}

impl Segment {
    /// The cloud density at the unit direction `p`: 1 within the radius, falling linearly to 0 at
    /// radius + fade, distances measured as chords of the unit sphere. Branch-free.
    #[inline(always)]
    fn density(&self, p: Vec3) -> f32 {
        let rel = p - self.start;
        #[allow(clippy::manual_clamp)] // clamp would pass NaN through
        let t = (rel.dot(self.along) * self.inv_len2).max(0.0).min(1.0);
        let dist = math::sqrt_kernel((rel - self.along * t).length_squared());
        #[allow(clippy::manual_clamp)]
        let density = ((self.outer - dist) * self.inv_fade).max(0.0).min(1.0);
        density
    }
}

/// Clouds drawn around points and polylines on the sky, in a fixed-capacity collection (no
/// allocation): at most [`CloudShapes::CAPACITY`] segments, where a point takes one segment and a
/// polyline of n points n − 1.
///
/// Each cloud has a `radius` within which it is fully dense and a `fade` over which its density
/// falls linearly to 0 (seed 004 §3.3: "based on distance to a particular point or spline, using
/// linear interpolation to fade out with distance"). Angles are in radians, measured from the
/// viewer as chords of the unit sphere: exact for points; a segment spanning an angle L is the
/// straight chord between its ends, which passes inside the sphere by up to 1 − cos(L/2) (0.001
/// for L = 5°), so draw curves with short segments. Where clouds overlap the densest counts. The sky under a cloud of density ρ keeps its
/// brightness (HSV value) and loses the fraction ρ of its saturation, as the noise clouds do
/// (eq. 8).
///
/// ```
/// use sky_core::aoas::CloudShapes;
/// use sky_core::{geom, SkyError};
///
/// let mut clouds = CloudShapes::new();
/// clouds.push_point(geom::direction(0.8, 1.0), 0.05, 0.05)?;
/// let line = [geom::direction(1.0, 0.0), geom::direction(1.0, 0.3), geom::direction(0.9, 0.6)];
/// clouds.push_polyline(&line, 0.02, 0.04)?;
/// assert_eq!(clouds.len(), 3);
/// // Too many points: a typed error, and nothing is added.
/// let many = [geom::direction(1.0, 0.0); CloudShapes::CAPACITY];
/// assert!(matches!(clouds.push_polyline(&many, 0.02, 0.04), Err(SkyError::CapacityExceeded { .. })));
/// assert_eq!(clouds.len(), 3);
/// # Ok::<(), SkyError>(())
/// ```
#[derive(Debug, Clone, PartialEq, Default)]
pub struct CloudShapes {
    segments: heapless::Vec<Segment, { CloudShapes::CAPACITY }>,
}

impl CloudShapes {
    /// The most segments the collection holds.
    pub const CAPACITY: usize = 64;

    /// No clouds.
    #[must_use]
    pub const fn new() -> Self {
        Self {
            segments: heapless::Vec::new(),
        }
    }

    /// The number of segments held.
    #[must_use]
    pub fn len(&self) -> usize {
        self.segments.len()
    }

    /// Whether there are no clouds.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.segments.is_empty()
    }

    /// Removes every cloud.
    pub fn clear(&mut self) {
        self.segments.clear();
    }

    /// Adds a round cloud centred on the direction `at` (any length but 0).
    ///
    /// # Errors
    /// As [`push_polyline`](Self::push_polyline).
    pub fn push_point(&mut self, at: Vec3, radius: f32, fade: f32) -> Result<(), SkyError> {
        self.push_polyline(&[at], radius, fade)
    }

    /// Adds a cloud along the polyline through `points` (directions of any length but 0); one
    /// point makes a round cloud. Either every segment is added or none.
    ///
    /// # Errors
    /// [`SkyError::OutOfRange`] for no points, a zero-length point, a radius outside
    /// [0, [`MAX_CLOUD_ANGLE`]] or a fade outside [[`MIN_CLOUD_FADE`], [`MAX_CLOUD_ANGLE`]];
    /// [`SkyError::NotFinite`] for a point with a NaN or infinite component;
    /// [`SkyError::CapacityExceeded`] when the segments would not fit.
    pub fn push_polyline(
        &mut self,
        points: &[Vec3],
        radius: f32,
        fade: f32,
    ) -> Result<(), SkyError> {
        #[allow(clippy::cast_precision_loss)] // small counts
        if points.is_empty() {
            return Err(SkyError::OutOfRange {
                parameter: "clouds.points (count)",
                value: 0.0,
                min: 1.0,
                max: (Self::CAPACITY + 1) as f32,
            });
        }
        let radius = check_range("clouds.radius [rad]", radius, 0.0, MAX_CLOUD_ANGLE)?;
        let fade = check_range("clouds.fade [rad]", fade, MIN_CLOUD_FADE, MAX_CLOUD_ANGLE)?;
        for p in points {
            if !p.is_finite() {
                return Err(SkyError::NotFinite {
                    parameter: "clouds.points",
                });
            }
            let len = p.length();
            if !(len >= f32::MIN_POSITIVE && len.is_finite()) {
                return Err(SkyError::OutOfRange {
                    parameter: "clouds.points (length)",
                    value: len,
                    min: f32::MIN_POSITIVE,
                    max: f32::MAX,
                });
            }
        }
        let needed = self.len() + points.len().saturating_sub(1).max(1);
        if needed > Self::CAPACITY {
            return Err(SkyError::CapacityExceeded {
                collection: "cloud segments",
                capacity: Self::CAPACITY,
                needed,
            });
        }
        // Chord of an angle a on the unit sphere: 2 sin(a/2).
        let chord = |a: f32| 2.0 * math::sin(0.5 * a);
        let inner = chord(radius);
        let outer = chord(radius + fade);
        let inv_fade = 1.0 / (outer - inner);
        let unit = |p: &Vec3| *p / p.length();
        let ends = points.windows(2).map(|w| (unit(&w[0]), unit(&w[1])));
        let single = (points.len() == 1).then(|| (unit(&points[0]), unit(&points[0])));
        for (start, end) in ends.chain(single) {
            let along = end - start;
            let len2 = along.length_squared();
            let segment = Segment {
                start,
                along,
                inv_len2: if len2 > 0.0 { 1.0 / len2 } else { 0.0 },
                outer,
                inv_fade,
            };
            // Cannot fail: the capacity was checked above.
            let _ = self.segments.push(segment);
        }
        Ok(())
    }

    /// The cloud density in [0, 1] towards the unit direction `dir` (the densest cloud there).
    #[inline(always)]
    pub(crate) fn density(&self, dir: Vec3) -> f32 {
        self.segments
            .iter()
            .fold(0.0f32, |d, s| d.max(s.density(dir)))
    }

    /// Raises each `density[k]` to the density of the clouds towards `(x[k], y[k], z[k])`, one
    /// segment at a time over all lanes (the same operations, in the same order, as
    /// [`density`](Self::density), so that the results agree bit for bit; this order vectorises).
    #[inline(always)]
    pub(crate) fn density_lanes<const N: usize>(
        &self,
        x: &[f32; N],
        y: &[f32; N],
        z: &[f32; N],
        density: &mut [f32; N],
    ) {
        for s in &self.segments {
            for k in 0..N {
                density[k] = density[k].max(s.density(Vec3::new(x[k], y[k], z[k])));
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::direction;

    #[test]
    fn point_cloud_fades_linearly_with_angle() {
        let mut c = CloudShapes::new();
        let centre = direction(0.7, 0.2);
        c.push_point(centre * 3.0, 0.1, 0.2).expect("valid");
        // Along a great circle away from the centre: density 1 up to 0.1 rad, then linear in the
        // chord to 0 at 0.3 rad.
        for k in 0..=40 {
            let a = k as f32 * 0.01;
            let d = direction(0.7 + a, 0.2);
            let chord = |x: f32| 2.0 * libm::sinf(0.5 * x);
            let want = ((chord(0.3) - chord(a)) / (chord(0.3) - chord(0.1))).clamp(0.0, 1.0);
            let got = c.density(d);
            assert!((got - want).abs() < 2e-5, "{a} rad: {got}, want {want}");
        }
    }

    #[test]
    fn polyline_covers_its_segments() {
        let mut c = CloudShapes::new();
        let pts = [
            direction(1.0, 0.0),
            direction(1.0, 0.4),
            direction(0.6, 0.4),
        ];
        c.push_polyline(&pts, 0.02, 0.05).expect("valid");
        assert_eq!(c.len(), 2);
        assert_eq!(c.density(direction(1.0, 0.2)), 1.0, "on the first segment");
        assert_eq!(c.density(direction(0.8, 0.4)), 1.0, "on the second segment");
        assert_eq!(c.density(direction(0.3, 2.0)), 0.0, "far away");
    }

    #[test]
    fn bad_clouds_are_typed_errors_and_add_nothing() {
        let mut c = CloudShapes::new();
        let p = direction(0.5, 0.5);
        let range = |e: Result<(), SkyError>, name: &str| match e {
            Err(SkyError::OutOfRange { parameter, .. }) => assert_eq!(parameter, name),
            other => panic!("{name}: {other:?}"),
        };
        range(c.push_point(p, -0.1, 0.1), "clouds.radius [rad]");
        range(c.push_point(p, 2.0, 0.1), "clouds.radius [rad]");
        range(c.push_point(p, f32::NAN, 0.1), "clouds.radius [rad]");
        range(c.push_point(p, 0.1, 0.0), "clouds.fade [rad]");
        range(c.push_point(p, 0.1, 1.6), "clouds.fade [rad]");
        range(c.push_point(Vec3::ZERO, 0.1, 0.1), "clouds.points (length)");
        range(c.push_polyline(&[], 0.1, 0.1), "clouds.points (count)");
        assert_eq!(
            c.push_point(Vec3::new(f32::NAN, 0.0, 1.0), 0.1, 0.1),
            Err(SkyError::NotFinite {
                parameter: "clouds.points"
            })
        );
        assert!(c.is_empty());
        for _ in 0..CloudShapes::CAPACITY {
            c.push_point(p, 0.1, 0.1).expect("fits");
        }
        assert_eq!(
            c.push_point(p, 0.1, 0.1),
            Err(SkyError::CapacityExceeded {
                collection: "cloud segments",
                capacity: CloudShapes::CAPACITY,
                needed: CloudShapes::CAPACITY + 1,
            })
        );
        assert_eq!(c.len(), CloudShapes::CAPACITY);
    }

    #[test]
    fn lanes_agree_with_one_direction() {
        let mut c = CloudShapes::new();
        c.push_polyline(&[direction(1.0, 0.0), direction(0.9, 0.5)], 0.03, 0.1)
            .expect("valid");
        c.push_point(direction(0.4, 2.0), 0.1, 0.2).expect("valid");
        let dirs: [Vec3; 8] =
            core::array::from_fn(|k| direction(0.3 + 0.1 * k as f32, 0.3 * k as f32));
        let mut density = [0.0; 8];
        c.density_lanes(
            &dirs.map(|d| d.x),
            &dirs.map(|d| d.y),
            &dirs.map(|d| d.z),
            &mut density,
        );
        for (d, got) in dirs.iter().zip(density) {
            assert_eq!(got.to_bits(), c.density(*d).to_bits());
        }
    }
}
