//! Geometry of the spherical shell and the parametrisations of the precomputed tables.
//!
//! A point is given by its radius r; a direction there by μ, the cosine of its zenith angle;
//! the sun by μs, the cosine of its zenith angle at the point; and the view's azimuth relative
//! to the sun by φ ∈ [0, π] (the field is symmetric about the sun's vertical plane). Along a
//! straight ray the cosine ν between the view and the sun is constant (Bruneton 2017, §2).
//!
//! Parametrisations (after Bruneton & Neyret 2008 / Bruneton 2017, simplified):
//! - r: u = √(r² − R²) / √(R_t² − R²), uniform in u (dense near the ground);
//! - μ: two halves split at the horizon μ_h(r) = −√(1 − (R / r)²), each uniform in
//!   x = √(|μ − μ_h| / (1 ∓ μ_h)), so that both sides of the horizon are resolved and rays that
//!   hit the ground are never interpolated with rays that do not;
//! - sun zenith angle: piecewise uniform in degrees, coarse by day and fine through twilight
//!   ([`SunGrid`]);
//! - φ: uniform in [0, π].

use super::constituents::{EARTH_RADIUS_M as R, TOP_RADIUS_M as RT};

/// √(R_t² − R²), m: the distance to the top of the atmosphere along the horizon at the ground.
#[must_use]
pub fn horizon_distance() -> f64 {
    (RT * RT - R * R).sqrt()
}

/// Cosine of the horizon's zenith angle at radius `r` (0 at the ground, negative above).
#[must_use]
#[inline]
pub fn mu_horizon(r: f64) -> f64 {
    let s = R / r;
    -(1.0 - s * s).max(0.0).sqrt()
}

/// Distance from radius `r` along `mu` to the top of the atmosphere.
#[must_use]
#[inline]
pub fn distance_to_top(r: f64, mu: f64) -> f64 {
    let disc = r * r * (mu * mu - 1.0) + RT * RT;
    (-r * mu + disc.max(0.0).sqrt()).max(0.0)
}

/// Distance from radius `r` along `mu` to the ground (for a ray that reaches it).
#[must_use]
#[inline]
pub fn distance_to_ground(r: f64, mu: f64) -> f64 {
    let disc = r * r * (mu * mu - 1.0) + R * R;
    (-r * mu - disc.max(0.0).sqrt()).max(0.0)
}

/// Whether the ray from `r` along `mu` hits the ground.
#[must_use]
#[inline]
pub fn hits_ground(r: f64, mu: f64) -> bool {
    mu < 0.0 && r * r * (mu * mu - 1.0) + R * R >= 0.0
}

/// The point at distance `t` along the ray (r, μ, μs, ν): its radius, μ and μs there.
#[must_use]
#[inline]
pub fn along(r: f64, mu: f64, mus: f64, nu: f64, t: f64) -> (f64, f64, f64) {
    let rt = (t * t + 2.0 * r * mu * t + r * r)
        .max(R * R * 0.999_999)
        .sqrt();
    (
        rt,
        ((r * mu + t) / rt).clamp(-1.0, 1.0),
        ((r * mus + t * nu) / rt).clamp(-1.0, 1.0),
    )
}

/// ν, the cosine between a view (μ, φ) and the sun (μs, azimuth 0).
#[must_use]
#[inline]
pub fn nu_of(mu: f64, mus: f64, phi: f64) -> f64 {
    let s = ((1.0 - mu * mu) * (1.0 - mus * mus)).max(0.0).sqrt();
    (mu * mus + s * phi.cos()).clamp(-1.0, 1.0)
}

/// φ from ν at (μ, μs); 0 where the azimuth is undefined.
#[must_use]
#[inline]
pub fn phi_of(mu: f64, mus: f64, nu: f64) -> f64 {
    let s = ((1.0 - mu * mu) * (1.0 - mus * mus)).max(0.0).sqrt();
    if s < 1e-12 {
        0.0
    } else {
        ((nu - mu * mus) / s).clamp(-1.0, 1.0).acos()
    }
}

/// The r coordinate u ∈ [0, 1].
#[must_use]
#[inline]
pub fn r_coord(r: f64) -> f64 {
    ((r * r - R * R).max(0.0).sqrt() / horizon_distance()).clamp(0.0, 1.0)
}

/// The radius at coordinate `u`.
#[must_use]
pub fn r_at(u: f64) -> f64 {
    let rho = u * horizon_distance();
    (rho * rho + R * R).sqrt()
}

/// A fractional index in [0, n − 1]: the lower node and the weight of the upper one.
#[must_use]
#[inline]
#[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
pub fn split(f: f64, n: usize) -> (usize, f64) {
    if n < 2 {
        return (0, 0.0);
    }
    let top = (n - 1) as f64;
    let f = if f.is_finite() {
        f.clamp(0.0, top)
    } else {
        0.0
    };
    let i = (f.floor() as usize).min(n - 2);
    (i, f - i as f64)
}

/// The μ coordinate at `r`: whether `mu` is in the upper half (rays that reach the top), and
/// x ∈ [0, 1] within the half (0 at the horizon).
#[must_use]
#[inline]
pub fn mu_coord(r: f64, mu: f64, upper: bool) -> f64 {
    let h = mu_horizon(r);
    if upper {
        ((mu - h) / (1.0 - h)).clamp(0.0, 1.0).sqrt()
    } else {
        ((h - mu) / (1.0 + h)).clamp(0.0, 1.0).sqrt()
    }
}

/// The μ of coordinate `x` (0 at the horizon) in the upper or lower half at `r`.
#[must_use]
pub fn mu_at(r: f64, x: f64, upper: bool) -> f64 {
    let h = mu_horizon(r);
    if upper {
        h + x * x * (1.0 - h)
    } else {
        h - x * x * (1.0 + h)
    }
}

/// Sun zenith angles of a table: uniform steps of `day_step` degrees up to 60°, `dusk_step` up
/// to 84°, `twilight_step` up to `max_deg` (which the steps must divide).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SunGrid {
    /// Step from 0° to 60°, degrees.
    pub day_step: f64,
    /// Step from 60° to 84°, degrees.
    pub dusk_step: f64,
    /// Step from 84° to `max_deg`, degrees.
    pub twilight_step: f64,
    /// The largest sun zenith angle, degrees.
    pub max_deg: f64,
}

const DUSK_DEG: f64 = 60.0;
const TWILIGHT_DEG: f64 = 84.0;

impl SunGrid {
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    fn counts(&self) -> (usize, usize, usize) {
        (
            (DUSK_DEG / self.day_step).round() as usize,
            ((TWILIGHT_DEG - DUSK_DEG) / self.dusk_step).round() as usize,
            ((self.max_deg - TWILIGHT_DEG) / self.twilight_step).round() as usize,
        )
    }

    /// The number of nodes.
    #[must_use]
    pub fn len(&self) -> usize {
        let (a, b, c) = self.counts();
        a + b + c + 1
    }

    /// Never empty.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        false
    }

    /// The sun zenith angle of node `i`, degrees.
    #[must_use]
    #[allow(clippy::cast_precision_loss)]
    pub fn angle_deg(&self, i: usize) -> f64 {
        let (a, b, _) = self.counts();
        if i <= a {
            i as f64 * self.day_step
        } else if i <= a + b {
            DUSK_DEG + (i - a) as f64 * self.dusk_step
        } else {
            TWILIGHT_DEG + (i - a - b) as f64 * self.twilight_step
        }
    }

    /// μs of node `i`.
    #[must_use]
    pub fn mus(&self, i: usize) -> f64 {
        self.angle_deg(i).to_radians().cos()
    }

    /// The fractional node index of a sun zenith angle in degrees (clamped to the grid).
    #[must_use]
    #[allow(clippy::cast_precision_loss)]
    pub fn index(&self, deg: f64) -> f64 {
        let (a, b, _) = self.counts();
        let deg = if deg.is_finite() {
            deg.clamp(0.0, self.max_deg)
        } else {
            0.0
        };
        if deg <= DUSK_DEG {
            deg / self.day_step
        } else if deg <= TWILIGHT_DEG {
            a as f64 + (deg - DUSK_DEG) / self.dusk_step
        } else {
            (a + b) as f64 + (deg - TWILIGHT_DEG) / self.twilight_step
        }
    }

    /// The fractional node index of μs.
    #[must_use]
    #[inline]
    pub fn index_of_mus(&self, mus: f64) -> f64 {
        self.index(mus.clamp(-1.0, 1.0).acos().to_degrees())
    }
}

/// Trapezoid weights of sorted nodes (half intervals at the ends).
#[must_use]
pub fn trapezoid_weights(nodes: &[f64]) -> Vec<f64> {
    let n = nodes.len();
    (0..n)
        .map(|i| {
            let lo = if i == 0 { nodes[0] } else { nodes[i - 1] };
            let hi = if i + 1 == n {
                nodes[n - 1]
            } else {
                nodes[i + 1]
            };
            0.5 * (hi - lo).abs()
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sun_grid_round_trip() {
        let g = SunGrid {
            day_step: 5.0,
            dusk_step: 2.0,
            twilight_step: 0.5,
            max_deg: 110.0,
        };
        assert_eq!(g.len(), 12 + 12 + 52 + 1);
        for i in 0..g.len() {
            assert!((g.index(g.angle_deg(i)) - i as f64).abs() < 1e-9);
        }
        assert!((g.index(97.25) - (24.0 + 26.5)).abs() < 1e-9);
    }

    #[test]
    fn mu_round_trip_and_ray_geometry() {
        let r = R + 30_000.0;
        for upper in [false, true] {
            for x in [0.0, 0.3, 1.0] {
                assert!((mu_coord(r, mu_at(r, x, upper), upper) - x).abs() < 1e-9);
            }
        }
        // A ray just below the horizon hits the ground, one just above does not.
        let h = mu_horizon(r);
        assert!(hits_ground(r, h - 1e-6) && !hits_ground(r, h + 1e-6));
        // Straight up from the ground to the top: 100 km.
        assert!((distance_to_top(R, 1.0) - 100_000.0).abs() < 1e-6);
        let (r1, mu1, _) = along(R, 1.0, 1.0, 1.0, 50_000.0);
        assert!((r1 - R - 50_000.0).abs() < 1e-6 && (mu1 - 1.0).abs() < 1e-12);
    }
}
