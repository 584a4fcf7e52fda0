//! Spherical-harmonics sky lighting, the fitting side (seed 001): projection of any sky model
//! onto real SH ([`projection`]), the polynomial fit in sun zenith and turbidity ([`fit`]), the
//! generated Rust tables ([`export`]) and the paper's error measures ([`eval`]).
//!
//! The sky model is a black box: anything [`crate::sources::build`] can make for a sun zenith
//! and turbidity (with the sun at azimuth 0) can be fitted.

pub mod eval;
pub mod export;
pub mod fit;
pub mod projection;
pub mod report;

use anyhow::{Context, Result};
use rayon::prelude::*;

use crate::args::ParamError;
use crate::sources::{self, ModelKind, SkyParams, SkySource};
use fit::{LeastSquares, Matrix};
use projection::{BANDS, COEFFICIENTS, Coefficients, Integrator, index};
use sky_core::sh::polynomial::RowWidth;

/// The coefficient functions stored: `(l, m)` with `m ≥ 0` (see sky-core's
/// `sh::polynomial::STORED_COEFFICIENTS`).
pub const STORED: usize = BANDS * (BANDS + 1) / 2;

/// `(l, m)` of every stored coefficient function, in order.
#[must_use]
pub fn stored_lm() -> Vec<(usize, usize)> {
    (0..BANDS)
        .flat_map(|l| (0..=l).map(move |m| (l, m)))
        .collect()
}

/// Polynomial degrees in sun zenith and turbidity.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Degrees {
    /// Degree in sun zenith θ.
    pub theta: usize,
    /// Degree in turbidity τ.
    pub tau: usize,
}

impl Degrees {
    /// The paper's degrees (§3.2): 13 in θ, 7 in τ.
    pub const PAPER: Self = Self { theta: 13, tau: 7 };

    /// Chebyshev coefficients per polynomial, `(θ + 1)(τ + 1)`.
    #[must_use]
    pub fn count(self) -> usize {
        (self.theta + 1) * (self.tau + 1)
    }
}

/// The bands of the low group (sky-core's `sh::polynomial::LOW_BANDS`).
pub const LOW_BANDS: usize = 5;

/// The step of the integer rows of the stored tables (sky-core's
/// `sh::polynomial::CoefficientRows`), low group (`l < 5`) and high group (`l = 5, 6`), in the
/// units of the coefficients (cd/m² for Preetham): powers of two, so that `n · step` is exact
/// in f32.
///
/// The low group's 2⁻¹³ leaves its rounding far below the fit's own error and the 0.005 % the
/// 5-band expansions are held to (eq. 3's E_mean of the rounding alone: about 3e-6 of the
/// smallest luminance, against the fit's 1.4e-5); the high group only needs the 7-band
/// 1.5 %, and its 2⁻⁸ adds about 4e-5 to the fit's 3.5e-3. `fit-sh --report` measures both
/// (the quantisation column of `docs/sh_errors.md`).
pub const STEPS: [f32; 2] = [1.0 / 8192.0, 1.0 / 256.0];

/// What `fit-sh` fits.
#[derive(Debug, Clone, PartialEq)]
pub struct FitConfig {
    /// The sky model.
    pub model: ModelKind,
    /// Degrees of the low group of bands, `l < 5`.
    pub low: Degrees,
    /// Degrees of the high group of bands, `l = 5, 6`.
    pub high: Degrees,
    /// Chebyshev sample points in sun zenith.
    pub nodes_theta: usize,
    /// Chebyshev sample points in turbidity.
    pub nodes_tau: usize,
    /// Sun zenith range in radians (as f32 values, which the tables store).
    pub sun_zenith: [f32; 2],
    /// Turbidity range.
    pub turbidity: [f32; 2],
    /// Convergence tolerance of the projection (see [`projection`]).
    pub tolerance: f64,
}

impl FitConfig {
    /// The tables sky-core ships: degrees (18, 13) in (θ, τ) for bands 0-4 and (12, 6) for
    /// bands 5-6, over the paper's domain (sun zenith 0-90°, turbidity 2.5-6, its §2.2), on
    /// 38 × 28 Chebyshev points, quadrature tolerance 2e-6.
    ///
    /// Why not the paper's (13, 7) throughout ([`Self::paper`]): measured with eqs. 2-3 against
    /// converged projections, (13, 7) leaves an E_mean of about 0.3 % at every band count
    /// (dominated by `c_00`), far above the paper's 0.005 % for up to 5 bands. The Preetham
    /// sky's coefficients have singularities close to the domain: the zenith luminance's
    /// `tan χ` (eq. 16) has a pole at sun zenith −0.28 to −0.42 rad, and the normalisation by
    /// `1 + A e^B` (eqs. 11-12) one at turbidity ≈ 1.65, which caps how fast any polynomial
    /// in (θ, τ) converges. Degrees (18, 13) bring bands 0-4 to about 1e-5; bands 5-6 only
    /// need the 1.5 % of 7 bands, so they stay small, and the 7-band table stays under 64 KB.
    ///
    /// Turbidity 2-2.5, which the Preetham sky accepts, is left out as in the paper: the pole
    /// at 1.65 is too close (fitting 2-6 at (13, 7) gives an E_mean of 5 % at one band).
    #[must_use]
    pub fn shipped(model: ModelKind) -> Self {
        Self {
            model,
            low: Degrees { theta: 18, tau: 13 },
            high: Degrees { theta: 12, tau: 6 },
            nodes_theta: 38,
            nodes_tau: 28,
            sun_zenith: [0.0, core::f32::consts::FRAC_PI_2],
            turbidity: [2.5, 6.0],
            tolerance: 2e-6,
        }
    }

    /// The paper's degrees, (13, 7) for every band, on 28 × 16 points; otherwise as
    /// [`Self::shipped`].
    #[must_use]
    pub fn paper(model: ModelKind) -> Self {
        Self {
            low: Degrees::PAPER,
            high: Degrees::PAPER,
            nodes_theta: 28,
            nodes_tau: 16,
            ..Self::shipped(model)
        }
    }

    /// The degrees of the polynomials of band `l`.
    #[must_use]
    pub fn degrees(&self, l: usize) -> Degrees {
        if l < LOW_BANDS { self.low } else { self.high }
    }

    /// The most Chebyshev sample points in each parameter (ten times the paper's degrees: the
    /// fit projects nodes_theta × nodes_turbidity skies).
    pub const MAX_NODES: usize = 200;

    /// Checks the configuration (in the command line's terms: `fit-sh` gives these flags).
    ///
    /// # Errors
    /// A [`ParamError`] when a degree is above 30, the points are fewer than the coefficients
    /// or more than [`MAX_NODES`](Self::MAX_NODES), a range is empty, or the turbidities lie
    /// outside the model's.
    pub fn validate(&self) -> Result<(), ParamError> {
        let err = |m: String| Err(ParamError(m));
        for (flag, n) in [
            ("--nodes-theta", self.nodes_theta),
            ("--nodes-turbidity", self.nodes_tau),
        ] {
            if n > Self::MAX_NODES {
                return err(format!(
                    "{flag} {n} is outside the valid range [1, {}]",
                    Self::MAX_NODES
                ));
            }
        }
        for (name, d, nodes, n) in [
            (
                "--degree-theta",
                self.low.theta,
                "--nodes-theta",
                self.nodes_theta,
            ),
            (
                "--degree-turbidity",
                self.low.tau,
                "--nodes-turbidity",
                self.nodes_tau,
            ),
            (
                "--degree-theta-high",
                self.high.theta,
                "--nodes-theta",
                self.nodes_theta,
            ),
            (
                "--degree-turbidity-high",
                self.high.tau,
                "--nodes-turbidity",
                self.nodes_tau,
            ),
        ] {
            if d > 30 {
                return err(format!("{name} {d} is outside the valid range [0, 30]"));
            }
            if n <= d {
                return err(format!(
                    "{nodes} {n}: too few sample points for a polynomial of {name} {d} (at least {})",
                    d + 1
                ));
            }
        }
        let (lo, hi) = self.model.turbidity_range();
        let [t0, t1] = self.turbidity.map(f64::from);
        let inside = |t: f64| !self.model.uses_turbidity() || (lo..=hi).contains(&t);
        if !(inside(t0) && inside(t1) && t0 < t1) {
            return err(format!(
                "--turbidity-min {} and --turbidity-max {}: expected min < max, both in [{lo}, {hi}] for --model {}",
                self.turbidity[0], self.turbidity[1], self.model
            ));
        }
        if self.sun_zenith[0].partial_cmp(&self.sun_zenith[1]) != Some(std::cmp::Ordering::Less) {
            return err("the fitted sun zeniths must not be an empty range".into());
        }
        Ok(())
    }

    /// The sky for sun zenith `theta` (radians, azimuth 0) and turbidity `tau`.
    ///
    /// # Errors
    /// When the model rejects the parameters.
    pub fn source(&self, theta: f64, tau: f64) -> Result<Box<dyn SkySource>> {
        let params = SkyParams::for_model(self.model, theta.to_degrees(), 0.0, tau);
        Ok(sources::build(self.model, &params)?)
    }

    fn theta_range(&self) -> (f64, f64) {
        (f64::from(self.sun_zenith[0]), f64::from(self.sun_zenith[1]))
    }

    fn tau_range(&self) -> (f64, f64) {
        (f64::from(self.turbidity[0]), f64::from(self.turbidity[1]))
    }
}

/// One sky's converged projection and its smallest radiance.
#[derive(Debug, Clone)]
pub struct Sample {
    /// Sun zenith, radians.
    pub theta: f64,
    /// Turbidity.
    pub tau: f64,
    /// The projected coefficients.
    pub coefficients: Coefficients,
    /// `L_min` (eqs. 2-3): the sky's smallest luminance.
    pub l_min: f64,
    /// Gauss-Legendre rows of the accepted quadrature.
    pub rows: usize,
}

impl Sample {
    /// The symmetry residual: `Σ_{m<0} |c_lm| / L_min`, the largest over channels (0 for a sky
    /// symmetric about the sun's vertical plane).
    #[must_use]
    pub fn asymmetry(&self) -> f64 {
        (0..3)
            .map(|k| {
                let mut s = 0.0;
                for l in 1..BANDS {
                    for m in 1..=l {
                        #[allow(clippy::cast_possible_wrap)]
                        let neg = index(l, -(m as isize));
                        s += self.coefficients[neg][k].abs();
                    }
                }
                s / self.l_min
            })
            .fold(0.0, f64::max)
    }
}

/// Projects the skies at every `(θ, τ)` of `points`, in parallel, in order.
///
/// # Errors
/// When a sky cannot be built or its projection does not converge.
pub fn project_all(
    config: &FitConfig,
    integrator: &Integrator,
    points: &[(f64, f64)],
) -> Result<Vec<Sample>> {
    points
        .par_iter()
        .map(|&(theta, tau)| {
            let source = config.source(theta, tau)?;
            let l_min = projection::minimum_luminance(&*source);
            let p = integrator
                .project(&*source, theta, 0.0, l_min)
                .with_context(|| format!("sun zenith {theta} rad, turbidity {tau}"))?;
            Ok(Sample {
                theta,
                tau,
                coefficients: p.coefficients,
                l_min,
                rows: p.rows,
            })
        })
        .collect()
}

/// Polynomial coefficients `[stored (l, m)][channel][i][j]`: the coefficient of
/// `T_i(u(θ)) T_j(v(τ))`.
pub type Polynomials = Vec<[Vec<Vec<f32>>; 3]>;

/// `[group][i][j]`: how the row of Chebyshev term `(i, j)` is stored, low group then high.
pub type RowWidths = [Vec<Vec<RowWidth>>; 2];

/// A fitted model: the polynomial coefficients, rounded to f32, and as stored.
///
/// Each coefficient function `c_lm(θ, τ)` is a tensor-product Chebyshev polynomial (eq. 1 in a
/// well-conditioned basis) with the degrees of its band's group. The stored table keeps the
/// row of each Chebyshev term (every `(l, m)` and channel of a group) as f32 or, where every
/// value of the row is within 32 767 (`i16`) or 127 (`i8`) steps of its group's [`STEPS`],
/// rounded to a whole number of steps.
#[derive(Debug, Clone)]
pub struct ShFit {
    /// What was fitted.
    pub config: FitConfig,
    /// `[stored (l, m)][channel][i][j]`: the coefficient of `T_i(u(θ)) T_j(v(τ))`, as stored
    /// (a value of an integer row is a whole number of steps).
    pub polynomials: Polynomials,
    /// The same, the least-squares fit rounded to f32 alone (before the integer rows).
    pub fitted: Polynomials,
    /// How the row of each Chebyshev term is stored.
    pub widths: RowWidths,
    /// The 2-norm condition number of the Chebyshev design matrix (θ ⊗ τ), the largest of the
    /// two groups.
    pub condition: f64,
    /// The same for raw monomials θ^i τ^j on the same points (eq. 1 as printed).
    pub condition_monomial: f64,
    /// The largest symmetry residual over the fit grid ([`Sample::asymmetry`]).
    pub asymmetry: f64,
    /// The most Gauss-Legendre rows any projection needed.
    pub max_rows: usize,
    /// Skies projected.
    pub samples: usize,
}

impl ShFit {
    /// Runs the projection on the Chebyshev grid and the least-squares fit.
    ///
    /// # Errors
    /// On a bad configuration, a sky the model rejects or a projection that does not converge.
    pub fn run(config: &FitConfig) -> Result<Self> {
        config.validate()?;
        let (t0, t1) = config.theta_range();
        let (u0, u1) = config.tau_range();
        let thetas = fit::chebyshev_points(config.nodes_theta, t0, t1);
        let taus = fit::chebyshev_points(config.nodes_tau, u0, u1);
        let points: Vec<(f64, f64)> = thetas
            .iter()
            .flat_map(|&t| taus.iter().map(move |&u| (t, u)))
            .collect();
        let integrator = Integrator::new(config.tolerance);
        let samples = project_all(config, &integrator, &points)?;

        let mut condition = 0.0f64;
        let mut condition_monomial = 0.0f64;
        let mut solvers = Vec::new();
        for d in [config.low, config.high] {
            let a = Matrix::chebyshev_design(&thetas, t0, t1, d.theta);
            let b = Matrix::chebyshev_design(&taus, u0, u1, d.tau);
            condition = condition.max(a.condition_number() * b.condition_number());
            condition_monomial = condition_monomial.max(
                Matrix::monomial_design(&thetas, d.theta).condition_number()
                    * Matrix::monomial_design(&taus, d.tau).condition_number(),
            );
            solvers.push((LeastSquares::new(&a), LeastSquares::new(&b)));
        }
        let exact: Vec<[Vec<Vec<f64>>; 3]> = stored_lm()
            .into_iter()
            .map(|(l, m)| {
                #[allow(clippy::cast_possible_wrap)]
                let at = index(l, m as isize);
                let (solve_a, solve_b) = &solvers[usize::from(l >= LOW_BANDS)];
                std::array::from_fn(|k| {
                    let values: Vec<Vec<f64>> = samples
                        .chunks(taus.len())
                        .map(|row| row.iter().map(|s| s.coefficients[at][k]).collect())
                        .collect();
                    fit::fit_tensor(&values, solve_a, solve_b)
                })
            })
            .collect();
        #[allow(clippy::cast_possible_truncation)] // stored as f32
        let fitted = exact
            .iter()
            .map(|p| {
                p.each_ref().map(|c| {
                    c.iter()
                        .map(|r| r.iter().map(|&v| v as f32).collect())
                        .collect()
                })
            })
            .collect();
        let (polynomials, widths) = quantise(config, &exact);
        Ok(Self {
            config: config.clone(),
            polynomials,
            fitted,
            widths,
            condition,
            condition_monomial,
            asymmetry: samples.iter().map(Sample::asymmetry).fold(0.0, f64::max),
            max_rows: samples.iter().map(|s| s.rows).max().unwrap_or(0),
            samples: samples.len(),
        })
    }

    /// The reconstructed coefficients (f64 arithmetic on the stored values) at sun zenith
    /// `theta` (radians, azimuth 0) and turbidity `tau`: the `m < 0` ones are 0.
    #[must_use]
    pub fn evaluate(&self, theta: f64, tau: f64) -> Coefficients {
        self.evaluate_polynomials(&self.polynomials, theta, tau)
    }

    /// As [`evaluate`](Self::evaluate), from the f32 fit before the integer rows
    /// ([`fitted`](Self::fitted)): their difference is the quantisation's own error.
    #[must_use]
    pub fn evaluate_fitted(&self, theta: f64, tau: f64) -> Coefficients {
        self.evaluate_polynomials(&self.fitted, theta, tau)
    }

    fn evaluate_polynomials(
        &self,
        polynomials: &[[Vec<Vec<f32>>; 3]],
        theta: f64,
        tau: f64,
    ) -> Coefficients {
        let (t0, t1) = self.config.theta_range();
        let (u0, u1) = self.config.tau_range();
        let (u, v) = (fit::normalise(theta, t0, t1), fit::normalise(tau, u0, u1));
        let mut c = [[0.0; 3]; COEFFICIENTS];
        for ((l, m), poly) in stored_lm().into_iter().zip(polynomials) {
            let d = self.config.degrees(l);
            let tu = fit::chebyshev(u, d.theta + 1);
            let tv = fit::chebyshev(v, d.tau + 1);
            #[allow(clippy::cast_possible_wrap)]
            let at = index(l, m as isize);
            for (k, p) in poly.iter().enumerate() {
                c[at][k] = p
                    .iter()
                    .zip(&tu)
                    .map(|(row, a)| {
                        a * row
                            .iter()
                            .zip(&tv)
                            .map(|(v, b)| f64::from(*v) * b)
                            .sum::<f64>()
                    })
                    .sum();
            }
        }
        c
    }

    /// Bytes of coefficient data stored for `bands` bands (as sky-core's
    /// `PolynomialTable::bytes_for_bands`).
    #[must_use]
    pub fn bytes_for_bands(&self, bands: usize) -> usize {
        let row_bytes = |group: &Vec<Vec<RowWidth>>| -> usize {
            group.iter().flatten().map(|w| w.bytes()).sum()
        };
        stored_lm()
            .into_iter()
            .filter(|&(l, _)| l < bands)
            .map(|(l, _)| 3 * row_bytes(&self.widths[usize::from(l >= LOW_BANDS)]))
            .sum()
    }
}

/// The narrowest width for a row whose largest magnitude is `steps` steps.
#[must_use]
pub fn row_width(steps: f64) -> RowWidth {
    if steps <= f64::from(i8::MAX) {
        RowWidth::I8
    } else if steps <= f64::from(i16::MAX) {
        RowWidth::I16
    } else {
        RowWidth::F32
    }
}

/// The stored tables of the least-squares polynomials `exact` (`[stored (l, m)][channel][i][j]`):
/// per group and Chebyshev term, the row of every `(l, m)` and channel at the narrowest
/// [`row_width`] for its largest value in steps of the group's [`STEPS`], an integer row's
/// values rounded to whole steps, an f32 row's to f32. Returns the stored values and the
/// widths (`[group][i][j]`).
#[must_use]
#[allow(clippy::cast_possible_truncation)] // stored as f32
pub fn quantise(config: &FitConfig, exact: &[[Vec<Vec<f64>>; 3]]) -> (Polynomials, RowWidths) {
    let lm = stored_lm();
    let widths: RowWidths = std::array::from_fn(|group| {
        let step = f64::from(STEPS[group]);
        let d = if group == 0 { config.low } else { config.high };
        let members: Vec<&[Vec<Vec<f64>>; 3]> = lm
            .iter()
            .zip(exact)
            .filter(|((l, _), _)| usize::from(*l >= LOW_BANDS) == group)
            .map(|(_, p)| p)
            .collect();
        (0..=d.theta)
            .map(|i| {
                (0..=d.tau)
                    .map(|j| {
                        let largest = members
                            .iter()
                            .flat_map(|p| p.iter().map(|c| (c[i][j] / step).round().abs()))
                            .fold(0.0, f64::max);
                        row_width(largest)
                    })
                    .collect()
            })
            .collect()
    });
    let stored = lm
        .iter()
        .zip(exact)
        .map(|(&(l, _), p)| {
            let group = usize::from(l >= LOW_BANDS);
            let step = f64::from(STEPS[group]);
            p.each_ref().map(|c| {
                c.iter()
                    .enumerate()
                    .map(|(i, row)| {
                        row.iter()
                            .enumerate()
                            .map(|(j, &v)| match widths[group][i][j] {
                                RowWidth::F32 => v as f32,
                                RowWidth::I16 | RowWidth::I8 => ((v / step).round() * step) as f32,
                            })
                            .collect()
                    })
                    .collect()
            })
        })
        .collect();
    (stored, widths)
}
