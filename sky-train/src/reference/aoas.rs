//! The single-scattering sky of seed 004 in f64, two ways:
//!
//! * [`SingleScattering::exact`]: the in-scattering integral of Nishita et al. (seed 004 eq. 4)
//!   computed by brute force: the optical depths towards the sun and back to the viewer
//!   integrated numerically along their rays (composite Simpson), the planet's shadow included
//!   (a sun ray that meets the planet carries no light), many points on the view ray. This is
//!   what O'Neil's approximation approximates.
//! * [`SingleScattering::o_neil`]: O'Neil's approximation ("Accurate Atmospheric Scattering",
//!   GPU Gems 2 ch. 16) in f64: the optical depths from his fitted scale function, `samples`
//!   midpoints on the view ray. sky-core's f32 `AoasSky` computes the same thing.
//!
//! Comparing the two measures what the scale function and the sample count cost; comparing
//! sky-core with [`SingleScattering::o_neil`] measures sky-core's f32 implementation.
//!
//! Written from O'Neil's chapter and seed 004's eqs. 1-4, independently of sky-core: no code or
//! types are shared. Lengths are in atmosphere thicknesses: the planet's radius is 40 (O'Neil's
//! 10 / (10.25 − 10), seed 004's r), the atmosphere's outer radius 41, the scale depth 0.25.
//! Directions are `[x, y, z]` with +z up.

use std::f64::consts::PI;

/// The planet's radius in atmosphere thicknesses.
pub const PLANET_RADIUS: f64 = 40.0;
/// The atmosphere's outer radius.
pub const OUTER_RADIUS: f64 = 41.0;
/// The density scale height.
pub const SCALE_DEPTH: f64 = 0.25;

type V3 = [f64; 3];

fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn add_scaled(a: V3, b: V3, s: f64) -> V3 {
    [a[0] + b[0] * s, a[1] + b[1] * s, a[2] + b[2] * s]
}

fn norm(a: V3) -> f64 {
    dot(a, a).sqrt()
}

fn unit(a: V3) -> V3 {
    let n = norm(a);
    [a[0] / n, a[1] / n, a[2] / n]
}

/// The distance along the unit direction `d` from `p` (inside the sphere of radius `radius`) to
/// that sphere.
fn exit_distance(p: V3, d: V3, radius: f64) -> f64 {
    let b = dot(p, d);
    let c = dot(p, p) - radius * radius; // ≤ 0 inside
    -b + (b * b - c).sqrt()
}

/// Whether the ray from `p` along `d` meets the planet.
fn hits_planet(p: V3, d: V3) -> bool {
    let b = dot(p, d);
    let c = dot(p, p) - PLANET_RADIUS * PLANET_RADIUS;
    b < 0.0 && b * b - c > 0.0
}

/// The density at `p` relative to the ground's.
fn density(p: V3) -> f64 {
    (-(norm(p) - PLANET_RADIUS) / SCALE_DEPTH).exp()
}

/// The optical depth (density integrated over length, thicknesses) from `p` to space along the
/// unit direction `d`, by composite Simpson with `intervals` (even) intervals; infinite when
/// the ray meets the planet.
fn optical_depth_to_space(p: V3, d: V3, intervals: usize) -> f64 {
    if hits_planet(p, d) {
        return f64::INFINITY;
    }
    let length = exit_distance(p, d, OUTER_RADIUS);
    let h = length / intervals as f64;
    let sum: f64 = (0..=intervals)
        .map(|j| simpson_weight(j, intervals) * density(add_scaled(p, d, h * j as f64)))
        .sum();
    sum * h / 3.0
}

/// The weight of point `j` of `intervals` (even) in the composite Simpson rule, before the
/// factor h/3: 1, 4, 2, 4, …, 2, 4, 1.
fn simpson_weight(j: usize, intervals: usize) -> f64 {
    if j == 0 || j == intervals {
        1.0
    } else if j % 2 == 1 {
        4.0
    } else {
        2.0
    }
}

/// O'Neil's fitted optical depth from the ground to space at angle θ from the vertical, in
/// thicknesses: 0.25 · exp(−0.00287 + x(0.459 + x(3.83 + x(−6.80 + 5.25 x)))), x = 1 − cos θ.
pub fn o_neil_scale(cos: f64) -> f64 {
    let x = 1.0 - cos;
    0.25 * (-0.00287 + x * (0.459 + x * (3.83 + x * (-6.80 + x * 5.25)))).exp()
}

/// The accuracy of the brute-force integral: Simpson intervals along the view ray and along
/// each sun ray.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Quadrature {
    /// Intervals along the view ray (even).
    pub view: usize,
    /// Intervals along each sun ray (even).
    pub light: usize,
}

impl Quadrature {
    /// The default: converged to about 1e-6 relative (tested by doubling both).
    pub const FINE: Self = Self {
        view: 160,
        light: 64,
    };
}

/// One sky: O'Neil's parameters in f64.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SingleScattering {
    /// Rayleigh constant Kr.
    pub kr: f64,
    /// Mie constant Km.
    pub km: f64,
    /// Sun intensity ESun.
    pub sun_intensity: f64,
    /// Mie asymmetry g, with cos θ = view · sun (forward scattering for g > 0).
    pub mie_g: f64,
    /// Per channel Rayleigh factor: 1/λ⁴ (λ in µm), or a sky hue.
    pub rayleigh: [f64; 3],
    /// Unit direction towards the sun.
    pub sun: V3,
    /// The viewer in skydome space (thicknesses), seed 004's Pvs.
    pub viewer: V3,
}

impl SingleScattering {
    /// O'Neil's parameters (Kr 0.0025, Km 0.0010, ESun 20, g 0.99 in this sign convention,
    /// wavelengths 650, 570, 475 nm), the viewer on the ground, the sun at `sun` (unit).
    #[must_use]
    pub fn o_neil_defaults(sun: V3) -> Self {
        Self {
            kr: 0.0025,
            km: 0.0010,
            sun_intensity: 20.0,
            mie_g: 0.99,
            rayleigh: [0.650_f64, 0.570, 0.475].map(|l: f64| 1.0 / l.powi(4)),
            sun: unit(sun),
            viewer: [0.0; 3],
        }
    }

    /// Seed 004 eq. 2: the viewer in Earth space, Pv = Pvs + r (Pvs − O)/|Pvs − O|, with the
    /// apex +z for Pvs = O.
    #[must_use]
    pub fn viewer_in_earth_space(&self) -> V3 {
        let n = norm(self.viewer);
        let apex = if n > 0.0 {
            unit(self.viewer)
        } else {
            [0.0, 0.0, 1.0]
        };
        add_scaled(self.viewer, apex, PLANET_RADIUS)
    }

    /// The Rayleigh phase function 0.75 (1 + cos²) and O'Neil's Mie phase function
    /// 1.5 (1 − g²)/(2 + g²) (1 + cos²)/(1 + g² − 2 g cos)^1.5, at cos = view · sun.
    fn phases(&self, cos: f64) -> (f64, f64) {
        let g = self.mie_g;
        let rayleigh = 0.75 * (1.0 + cos * cos);
        let mie = 1.5 * (1.0 - g * g) / (2.0 + g * g) * (1.0 + cos * cos)
            / (1.0 + g * g - 2.0 * g * cos).powf(1.5);
        (rayleigh, mie)
    }

    /// Extinction per unit optical depth per channel: 4π (Kr K + Km).
    fn extinction(&self) -> [f64; 3] {
        self.rayleigh.map(|k| 4.0 * PI * (self.kr * k + self.km))
    }

    /// Turns ∫ρ e^{−β τ} per channel into the colour: ESun (Kr K F_R + Km F_M).
    fn colour(&self, cos: f64, integral: [f64; 3]) -> [f64; 3] {
        let (fr, fm) = self.phases(cos);
        let mut out = [0.0; 3];
        for c in 0..3 {
            out[c] =
                self.sun_intensity * integral[c] * (self.kr * self.rayleigh[c] * fr + self.km * fm);
        }
        out
    }

    /// The view direction made unit, or `None` below the viewer's horizon (views within 1e-6
    /// in cos θ below it count as on it, as in sky-core: the f32 nearest π/2 lies just below).
    fn view(&self, dir: V3) -> Option<V3> {
        let d = unit(dir);
        let pv = self.viewer_in_earth_space();
        (dot(d, unit(pv)) >= -1e-6).then_some(d)
    }

    /// The exact single-scattering sky towards `dir` (eq. 4), linear RGB in O'Neil's units;
    /// black below the viewer's horizon.
    #[must_use]
    pub fn exact(&self, dir: V3, q: Quadrature) -> [f64; 3] {
        let Some(d) = self.view(dir) else {
            return [0.0; 3];
        };
        let pv = self.viewer_in_earth_space();
        let length = exit_distance(pv, d, OUTER_RADIUS);
        let n = q.view;
        let h = length / n as f64;
        let rho: Vec<f64> = (0..=n)
            .map(|j| density(add_scaled(pv, d, h * j as f64)))
            .collect();
        // The optical depth back to the viewer at every grid point: Simpson over pairs of
        // intervals, and for odd points the first half of a pair by the three-point rule
        // h/12 (5 f0 + 8 f1 − f2), also exact for quadratics.
        let mut to_viewer = vec![0.0; n + 1];
        for j in (0..n).step_by(2) {
            let (a, b, c) = (rho[j], rho[j + 1], rho[j + 2]);
            to_viewer[j + 1] = to_viewer[j] + h / 12.0 * (5.0 * a + 8.0 * b - c);
            to_viewer[j + 2] = to_viewer[j] + h / 3.0 * (a + 4.0 * b + c);
        }
        let beta = self.extinction();
        let mut integral = [0.0; 3];
        for j in 0..=n {
            let p = add_scaled(pv, d, h * j as f64);
            let tau = to_viewer[j] + optical_depth_to_space(p, self.sun, q.light);
            let w = simpson_weight(j, n);
            for c in 0..3 {
                integral[c] += w * rho[j] * (-beta[c] * tau).exp();
            }
        }
        self.colour(dot(d, self.sun), integral.map(|i| i * h / 3.0))
    }

    /// O'Neil's approximation towards `dir` with `samples` midpoints (GPU Gems 2 ch. 16, "sky
    /// from atmosphere"), in f64; black below the viewer's horizon.
    #[must_use]
    pub fn o_neil(&self, dir: V3, samples: usize) -> [f64; 3] {
        let Some(d) = self.view(dir) else {
            return [0.0; 3];
        };
        let pv = self.viewer_in_earth_space();
        let camera_height = norm(pv);
        let far = exit_distance(pv, d, OUTER_RADIUS);
        let depth = |height: f64| ((PLANET_RADIUS - height) / SCALE_DEPTH).exp();
        let start_offset = depth(camera_height) * o_neil_scale(dot(d, pv) / camera_height);
        let step = far / samples as f64;
        let beta = self.extinction();
        let mut integral = [0.0; 3];
        for i in 0..samples {
            let p = add_scaled(pv, d, step * (i as f64 + 0.5));
            let height = norm(p);
            let light_angle = dot(self.sun, p) / height;
            let camera_angle = dot(d, p) / height;
            let scatter = start_offset
                + depth(height) * (o_neil_scale(light_angle) - o_neil_scale(camera_angle));
            for c in 0..3 {
                integral[c] += (-scatter * beta[c]).exp() * depth(height) * step;
            }
        }
        self.colour(dot(d, self.sun), integral)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn direction(zenith_deg: f64, azimuth_deg: f64) -> V3 {
        let (t, p) = (zenith_deg.to_radians(), azimuth_deg.to_radians());
        [t.sin() * p.cos(), t.sin() * p.sin(), t.cos()]
    }

    fn rel(a: [f64; 3], b: [f64; 3]) -> f64 {
        (0..3).fold(0.0, |m, c| m.max((a[c] - b[c]).abs() / b[c].abs()))
    }

    #[test]
    fn the_fit_approximates_the_integrated_optical_depth() {
        // O'Neil's fit is the optical depth from the ground to space: check it against the
        // numerical integral for angles 0-80° (within his "few percent"; worst near 90°).
        let ground = [0.0, 0.0, PLANET_RADIUS];
        for deg in [0.0, 30.0, 60.0, 80.0] {
            let d = direction(deg, 0.0);
            let exact = optical_depth_to_space(ground, d, 2000);
            let fit = o_neil_scale(d[2]);
            assert!(
                (fit / exact - 1.0).abs() < 0.03,
                "{deg} deg: fit {fit}, integral {exact}"
            );
        }
    }

    #[test]
    fn the_brute_force_integral_has_converged() {
        let sky = SingleScattering::o_neil_defaults(direction(80.0, 0.0));
        let finer = Quadrature {
            view: 2 * Quadrature::FINE.view,
            light: 2 * Quadrature::FINE.light,
        };
        for (z, a) in [
            (0.0, 0.0),
            (60.0, 10.0),
            (85.0, 0.0),
            (89.9, 180.0),
            (45.0, 90.0),
        ] {
            let d = direction(z, a);
            let e = rel(sky.exact(d, Quadrature::FINE), sky.exact(d, finer));
            assert!(e < 1e-6, "({z}, {a}): {e:e}");
        }
    }

    #[test]
    fn o_neil_converges_to_the_integral_with_the_fit() {
        // With many samples O'Neil's sum approaches the integral of the same integrand; the two
        // differ by the fit and the shadow only, a few percent at most away from the horizon.
        let sky = SingleScattering::o_neil_defaults(direction(30.0, 0.0));
        for (z, a) in [(0.0, 0.0), (45.0, 90.0), (60.0, 180.0)] {
            let d = direction(z, a);
            let e = rel(sky.o_neil(d, 4096), sky.exact(d, Quadrature::FINE));
            assert!(e < 0.05, "({z}, {a}): {e:e}");
        }
    }

    #[test]
    fn below_the_horizon_is_black() {
        let sky = SingleScattering::o_neil_defaults(direction(30.0, 0.0));
        assert_eq!(sky.exact(direction(95.0, 0.0), Quadrature::FINE), [0.0; 3]);
        assert_eq!(sky.o_neil(direction(95.0, 0.0), 5), [0.0; 3]);
    }
}
