//! Full-batch Levenberg-Marquardt (Marquardt's diagonal scaling) for least-squares problems with
//! a few hundred parameters: the normal equations are small enough to solve exactly.

use std::time::Instant;

use rayon::prelude::*;

/// A least-squares problem: residuals r(p) and their Jacobian, summed over examples.
pub trait LeastSquares: Sync {
    /// Number of examples.
    fn examples(&self) -> usize;
    /// Adds example `i`'s residuals to `cost` (sum of squares) and, when `normal` is given,
    /// its Jacobian rows and residuals with [`Accumulator::add_row`].
    fn accumulate(&self, params: &[f64], i: usize, acc: &mut Accumulator, normal: bool);
}

/// Jacobian rows are gathered in blocks of this many and added to JᵀJ by one matrix product
/// (a cache-blocked GEMM runs several times faster than adding rows one by one).
const BLOCK: usize = 256;

/// Partial sums of the normal equations.
#[derive(Debug, Clone)]
pub struct Accumulator {
    /// Σ r².
    pub cost: f64,
    /// JᵀJ, P × P row-major, symmetric (complete after [`Accumulator::flush`]).
    pub jtj: Vec<f64>,
    /// Jᵀr (complete after [`Accumulator::flush`]).
    pub jtr: Vec<f64>,
    /// Rows added since the last flush, row-major (up to `BLOCK` × P), and their residuals.
    block: Vec<f64>,
    block_residuals: Vec<f64>,
    /// Scratch for the problem's use.
    pub scratch: crate::train::net::Scratch,
    /// Scratch gradient rows for the problem's use.
    pub rows: [Vec<f64>; 3],
}

impl Accumulator {
    fn new(p: usize, normal: bool) -> Self {
        Self {
            cost: 0.0,
            jtj: if normal { vec![0.0; p * p] } else { Vec::new() },
            jtr: if normal { vec![0.0; p] } else { Vec::new() },
            block: Vec::new(),
            block_residuals: Vec::new(),
            scratch: crate::train::net::Scratch::default(),
            rows: Default::default(),
        }
    }

    /// Adds one residual `r` with Jacobian row `row` (length P).
    #[inline]
    pub fn add_row(&mut self, r: f64, row: &[f64]) {
        debug_assert_eq!(row.len(), self.jtr.len());
        self.block.extend_from_slice(row);
        self.block_residuals.push(r);
        if self.block_residuals.len() == BLOCK {
            self.flush();
        }
    }

    /// Adds the pending rows to JᵀJ and Jᵀr: JᵀJ += BᵀB, Jᵀr += Bᵀr for the block B.
    pub fn flush(&mut self) {
        let (n, p) = (self.block_residuals.len(), self.jtr.len());
        if n == 0 {
            return;
        }
        for (row, r) in self.block.chunks_exact(p).zip(&self.block_residuals) {
            for (g, a) in self.jtr.iter_mut().zip(row) {
                *g += a * r;
            }
        }
        assert!(self.block.len() == n * p && self.jtj.len() == p * p);
        let (stride, p_stride) = (1, isize::try_from(p).unwrap_or(isize::MAX));
        // SAFETY: `block` holds n × p values read as the p × n matrix Bᵀ (row stride 1, column
        // stride p) and as the n × p matrix B (row stride p, column stride 1); `jtj` holds
        // p × p values written as a row-major p × p matrix; both lengths are checked just
        // above, and the input and output buffers are distinct allocations.
        #[allow(unsafe_code)]
        unsafe {
            matrixmultiply::dgemm(
                p,
                n,
                p,
                1.0,
                self.block.as_ptr(),
                stride,
                p_stride,
                self.block.as_ptr(),
                p_stride,
                stride,
                1.0,
                self.jtj.as_mut_ptr(),
                p_stride,
                stride,
            );
        }
        self.block.clear();
        self.block_residuals.clear();
    }

    fn merge(mut self, other: Self) -> Self {
        self.cost += other.cost;
        for (a, b) in self.jtj.iter_mut().zip(&other.jtj) {
            *a += b;
        }
        for (a, b) in self.jtr.iter_mut().zip(&other.jtr) {
            *a += b;
        }
        self
    }
}

/// Σ r² at `params`, and the normal equations when `normal`, over all examples, in parallel;
/// `None` when `deadline` passes first (checked every `BLOCK` (256) examples).
///
/// The examples are split into a fixed number of chunks whose sums are added in chunk order,
/// so the result does not depend on the thread count or on scheduling: training is
/// reproducible bit for bit. The chunks are summed as many at a time as there are threads, so
/// that at most threads + 1 P × P matrices exist at once (memory: see [`MAX_PARAMETERS`]).
pub fn evaluate(
    problem: &impl LeastSquares,
    params: &[f64],
    normal: bool,
    deadline: Option<Instant>,
) -> Option<Accumulator> {
    const CHUNKS: usize = 64;
    let p = params.len();
    let n = problem.examples();
    let chunk = n.div_ceil(CHUNKS).max(1);
    let chunks = n.div_ceil(chunk);
    let group = rayon::current_num_threads().max(1);
    let late = || deadline.is_some_and(|d| Instant::now() >= d);
    let mut total = Accumulator::new(p, normal);
    for first in (0..chunks).step_by(group) {
        let parts: Vec<Option<Accumulator>> = (first..(first + group).min(chunks))
            .into_par_iter()
            .map(|c| {
                let mut acc = Accumulator::new(p, normal);
                let mut in_time = true;
                crate::dispatch::fastest(
                    #[inline(always)]
                    || {
                        for i in c * chunk..((c + 1) * chunk).min(n) {
                            if i % BLOCK == 0 && late() {
                                in_time = false;
                                return;
                            }
                            problem.accumulate(params, i, &mut acc, normal);
                        }
                    },
                );
                acc.flush();
                acc.block = Vec::new();
                in_time.then_some(acc)
            })
            .collect();
        for part in parts {
            total = total.merge(part?);
        }
    }
    Some(total)
}

/// The most parameters Levenberg-Marquardt trains: its normal equations are a P × P matrix of
/// f64, of which [`evaluate`] holds one per thread plus one and [`damped_step`] one more, 72 MB
/// each at this size (a 6-255-3 network has 2,553 parameters; 6-255-255-3 has 67,833, whose
/// matrix alone would take 37 GB).
pub const MAX_PARAMETERS: usize = 3000;

/// Solves (A + λ diag(A)) x = −g for symmetric positive (semi)definite A given as its upper
/// triangle, by Cholesky. Returns `None` when the damped matrix is not positive definite.
#[must_use]
pub fn damped_step(jtj: &[f64], jtr: &[f64], lambda: f64) -> Option<Vec<f64>> {
    let p = jtr.len();
    let mut l = vec![0.0; p * p];
    for i in 0..p {
        for j in i..p {
            let mut v = jtj[i * p + j];
            if i == j {
                v += lambda * v.max(1e-12) + 1e-12;
            }
            l[j * p + i] = v; // lower triangle of A
        }
    }
    // In-place Cholesky: A = L Lᵀ.
    for j in 0..p {
        let mut d = l[j * p + j];
        for k in 0..j {
            d -= l[j * p + k] * l[j * p + k];
        }
        if d <= 0.0 || !d.is_finite() {
            return None;
        }
        let d = d.sqrt();
        l[j * p + j] = d;
        for i in j + 1..p {
            let mut v = l[i * p + j];
            for k in 0..j {
                v -= l[i * p + k] * l[j * p + k];
            }
            l[i * p + j] = v / d;
        }
    }
    // L y = −g, then Lᵀ x = y.
    let mut y = vec![0.0; p];
    for i in 0..p {
        let mut v = -jtr[i];
        for k in 0..i {
            v -= l[i * p + k] * y[k];
        }
        y[i] = v / l[i * p + i];
    }
    let mut x = vec![0.0; p];
    for i in (0..p).rev() {
        let mut v = y[i];
        for k in i + 1..p {
            v -= l[k * p + i] * x[k];
        }
        x[i] = v / l[i * p + i];
    }
    Some(x)
}

/// State of a Levenberg-Marquardt run, advanced one accepted step at a time.
#[derive(Debug, Clone)]
pub struct Lm {
    /// Current parameters.
    pub params: Vec<f64>,
    /// Σ r² at `params`.
    pub cost: f64,
    /// Damping.
    pub lambda: f64,
    /// No step is taken after this instant: a step still running then is abandoned, and the
    /// parameters stay as they were.
    pub deadline: Option<Instant>,
}

impl Lm {
    /// Starts at `params` (cost infinite if `deadline` passes while it is computed).
    pub fn new(problem: &impl LeastSquares, params: Vec<f64>, deadline: Option<Instant>) -> Self {
        let cost = evaluate(problem, &params, false, deadline).map_or(f64::INFINITY, |a| a.cost);
        Self {
            params,
            cost,
            lambda: 1e-2,
            deadline,
        }
    }

    /// One iteration: builds the normal equations and tries ever more damped steps until one
    /// lowers the cost. Returns false when none does up to λ = 10¹² (converged or stuck), or
    /// when the deadline passes.
    pub fn step(&mut self, problem: &impl LeastSquares) -> bool {
        if !self.cost.is_finite() {
            return false;
        }
        let Some(acc) = evaluate(problem, &self.params, true, self.deadline) else {
            return false;
        };
        // From λ = 10⁻¹² to 10¹² in steps of 4 takes 40 tries.
        for _ in 0..48 {
            if let Some(delta) = damped_step(&acc.jtj, &acc.jtr, self.lambda) {
                let trial: Vec<f64> = self.params.iter().zip(&delta).map(|(p, d)| p + d).collect();
                let Some(cost) = evaluate(problem, &trial, false, self.deadline).map(|a| a.cost)
                else {
                    return false;
                };
                if cost.is_finite() && cost < self.cost {
                    self.params = trial;
                    self.cost = cost;
                    self.lambda = (self.lambda / 3.0).max(1e-12);
                    return true;
                }
            }
            self.lambda *= 4.0;
            if self.lambda > 1e12 {
                break;
            }
        }
        false
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Fits y = a e^{b x} to exact data: LM must recover (a, b).
    struct Exp {
        xs: Vec<f64>,
        ys: Vec<f64>,
    }

    impl LeastSquares for Exp {
        fn examples(&self) -> usize {
            self.xs.len()
        }
        fn accumulate(&self, p: &[f64], i: usize, acc: &mut Accumulator, normal: bool) {
            let e = (p[1] * self.xs[i]).exp();
            let r = p[0] * e - self.ys[i];
            acc.cost += r * r;
            if normal {
                acc.add_row(r, &[e, p[0] * self.xs[i] * e]);
            }
        }
    }

    #[test]
    fn recovers_an_exponential() {
        let xs: Vec<f64> = (0..50).map(|i| f64::from(i) / 25.0).collect();
        let ys = xs.iter().map(|x| 2.5 * (-1.3 * x).exp()).collect();
        let problem = Exp { xs, ys };
        let mut lm = Lm::new(&problem, vec![1.0, 0.0], None);
        for _ in 0..100 {
            if !lm.step(&problem) {
                break;
            }
        }
        assert!((lm.params[0] - 2.5).abs() < 1e-8, "{:?}", lm.params);
        assert!((lm.params[1] + 1.3).abs() < 1e-8, "{:?}", lm.params);
    }
}
