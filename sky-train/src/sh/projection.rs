//! Projection of a sky onto the real SH basis by numerical integration (seed 001, §3.1).
//!
//! The sky is defined on the upper hemisphere and zero below (§3.3), so the integral
//! `c_lm = ∫ L(ω) Y_lm(ω) dω` runs over the upper hemisphere only:
//!
//! * **Quadrature**: a product rule in the zenith angle θ ∈ [0, π/2] and azimuth. In θ,
//!   Gauss-Legendre nodes with the weight `sin θ` (the horizon's jump to zero is at the end of
//!   the interval, so it costs nothing). In azimuth, the trapezoid rule with `2n` nodes after a
//!   periodic change of variable that gathers them around the sun's azimuth
//!   ([`Quadrature::new`]). The basis is separable,
//!   `Y_lm = N_lm P_l^|m|(μ) {cos, sin}(|m| φ)`, so each row of nodes is reduced to its Fourier
//!   moments first.
//!   The only non-smooth feature inside the domain is the circumsolar peak's cone `e^{Dγ}` at
//!   the sun (γ is the angle to the sun), whose row integrals are non-smooth at the sun's θ:
//!   the θ interval is split there, `n/2` nodes on each side, which turns that into an
//!   endpoint singularity of each half (and a sun at the zenith into a smooth integrand, γ = θ).
//! * **Convergence**: `n` doubles from 16 (the sky is evaluated in f32, whose rounding sets a
//!   floor near 3e-7 on the change); the result at `n` is accepted when, in every colour
//!   channel, `Σ_lm |c_lm(n) − c_lm(n/2)| ≤ tolerance · L_min` (the change in the units of
//!   eq. 2), with `L_min` the sky's smallest luminance ([`minimum_luminance`]).
//!
//! Everything is f64 and deterministic: the nodes come from Newton iterations started at fixed
//! points, the transcendental functions are the `libm` crate's (the same bits on every
//! machine), and sums run in a fixed order.

use std::f64::consts::{FRAC_PI_2, PI, TAU};

use anyhow::{Result, bail};
use sky_core::Vec3;

use crate::sources::SkySource;

/// Bands projected (the most sky-core uses).
pub const BANDS: usize = 7;
/// Coefficients projected: `BANDS²`, at index `l² + l + m`.
pub const COEFFICIENTS: usize = BANDS * BANDS;

/// SH coefficients of an RGB sky: `[index(l, m)][channel]`.
pub type Coefficients = [[f64; 3]; COEFFICIENTS];

/// The index of `(l, m)`: `l² + l + m` (as in sky-core).
#[must_use]
#[allow(clippy::cast_sign_loss, clippy::cast_possible_wrap)]
pub const fn index(l: usize, m: isize) -> usize {
    ((l * l + l) as isize + m) as usize
}

/// Gauss-Legendre nodes and weights on [0, 1], `n` points, by Newton's method on P_n.
#[must_use]
#[allow(clippy::cast_precision_loss)]
pub fn gauss_legendre(n: usize) -> Vec<(f64, f64)> {
    let nf = n as f64;
    (0..n)
        .map(|k| {
            // Start at the Chebyshev-like guess of the k-th root of P_n in (-1, 1).
            let mut x = libm::cos(PI * (k as f64 + 0.75) / (nf + 0.5));
            let mut dp = 1.0;
            for _ in 0..100 {
                let (mut p0, mut p1) = (1.0, x);
                for j in 2..=n {
                    let jf = j as f64;
                    (p0, p1) = (p1, ((2.0 * jf - 1.0) * x * p1 - (jf - 1.0) * p0) / jf);
                }
                dp = nf * (x * p1 - p0) / (x * x - 1.0);
                let dx = p1 / dp;
                x -= dx;
                if dx.abs() < 1e-16 {
                    break;
                }
            }
            let w = 2.0 / ((1.0 - x * x) * dp * dp);
            // [-1, 1] → [0, 1].
            (0.5 * (x + 1.0), 0.5 * w)
        })
        .collect()
}

/// `N_lm` (times √2 for m > 0), the normalisation of the orthonormal real SH.
#[must_use]
#[allow(clippy::cast_precision_loss)]
pub fn normalisation(l: usize, m: usize) -> f64 {
    let ratio: f64 = ((l - m + 1)..=(l + m)).map(|k| 1.0 / k as f64).product();
    let k = libm::sqrt((2 * l + 1) as f64 / (4.0 * PI) * ratio);
    if m > 0 {
        k * std::f64::consts::SQRT_2
    } else {
        k
    }
}

/// The associated Legendre functions `P_l^m(μ)` without the Condon-Shortley phase, for
/// `0 ≤ m ≤ l < BANDS`, `[l][m]`.
#[must_use]
#[allow(clippy::cast_precision_loss)]
pub fn legendre(mu: f64) -> [[f64; BANDS]; BANDS] {
    let s = libm::sqrt((1.0 - mu * mu).max(0.0));
    let mut p = [[0.0; BANDS]; BANDS];
    let mut pmm = 1.0;
    for m in 0..BANDS {
        if m > 0 {
            pmm *= (2 * m - 1) as f64 * s;
        }
        p[m][m] = pmm;
        if m + 1 < BANDS {
            p[m + 1][m] = mu * (2 * m + 1) as f64 * pmm;
        }
        for l in (m + 2)..BANDS {
            p[l][m] = ((2 * l - 1) as f64 * mu * p[l - 1][m] - (l + m - 1) as f64 * p[l - 2][m])
                / (l - m) as f64;
        }
    }
    p
}

/// The real SH basis at a unit direction given by `μ = cos θ` and azimuth `phi` (f64), at
/// [`index`]`(l, m)`.
#[must_use]
#[allow(clippy::needless_range_loop)] // (l, m) index arithmetic reads best as loops
pub fn basis(mu: f64, phi: f64) -> [f64; COEFFICIENTS] {
    let p = legendre(mu);
    let mut y = [0.0; COEFFICIENTS];
    for l in 0..BANDS {
        for m in 0..=l {
            let n = normalisation(l, m) * p[l][m];
            #[allow(clippy::cast_possible_wrap, clippy::cast_precision_loss)]
            let (mi, mf) = (m as isize, m as f64);
            if m == 0 {
                y[index(l, 0)] = n;
            } else {
                y[index(l, mi)] = n * libm::cos(mf * phi);
                y[index(l, -mi)] = n * libm::sin(mf * phi);
            }
        }
    }
    y
}

/// The nodes of the product rule at one resolution: `n` rows in θ (Gauss-Legendre, `n/2` on
/// each side of the sun), `2n` azimuths (trapezoid rule after a change of variable that
/// gathers them around the sun's azimuth).
#[derive(Debug, Clone)]
pub struct Quadrature {
    /// Gauss-Legendre nodes and weights on [0, 1], `n/2` of them.
    gauss: Vec<(f64, f64)>,
    /// The azimuths relative to the sun, `g(ψ_j)`, and their trapezoid weights `2π/(2n) g'(ψ_j)`.
    azimuths: Vec<(f64, f64)>,
}

impl Quadrature {
    /// The rule with `n` Gauss-Legendre rows and `2n` azimuths.
    ///
    /// The azimuths relative to the sun are `φ = g(ψ) = ψ − sin ψ` at equally spaced
    /// `ψ_j = 2π j / (2n)`, with weights `2π / (2n) · g'(ψ_j)`: `g` maps the circle onto
    /// itself smoothly and periodically with `g'(0) = 0`, so the trapezoid rule stays spectrally
    /// accurate while the nodes crowd around the sun, where the circumsolar cone is not smooth
    /// (a kink `|φ|` becomes `|ψ|³/6`, smooth to higher order).
    #[must_use]
    #[allow(clippy::cast_precision_loss)]
    pub fn new(n: usize) -> Self {
        let n_phi = 2 * n;
        let h = TAU / n_phi as f64;
        let azimuths = (0..n_phi)
            .map(|j| {
                let psi = h * j as f64;
                (psi - libm::sin(psi), h * (1.0 - libm::cos(psi)))
            })
            .collect();
        Self {
            gauss: gauss_legendre((n / 2).max(1)),
            azimuths,
        }
    }

    /// Nodes in θ.
    #[must_use]
    pub fn rows(&self) -> usize {
        2 * self.gauss.len()
    }

    /// The rows `(μ, weight)`: Gauss-Legendre in the zenith angle θ (weight `sin θ dθ`) on
    /// `[0, θ_split]` and on `[θ_split, π/2]`, so that the circumsolar cone (non-smooth at the
    /// sun) lies on the boundary between the two and costs each only an endpoint singularity.
    fn rows_split(&self, theta_split: f64) -> Vec<(f64, f64)> {
        let s = theta_split.clamp(0.0, FRAC_PI_2);
        let mut rows = Vec::with_capacity(self.rows());
        for (lo, hi) in [(0.0, s), (s, FRAC_PI_2)] {
            if hi > lo {
                rows.extend(self.gauss.iter().map(|&(x, w)| {
                    let theta = lo + (hi - lo) * x;
                    (libm::cos(theta), (hi - lo) * w * libm::sin(theta))
                }));
            }
        }
        rows
    }

    /// The projection of `source`, whose sun lies at zenith angle `sun_zenith` and azimuth
    /// `sun_azimuth` (radians), by this rule.
    #[must_use]
    #[allow(clippy::cast_possible_truncation)]
    pub fn project(
        &self,
        source: &dyn SkySource,
        sun_zenith: f64,
        sun_azimuth: f64,
    ) -> Coefficients {
        let n_phi = self.azimuths.len();
        // cos φ_j, sin φ_j, and w_j cos mφ_j, w_j sin mφ_j (by complex powers).
        let mut phi = Vec::with_capacity(n_phi);
        let mut cos_w = Vec::with_capacity(n_phi);
        let mut sin_w = Vec::with_capacity(n_phi);
        for &(g, w) in &self.azimuths {
            let (s1, c1) = (libm::sin(sun_azimuth + g), libm::cos(sun_azimuth + g));
            phi.push((c1, s1));
            let (mut cm, mut sm) = (1.0, 0.0);
            let mut cw = [0.0; BANDS];
            let mut sw = [0.0; BANDS];
            for m in 0..BANDS {
                cw[m] = w * cm;
                sw[m] = w * sm;
                (cm, sm) = (cm * c1 - sm * s1, sm * c1 + cm * s1);
            }
            cos_w.push(cw);
            sin_w.push(sw);
        }
        let mut dirs = vec![Vec3::ZERO; n_phi];
        let mut values = vec![Vec3::ZERO; n_phi];
        let mut c = [[0.0; 3]; COEFFICIENTS];
        for (mu, w_mu) in self.rows_split(sun_zenith) {
            let s = libm::sqrt((1.0 - mu * mu).max(0.0));
            for (d, &(cp, sp)) in dirs.iter_mut().zip(&phi) {
                *d = Vec3::new((s * cp) as f32, (s * sp) as f32, mu as f32);
            }
            source.rgb_batch(&dirs, &mut values);
            // Fourier moments of the row: Σ_j w f(φ_j) cos mφ_j and sin mφ_j.
            let mut fc = [[0.0; 3]; BANDS];
            let mut fs = [[0.0; 3]; BANDS];
            for ((v, cw), sw) in values.iter().zip(&cos_w).zip(&sin_w) {
                let v = [f64::from(v.x), f64::from(v.y), f64::from(v.z)];
                for m in 0..BANDS {
                    for k in 0..3 {
                        fc[m][k] += v[k] * cw[m];
                        fs[m][k] += v[k] * sw[m];
                    }
                }
            }
            let p = legendre(mu);
            for l in 0..BANDS {
                for m in 0..=l {
                    let f = w_mu * normalisation(l, m) * p[l][m];
                    #[allow(clippy::cast_possible_wrap)]
                    let mi = m as isize;
                    for k in 0..3 {
                        c[index(l, mi)][k] += f * fc[m][k];
                        if m > 0 {
                            c[index(l, -mi)][k] += f * fs[m][k];
                        }
                    }
                }
            }
        }
        c
    }
}

/// A converged projection.
#[derive(Debug, Clone)]
pub struct Projection {
    /// The coefficients at the finest resolution used.
    pub coefficients: Coefficients,
    /// The Gauss-Legendre rows of that resolution (azimuths: twice as many).
    pub rows: usize,
    /// The last change, `max over channels of Σ_lm |Δc_lm| / L_min`.
    pub change: f64,
}

/// The quadrature rules of the doubling sequence 16, 32, …, 1024, built once and shared.
#[derive(Debug, Clone)]
pub struct Integrator {
    rules: Vec<Quadrature>,
    tolerance: f64,
}

impl Integrator {
    /// The smallest resolution tried.
    pub const FIRST_ROWS: usize = 16;
    /// The largest resolution tried.
    pub const MAX_ROWS: usize = 1024;

    /// An integrator accepting a change of at most `tolerance` (relative to `L_min`, summed
    /// over the coefficients as in eq. 2).
    #[must_use]
    pub fn new(tolerance: f64) -> Self {
        let mut rules = Vec::new();
        let mut n = Self::FIRST_ROWS;
        while n <= Self::MAX_ROWS {
            rules.push(Quadrature::new(n));
            n *= 2;
        }
        Self { rules, tolerance }
    }

    /// The projection of `source`, converged as described in the module docs; `l_min` is the
    /// smallest radiance per channel.
    ///
    /// # Errors
    /// When the change is still above the tolerance at [`Self::MAX_ROWS`] rows.
    pub fn project(
        &self,
        source: &dyn SkySource,
        sun_zenith: f64,
        sun_azimuth: f64,
        l_min: f64,
    ) -> Result<Projection> {
        let mut previous: Option<Coefficients> = None;
        let mut change = f64::INFINITY;
        for rule in &self.rules {
            let c = rule.project(source, sun_zenith, sun_azimuth);
            if let Some(p) = previous {
                change = (0..3)
                    .map(|k| {
                        let sum: f64 = c.iter().zip(&p).map(|(a, b)| (a[k] - b[k]).abs()).sum();
                        sum / l_min
                    })
                    .fold(0.0, f64::max);
                if change <= self.tolerance {
                    return Ok(Projection {
                        coefficients: c,
                        rows: rule.rows(),
                        change,
                    });
                }
            }
            previous = Some(c);
        }
        bail!(
            "SH projection of {} did not converge: change {change:.2e} > {:.1e} at {} rows",
            source.describe(),
            self.tolerance,
            Self::MAX_ROWS
        )
    }
}

/// `L_min` of eqs. 2-3: the smallest luminance of the sky over the upper hemisphere (in the
/// units of its radiance: cd/m² for Preetham), sampled every degree in zenith angle (0° to 90°,
/// the horizon included) and azimuth.
#[must_use]
#[allow(clippy::cast_possible_truncation)]
pub fn minimum_luminance(source: &dyn SkySource) -> f64 {
    let dirs: Vec<Vec3> = (0..=90)
        .flat_map(|t| {
            (0..360).map(move |p| {
                sky_core::geom::direction(
                    f64::from(t).to_radians() as f32,
                    f64::from(p).to_radians() as f32,
                )
            })
        })
        .collect();
    let mut out = vec![Vec3::ZERO; dirs.len()];
    source.rgb_batch(&dirs, &mut out);
    out.iter()
        .map(|v| f64::from(sky_core::color::luminance(*v)))
        .fold(f64::INFINITY, f64::min)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gauss_legendre_integrates_polynomials_exactly() {
        let rule = gauss_legendre(8);
        for k in 0..16 {
            let got: f64 = rule.iter().map(|&(x, w)| w * x.powi(k)).sum();
            assert!((got - 1.0 / f64::from(k + 1)).abs() < 1e-14, "x^{k}: {got}");
        }
    }

    #[test]
    fn basis_is_orthonormal_over_the_sphere() {
        // Gauss-Legendre on [0,1] twice (upper and lower hemisphere) × trapezoid in φ.
        let rule = gauss_legendre(16);
        let n_phi = 32;
        let mut gram = vec![[0.0; COEFFICIENTS]; COEFFICIENTS];
        for &(mu, w) in &rule {
            for sign in [1.0, -1.0] {
                for j in 0..n_phi {
                    let phi = TAU * f64::from(j) / f64::from(n_phi);
                    let y = basis(sign * mu, phi);
                    for a in 0..COEFFICIENTS {
                        for b in 0..COEFFICIENTS {
                            gram[a][b] += w * TAU / f64::from(n_phi) * y[a] * y[b];
                        }
                    }
                }
            }
        }
        for (a, row) in gram.iter().enumerate() {
            for (b, g) in row.iter().enumerate() {
                let want = if a == b { 1.0 } else { 0.0 };
                assert!((g - want).abs() < 1e-12, "<Y{a}, Y{b}> = {g}");
            }
        }
    }
}
