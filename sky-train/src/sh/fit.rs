//! Least-squares fit of each SH coefficient as a 2-D polynomial in sun zenith and turbidity
//! (seed 001, §3.1, eq. 1), in a Chebyshev basis of the normalised variables.
//!
//! The samples lie on a tensor grid of Chebyshev points (of the first kind) in θ and τ, so the
//! design matrix is a Kronecker product `A_θ ⊗ A_τ`; its least-squares solution is
//! `A_θ⁺ C A_τ⁺ᵀ`, solved one dimension at a time with Householder QR, and its 2-norm condition
//! number is `cond(A_θ) · cond(A_τ)`. On Chebyshev points the columns `T_i(x_k)` are orthogonal
//! (discrete orthogonality), so the condition number is √2 in each dimension; raw monomials
//! `θ^i τ^j` on the same points (eq. 1 as printed) would be ill-conditioned by many orders of
//! magnitude (both are reported by `sky-train fit-sh`).

use std::f64::consts::PI;

/// The `n` Chebyshev points of the first kind mapped to `[lo, hi]`, increasing.
#[must_use]
#[allow(clippy::cast_precision_loss)]
pub fn chebyshev_points(n: usize, lo: f64, hi: f64) -> Vec<f64> {
    (0..n)
        .map(|k| {
            let x = -libm::cos(PI * (k as f64 + 0.5) / n as f64);
            0.5 * (lo + hi) + 0.5 * (hi - lo) * x
        })
        .collect()
}

/// `x` in `[lo, hi]` mapped to `[−1, 1]`.
#[must_use]
pub fn normalise(x: f64, lo: f64, hi: f64) -> f64 {
    (2.0 * x - lo - hi) / (hi - lo)
}

/// `T_0(x) … T_{n−1}(x)`.
#[must_use]
pub fn chebyshev(x: f64, n: usize) -> Vec<f64> {
    let mut t = Vec::with_capacity(n);
    for k in 0..n {
        t.push(match k {
            0 => 1.0,
            1 => x,
            _ => 2.0 * x * t[k - 1] - t[k - 2],
        });
    }
    t
}

/// A dense row-major matrix.
#[derive(Debug, Clone, PartialEq)]
pub struct Matrix {
    /// Rows.
    pub rows: usize,
    /// Columns.
    pub cols: usize,
    /// `rows × cols` entries, row-major.
    pub data: Vec<f64>,
}

impl Matrix {
    /// The entry at (`r`, `c`).
    #[must_use]
    pub fn at(&self, r: usize, c: usize) -> f64 {
        self.data[r * self.cols + c]
    }

    /// The matrix whose row `i` is `row(points[i])`, of `cols` entries.
    fn from_rows(points: &[f64], cols: usize, row: impl Fn(f64) -> Vec<f64>) -> Self {
        Self {
            rows: points.len(),
            cols,
            data: points.iter().flat_map(|&x| row(x)).collect(),
        }
    }

    /// The design matrix `[T_j(u(x_i))]` of `points` in `[lo, hi]` for degree `degree`.
    #[must_use]
    pub fn chebyshev_design(points: &[f64], lo: f64, hi: f64, degree: usize) -> Self {
        Self::from_rows(points, degree + 1, |x| {
            chebyshev(normalise(x, lo, hi), degree + 1)
        })
    }

    /// The design matrix of raw monomials `[x_i^j]` (eq. 1 as printed), for comparison.
    #[must_use]
    #[allow(clippy::cast_possible_wrap, clippy::cast_possible_truncation)]
    pub fn monomial_design(points: &[f64], degree: usize) -> Self {
        Self::from_rows(points, degree + 1, |x| {
            (0..=degree).map(|j| x.powi(j as i32)).collect()
        })
    }

    /// The 2-norm condition number `σ_max / σ_min`, from the eigenvalues of `AᵀA` (cyclic
    /// Jacobi rotations).
    #[must_use]
    pub fn condition_number(&self) -> f64 {
        let n = self.cols;
        let mut g = vec![0.0; n * n];
        for i in 0..n {
            for j in 0..n {
                g[i * n + j] = (0..self.rows).map(|r| self.at(r, i) * self.at(r, j)).sum();
            }
        }
        for _sweep in 0..100 {
            let off: f64 = (0..n)
                .flat_map(|i| (0..n).filter(move |&j| j != i).map(move |j| (i, j)))
                .map(|(i, j)| g[i * n + j] * g[i * n + j])
                .sum();
            let diag: f64 = (0..n).map(|i| g[i * n + i] * g[i * n + i]).sum();
            if off <= 1e-30 * diag {
                break;
            }
            for p in 0..n {
                for q in (p + 1)..n {
                    let apq = g[p * n + q];
                    if apq == 0.0 {
                        continue;
                    }
                    let theta = (g[q * n + q] - g[p * n + p]) / (2.0 * apq);
                    let t = theta.signum() / (theta.abs() + libm::sqrt(theta * theta + 1.0));
                    let t = if theta == 0.0 { 1.0 } else { t };
                    let c = 1.0 / libm::sqrt(t * t + 1.0);
                    let s = t * c;
                    for k in 0..n {
                        let (gkp, gkq) = (g[k * n + p], g[k * n + q]);
                        g[k * n + p] = c * gkp - s * gkq;
                        g[k * n + q] = s * gkp + c * gkq;
                    }
                    for k in 0..n {
                        let (gpk, gqk) = (g[p * n + k], g[q * n + k]);
                        g[p * n + k] = c * gpk - s * gqk;
                        g[q * n + k] = s * gpk + c * gqk;
                    }
                }
            }
        }
        let eig: Vec<f64> = (0..n).map(|i| g[i * n + i].abs()).collect();
        let max = eig.iter().copied().fold(0.0, f64::max);
        let min = eig.iter().copied().fold(f64::INFINITY, f64::min);
        libm::sqrt(max / min)
    }
}

/// A least-squares solver for one design matrix: its Householder QR factorisation.
#[derive(Debug, Clone)]
pub struct LeastSquares {
    /// R above the diagonal, Householder vectors below (LAPACK's compact form, without the
    /// implicit 1).
    qr: Matrix,
    /// The Householder scalars τ_k and the diagonal of R.
    tau: Vec<f64>,
    diag: Vec<f64>,
}

impl LeastSquares {
    /// Factorises `a` (rows ≥ columns, full column rank).
    #[must_use]
    pub fn new(a: &Matrix) -> Self {
        let (m, n) = (a.rows, a.cols);
        let mut qr = a.clone();
        let mut tau = vec![0.0; n];
        let mut diag = vec![0.0; n];
        for k in 0..n {
            let norm = libm::sqrt((k..m).map(|r| qr.at(r, k).powi(2)).sum::<f64>());
            let akk = qr.at(k, k);
            let alpha = if akk > 0.0 { -norm } else { norm };
            // v = x − α e_1, stored in column k; τ = 2 / (vᵀv).
            qr.data[k * n + k] = akk - alpha;
            let vtv: f64 = (k..m).map(|r| qr.at(r, k).powi(2)).sum();
            tau[k] = if vtv > 0.0 { 2.0 / vtv } else { 0.0 };
            diag[k] = alpha;
            for c in (k + 1)..n {
                let dot: f64 = (k..m).map(|r| qr.at(r, k) * qr.at(r, c)).sum();
                let f = tau[k] * dot;
                for r in k..m {
                    qr.data[r * n + c] -= f * qr.at(r, k);
                }
            }
        }
        Self { qr, tau, diag }
    }

    /// The least-squares solution `x` of `A x ≈ b`.
    #[must_use]
    pub fn solve(&self, b: &[f64]) -> Vec<f64> {
        let (m, n) = (self.qr.rows, self.qr.cols);
        let mut y = b.to_vec();
        for k in 0..n {
            let dot: f64 = (k..m).map(|r| self.qr.at(r, k) * y[r]).sum();
            let f = self.tau[k] * dot;
            for (r, yr) in y.iter_mut().enumerate().take(m).skip(k) {
                *yr -= f * self.qr.at(r, k);
            }
        }
        let mut x = vec![0.0; n];
        for k in (0..n).rev() {
            let s: f64 = ((k + 1)..n).map(|c| self.qr.at(k, c) * x[c]).sum();
            x[k] = (y[k] - s) / self.diag[k];
        }
        x
    }
}

/// Fits `values[i][j]` (sampled at `theta[i]`, `tau[j]`) by the tensor-product polynomial of the
/// two design matrices' solvers: returns `p[a][b]` multiplying `T_a(u(θ)) T_b(v(τ))`.
#[must_use]
pub fn fit_tensor(
    values: &[Vec<f64>],
    solve_theta: &LeastSquares,
    solve_tau: &LeastSquares,
) -> Vec<Vec<f64>> {
    let n_tau = values.first().map_or(0, Vec::len);
    // Along θ for every τ column: D[a][j].
    let columns: Vec<Vec<f64>> = (0..n_tau)
        .map(|j| solve_theta.solve(&values.iter().map(|row| row[j]).collect::<Vec<_>>()))
        .collect();
    let n_a = columns.first().map_or(0, Vec::len);
    // Along τ for every θ coefficient.
    (0..n_a)
        .map(|a| solve_tau.solve(&columns.iter().map(|col| col[a]).collect::<Vec<_>>()))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn least_squares_recovers_a_polynomial_and_conditions_are_sane() {
        let theta = chebyshev_points(28, 0.0, 1.5);
        let tau = chebyshev_points(16, 2.0, 6.0);
        let a = Matrix::chebyshev_design(&theta, 0.0, 1.5, 13);
        let b = Matrix::chebyshev_design(&tau, 2.0, 6.0, 7);
        let f = |t: f64, u: f64| 3.0 + t * t * t - 0.5 * t * u + 0.01 * u.powi(7);
        let values: Vec<Vec<f64>> = theta
            .iter()
            .map(|&t| tau.iter().map(|&u| f(t, u)).collect())
            .collect();
        let p = fit_tensor(&values, &LeastSquares::new(&a), &LeastSquares::new(&b));
        for &(t, u) in &[(0.0, 2.0), (0.7, 3.3), (1.5, 6.0)] {
            let tu = chebyshev(normalise(t, 0.0, 1.5), 14);
            let tv = chebyshev(normalise(u, 2.0, 6.0), 8);
            let got: f64 = (0..14)
                .flat_map(|i| (0..8).map(move |j| (i, j)))
                .map(|(i, j)| p[i][j] * tu[i] * tv[j])
                .sum();
            assert!((got - f(t, u)).abs() < 1e-9, "{got} vs {}", f(t, u));
        }
        // Discrete orthogonality on Chebyshev points: cond = √2.
        assert!((a.condition_number() - std::f64::consts::SQRT_2).abs() < 1e-9);
        assert!(Matrix::monomial_design(&theta, 13).condition_number() > 1e6);
    }
}
