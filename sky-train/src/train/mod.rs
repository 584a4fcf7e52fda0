//! Training the neural sky (seed 000 §III-C): data sets, the paper's backpropagation with
//! momentum, and full-batch Levenberg-Marquardt, which wins by orders of magnitude for a
//! 123-parameter network (measured: docs/training.md).

pub mod backprop;
pub mod dataset;
pub mod lm;
pub mod net;

use std::path::PathBuf;
use std::time::Instant;

use anyhow::{Result, bail};
use indicatif::{ProgressBar, ProgressStyle};
use rand::SeedableRng;
use sky_core::Vec3;

use crate::sources::ModelKind;
use dataset::{DataSet, Sampling, TestImage};
use lm::{Accumulator, LeastSquares, Lm};
use net::{Net, Scratch};

/// The optimiser.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Optimizer {
    /// Full-batch Levenberg-Marquardt on the linear-radiance residuals, weighted per sky by
    /// 1/(max − min) so that the loss is the paper's NRMSE².
    Lm,
    /// Seed 000's baseline: per-example backpropagation with momentum (β = 0.01, μ = 0.9) on the
    /// eq. 9 loss over the scaled targets y = 1/(1 + 2L).
    Backprop,
}

/// What training needs to know.
#[derive(Debug, Clone)]
pub struct TrainConfig {
    /// Hidden layer sizes (`[12]` is the paper's network).
    pub hidden: Vec<usize>,
    /// The optimiser.
    pub optimizer: Optimizer,
    /// Random seed (initial weights, view jitter, example order).
    pub seed: u64,
    /// Stop after this many iterations (LM steps or backprop epochs).
    pub max_iterations: usize,
    /// Stop after this many seconds of wall time.
    pub max_seconds: f64,
    /// Stop when the validation NRMSE has not improved for this many iterations.
    pub patience: usize,
    /// Stop as soon as the validation NRMSE is at most this.
    pub target_nrmse: f64,
    /// Training-set sampling of a model's skies ([`DataSet::training`]; captured skies are
    /// sampled from their frames instead, see [`crate::captures`]).
    pub sampling: Sampling,
    /// Random starts tried (each a few iterations) before the best one is trained on.
    pub restarts: usize,
    /// Resume from and save to this checkpoint file.
    pub checkpoint: Option<PathBuf>,
    /// Start from this network and scaling (e.g. a weight file's, [`crate::export::from_weights`])
    /// instead of random starts; a checkpoint still takes precedence.
    pub init: Option<(Net, Scaling)>,
    /// Show a progress bar.
    pub progress: bool,
    /// Record when the network first reaches this mean NRMSE on these images (seed 000's
    /// Table 1 figure on its test protocol, see [`Milestone::paper`]). Only timed: the images
    /// never steer training, and they are evaluated only until the figure is reached.
    pub milestone: Option<Milestone>,
    /// Weight of each sky's irradiance residual in LM (0 = NRMSE only; 1 = a relative
    /// irradiance error costs as much as an NRMSE of the same size).
    pub irradiance_weight: f64,
}

impl TrainConfig {
    /// Defaults for `model`: the paper's network and sampling, LM, 60 s at most.
    #[must_use]
    pub fn new(model: ModelKind) -> Self {
        Self {
            hidden: vec![12],
            optimizer: Optimizer::Lm,
            seed: 1,
            max_iterations: 400,
            max_seconds: 60.0,
            patience: 40,
            target_nrmse: 0.0,
            sampling: Sampling::paper(model),
            restarts: 4,
            checkpoint: None,
            init: None,
            progress: true,
            milestone: None,
            irradiance_weight: 1.0,
        }
    }
}

impl TrainConfig {
    /// Checks what the configuration asks for is within the trainer's limits: LM trains at
    /// most [`lm::MAX_PARAMETERS`] parameters.
    ///
    /// # Errors
    /// A [`crate::args::ParamError`] naming `--hidden`, the network's parameter count and
    /// the limit.
    pub fn check(&self) -> Result<()> {
        let mut sizes = vec![6];
        sizes.extend(&self.hidden);
        sizes.push(3);
        let p = Net::param_count(&sizes);
        if self.optimizer == Optimizer::Lm && p > lm::MAX_PARAMETERS {
            let hidden: Vec<String> = self.hidden.iter().map(ToString::to_string).collect();
            return Err(crate::args::ParamError(format!(
                "--hidden {}: a network of {p} parameters; Levenberg-Marquardt trains at most {} (its normal equations are a P x P matrix per thread); use fewer neurons or --optimizer backprop",
                hidden.join(","),
                lm::MAX_PARAMETERS
            ))
            .into());
        }
        Ok(())
    }
}

/// A figure to time training against: a mean NRMSE over some images.
#[derive(Debug, Clone)]
pub struct Milestone {
    /// The mean NRMSE to reach.
    pub nrmse: f64,
    /// The images it is measured on.
    pub images: Vec<TestImage>,
}

impl Milestone {
    /// Seed 000's Table 1 NRMSE for `model` on its test protocol
    /// ([`dataset::paper_test_set`]); `None` for models the paper has no figure for.
    ///
    /// # Errors
    /// When the model rejects a test case.
    pub fn paper(model: ModelKind) -> Result<Option<Self>> {
        let Some(figures) = dataset::PaperFigures::of(model) else {
            return Ok(None);
        };
        Ok(Some(Self {
            nrmse: figures.nrmse,
            images: dataset::paper_test_set(model)?,
        }))
    }
}

/// A training whose best validation NRMSE is above this (or not a number) has diverged: its
/// error exceeds the whole range of the sky's radiance, worse than any constant sky, and
/// [`train`] returns an error instead of the network.
pub const DIVERGED_NRMSE: f64 = 1.0;

/// What early stopping watches: the mean NRMSE of a network on skies it is not trained on.
pub trait Validation {
    /// The mean NRMSE of `trained` over the validation skies.
    fn mean_nrmse(&self, trained: &Trained) -> f64;
}

impl Validation for [TestImage] {
    fn mean_nrmse(&self, trained: &Trained) -> f64 {
        trained.mean_nrmse(self)
    }
}

/// Input standardisation and output scaling of a trained network.
#[derive(Debug, Clone, PartialEq)]
pub struct Scaling {
    /// u_k = (V_k − offset_k) · scale_k.
    pub input_offset: [f64; 6],
    /// See `input_offset`.
    pub input_scale: [f64; 6],
    /// Radiance = output_scale · ½ z².
    pub output_scale: f64,
}

impl Scaling {
    /// Standardises every input over `set` (zero mean, unit variance; an input with no spread,
    /// such as a zeroed turbidity, gets scale 0) and scales radiance by its mean.
    #[must_use]
    pub fn fit(set: &DataSet) -> Self {
        #[allow(clippy::cast_precision_loss)]
        let n = set.inputs.len().max(1) as f64;
        let mut input_offset = [0.0; 6];
        let mut input_scale = [0.0; 6];
        for k in 0..6 {
            let mean = set.inputs.iter().map(|v| v[k]).sum::<f64>() / n;
            let var = set
                .inputs
                .iter()
                .map(|v| (v[k] - mean).powi(2))
                .sum::<f64>()
                / n;
            input_offset[k] = mean;
            input_scale[k] = if var > 1e-18 { 1.0 / var.sqrt() } else { 0.0 };
        }
        let mean = set.targets.iter().flatten().sum::<f64>() / (3.0 * n);
        Self {
            input_offset,
            input_scale,
            output_scale: if mean > 0.0 { mean } else { 1.0 },
        }
    }

    /// The normalised input u of V.
    #[must_use]
    pub fn apply(&self, v: &[f64; 6]) -> [f64; 6] {
        std::array::from_fn(|k| (v[k] - self.input_offset[k]) * self.input_scale[k])
    }
}

/// The least-squares problem LM solves: per example and channel, the residual
/// w_case (½ z² − L / s), with w_case = 1 / (max − min) of the case's scaled targets.
///
/// Each sky also contributes one residual for its irradiance (eq. 11): λ (Î − I)/I with Î, I
/// the network's and the model's cosine-weighted sums of luminance over the sky's views
/// (weights cos θ sin θ for views stratified uniformly in θ and φ), and
/// λ = `irradiance_weight` · √(residuals of the sky), so that a relative irradiance error costs
/// as much as an NRMSE of the same size.
struct Problem<'a> {
    net: &'a Net,
    inputs: Vec<[f64; 6]>,
    targets: Vec<[f64; 3]>,
    weights: Vec<f64>,
    /// Quadrature weight cos θ sin θ of each example's view.
    quadrature: Vec<f64>,
    /// Examples of each sky.
    members: Vec<Vec<usize>>,
    /// Reference irradiance of each sky (scaled units).
    irradiance: Vec<f64>,
    /// λ per sky (0: no irradiance residuals).
    lambda: Vec<f64>,
}

/// Luminance of linear sRGB (the middle row of the sRGB → XYZ matrix).
const LUMINANCE: [f64; 3] = [0.2126, 0.7152, 0.0722];

impl<'a> Problem<'a> {
    fn new(net: &'a Net, set: &DataSet, scaling: &Scaling, irradiance_weight: f64) -> Self {
        let mut lo = vec![f64::INFINITY; set.cases.len()];
        let mut hi = vec![f64::NEG_INFINITY; set.cases.len()];
        let targets: Vec<[f64; 3]> = set
            .targets
            .iter()
            .map(|t| t.map(|c| c / scaling.output_scale))
            .collect();
        for (t, &k) in targets.iter().zip(&set.case) {
            for c in t {
                lo[k] = lo[k].min(*c);
                hi[k] = hi[k].max(*c);
            }
        }
        let quadrature: Vec<f64> = set
            .inputs
            .iter()
            .map(|v| v[4].max(0.0) * (1.0 - v[4] * v[4]).max(0.0).sqrt())
            .collect();
        let mut members = vec![Vec::new(); set.cases.len()];
        for (i, &k) in set.case.iter().enumerate() {
            members[k].push(i);
        }
        let irradiance: Vec<f64> = members
            .iter()
            .map(|m| {
                m.iter()
                    .map(|&i| quadrature[i] * dot(LUMINANCE, targets[i]))
                    .sum::<f64>()
            })
            .collect();
        #[allow(clippy::cast_precision_loss)]
        let lambda = members
            .iter()
            .map(|m| irradiance_weight * (3.0 * m.len() as f64).sqrt())
            .collect();
        Self {
            net,
            inputs: set.inputs.iter().map(|v| scaling.apply(v)).collect(),
            weights: set
                .case
                .iter()
                .map(|&k| 1.0 / (hi[k] - lo[k]).max(1e-9))
                .collect(),
            targets,
            quadrature,
            members,
            irradiance,
            lambda,
        }
    }

    /// The irradiance residual of sky `k` (see the type's docs).
    fn accumulate_irradiance(&self, params: &[f64], k: usize, acc: &mut Accumulator, normal: bool) {
        let (lambda, reference) = (self.lambda[k], self.irradiance[k]);
        if lambda == 0.0 || reference <= 0.0 {
            return;
        }
        let sizes = &self.net.sizes;
        let mut predicted = 0.0;
        let mut gradient = vec![0.0; if normal { params.len() } else { 0 }];
        let mut rows = std::mem::take(&mut acc.rows);
        for &i in &self.members[k] {
            let q = self.quadrature[i];
            let z = if normal {
                net::jacobian(sizes, params, &self.inputs[i], &mut acc.scratch, &mut rows)
            } else {
                net::forward(sizes, params, &self.inputs[i], &mut acc.scratch)
            };
            predicted += q
                * (0..3)
                    .map(|c| LUMINANCE[c] * 0.5 * z[c] * z[c])
                    .sum::<f64>();
            if normal {
                for c in 0..3 {
                    let f = q * LUMINANCE[c] * z[c];
                    for (g, r) in gradient.iter_mut().zip(&rows[c]) {
                        *g += f * r;
                    }
                }
            }
        }
        acc.rows = rows;
        let scale = lambda / reference;
        let r = scale * (predicted - reference);
        acc.cost += r * r;
        if normal {
            for g in &mut gradient {
                *g *= scale;
            }
            acc.add_row(r, &gradient);
        }
    }
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

impl LeastSquares for Problem<'_> {
    fn examples(&self) -> usize {
        self.inputs.len() + self.members.len()
    }

    #[inline(always)]
    fn accumulate(&self, params: &[f64], i: usize, acc: &mut Accumulator, normal: bool) {
        if i >= self.inputs.len() {
            self.accumulate_irradiance(params, i - self.inputs.len(), acc, normal);
            return;
        }
        let w = self.weights[i];
        let sizes = &self.net.sizes;
        if normal {
            let mut rows = std::mem::take(&mut acc.rows);
            let z = net::jacobian(sizes, params, &self.inputs[i], &mut acc.scratch, &mut rows);
            for c in 0..3 {
                let r = w * (0.5 * z[c] * z[c] - self.targets[i][c]);
                acc.cost += r * r;
                let scale = w * z[c];
                for g in &mut rows[c] {
                    *g *= scale;
                }
                acc.add_row(r, &rows[c]);
            }
            acc.rows = rows;
        } else {
            let z = net::forward(sizes, params, &self.inputs[i], &mut acc.scratch);
            for c in 0..3 {
                let r = w * (0.5 * z[c] * z[c] - self.targets[i][c]);
                acc.cost += r * r;
            }
        }
    }
}

/// A trained network with its scaling and how it was obtained.
#[derive(Debug, Clone)]
pub struct Trained {
    /// The network.
    pub net: Net,
    /// Its input/output normalisation.
    pub scaling: Scaling,
    /// Mean validation NRMSE.
    pub validation_nrmse: f64,
    /// Iterations run.
    pub iterations: usize,
    /// Wall time in seconds.
    pub seconds: f64,
    /// Training examples.
    pub examples: usize,
    /// Wall seconds and iterations until the configured [`Milestone`] was first reached.
    pub milestone: Option<(f64, usize)>,
}

impl Trained {
    /// Linear RGB radiance predicted for `image`'s sky at the test directions, with the sun at
    /// [`dataset::TEST_SUN_AZIMUTH`] (views rotated by eq. 10).
    #[must_use]
    pub fn predict(&self, case: dataset::SkyCase, dirs: &[Vec3], sun_azimuth: f64) -> Vec<Vec3> {
        let rotate = sun_azimuth - std::f64::consts::PI;
        let (sr, cr) = rotate.sin_cos();
        let mut s = Scratch::default();
        dirs.iter()
            .map(|d| {
                let (x0, y0, z0) = (f64::from(d.x), f64::from(d.y), f64::from(d.z));
                let v = [x0 * cr + y0 * sr, y0 * cr - x0 * sr, z0];
                let u = self
                    .scaling
                    .apply(&dataset::input(case.turbidity, case.sun_zenith, v));
                let z = self.net.forward(&u, &mut s);
                #[allow(clippy::cast_possible_truncation)]
                let c = z.map(|z| (self.scaling.output_scale * 0.5 * z * z) as f32);
                Vec3::from_array(c)
            })
            .collect()
    }

    /// Mean NRMSE over `images`.
    #[must_use]
    pub fn mean_nrmse(&self, images: &[TestImage]) -> f64 {
        use rayon::prelude::*;
        let dirs = dataset::test_directions();
        // Summed in image order whatever the threads do: reproducible bit for bit.
        let per_image: Vec<f64> = images
            .par_iter()
            .map(|im| {
                let p = self.predict(im.case, &dirs, dataset::TEST_SUN_AZIMUTH);
                dataset::nrmse(&im.reference, &p)
            })
            .collect();
        #[allow(clippy::cast_precision_loss)]
        let n = images.len().max(1) as f64;
        per_image.iter().sum::<f64>() / n
    }
}

/// The validation images used for early stopping: turbidities half-way between the test
/// turbidities' neighbours and the training ones (never a test or training sky), 5 sun zeniths.
///
/// # Errors
/// When the model rejects a case.
pub fn validation_set(model: ModelKind) -> Result<Vec<TestImage>> {
    if !model.uses_turbidity() {
        // One atmosphere: 4 sun zeniths between the test ones (multiples of 15°).
        let zeniths: Vec<f64> = (0..4)
            .map(|i| std::f64::consts::FRAC_PI_2 * (f64::from(i) + 0.5) / 4.0)
            .collect();
        return dataset::test_set(model, &[0.0], &zeniths);
    }
    let (lo, hi) = model.turbidity_range();
    let turbidities = [lo + 0.25, 0.5 * (lo + hi) + 0.25, hi - 0.25];
    dataset::test_set(model, &turbidities, &dataset::sun_zeniths(5))
}

fn progress_bar(config: &TrainConfig) -> ProgressBar {
    if !config.progress {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::new(config.max_iterations as u64);
    bar.set_style(
        ProgressStyle::with_template("{spinner} {elapsed:>4} [{bar:30}] {pos}/{len} {msg}")
            .unwrap_or_else(|_| ProgressStyle::default_bar())
            .progress_chars("=> "),
    );
    bar
}

/// Trains a network as `config` says, on `set` (a model's skies, [`DataSet::training`], or
/// captured frames, [`crate::captures`]), stopping early on `validation`.
///
/// # Errors
/// When the checkpoint cannot be read or written, or when training diverged (its best
/// validation NRMSE is above [`DIVERGED_NRMSE`] or not a number).
pub fn train<V: Validation + ?Sized>(
    config: &TrainConfig,
    set: &DataSet,
    validation: &V,
) -> Result<Trained> {
    let start = Instant::now();
    config.check()?;
    // Every step, the initial race included, stops when the wall-time budget is spent.
    let deadline = start + std::time::Duration::from_secs_f64(config.max_seconds.clamp(0.0, 1e9));
    let scaling = config
        .init
        .as_ref()
        .map_or_else(|| Scaling::fit(set), |(_, s)| s.clone());
    let mut sizes = vec![6];
    sizes.extend(&config.hidden);
    sizes.push(3);
    let bar = progress_bar(config);

    let resumed = match &config.checkpoint {
        Some(path) => checkpoint::resume(path, &sizes)?,
        None => None,
    };
    let (mut net, first_iteration, resumed_lambda) = match resumed {
        Some(r) => (r.net, r.iteration, r.lambda),
        None => match &config.init {
            Some((net, _)) if net.sizes == sizes => (net.clone(), 0, None),
            Some((net, _)) => bail!(
                "the initial network is {:?}, this run trains {sizes:?}",
                net.sizes
            ),
            None => (
                initial_net(config, &sizes, set, &scaling, deadline),
                0,
                None,
            ),
        },
    };
    let mut best = Trained {
        net: net.clone(),
        scaling: scaling.clone(),
        validation_nrmse: f64::INFINITY,
        iterations: first_iteration,
        seconds: 0.0,
        examples: set.inputs.len(),
        milestone: None,
    };
    best.validation_nrmse = validation.mean_nrmse(&best);
    let mut milestone = None;
    let mut since_best = 0;
    let mut lm_state: Option<Lm> = None;
    let mut momentum = vec![0.0; net.params.len()];
    let mut rng = rand::rngs::StdRng::seed_from_u64(config.seed.wrapping_add(17));
    bar.set_position(first_iteration as u64);
    for iteration in first_iteration..config.max_iterations {
        let moved = match config.optimizer {
            Optimizer::Lm => {
                let problem = Problem::new(&net, set, &scaling, config.irradiance_weight);
                let state = lm_state.get_or_insert_with(|| {
                    let mut lm = Lm::new(&problem, net.params.clone(), Some(deadline));
                    lm.lambda = resumed_lambda.unwrap_or(lm.lambda);
                    lm
                });
                let moved = state.step(&problem);
                net.params.clone_from(&state.params);
                moved
            }
            Optimizer::Backprop => {
                backprop::epoch(&mut net, &mut momentum, set, &scaling, &mut rng, deadline);
                true
            }
        };
        let current = Trained {
            net: net.clone(),
            scaling: scaling.clone(),
            validation_nrmse: 0.0,
            iterations: iteration + 1,
            seconds: start.elapsed().as_secs_f64(),
            examples: set.inputs.len(),
            milestone: None,
        };
        let v = validation.mean_nrmse(&current);
        if let Some(m) = config.milestone.as_ref().filter(|_| milestone.is_none())
            && current.mean_nrmse(&m.images) <= m.nrmse
        {
            milestone = Some((start.elapsed().as_secs_f64(), iteration + 1));
        }
        if v < best.validation_nrmse {
            best = Trained {
                validation_nrmse: v,
                ..current
            };
            since_best = 0;
        } else {
            since_best += 1;
        }
        bar.set_position(iteration as u64 + 1);
        bar.set_message(format!(
            "validation NRMSE {v:.5} (best {:.5})",
            best.validation_nrmse
        ));
        if !net.params.iter().all(|p| p.is_finite()) {
            break; // diverged (backprop); the best network so far is kept
        }
        if let Some(path) = &config.checkpoint {
            let lambda = lm_state.as_ref().map(|lm| lm.lambda);
            checkpoint::write(path, &net, iteration + 1, lambda)?;
        }
        let elapsed = start.elapsed().as_secs_f64();
        if !moved
            || since_best >= config.patience
            || elapsed >= config.max_seconds
            || best.validation_nrmse <= config.target_nrmse
        {
            break;
        }
    }
    bar.finish_and_clear();
    if best.validation_nrmse.is_nan() || best.validation_nrmse > DIVERGED_NRMSE {
        bail!(
            "training diverged: the best validation NRMSE is {} after {} iterations (a usable \
             network is below {DIVERGED_NRMSE}); check the training data's values",
            best.validation_nrmse,
            best.iterations
        );
    }
    best.seconds = start.elapsed().as_secs_f64();
    best.milestone = milestone;
    Ok(best)
}

/// The starting network: the best of `config.restarts` random starts after a few LM steps each
/// (random starts of a 123-parameter network differ a lot; a short race is cheap).
///
/// The race shares the run's clock: it stops at `deadline`, with the best start so far.
fn initial_net(
    config: &TrainConfig,
    sizes: &[usize],
    set: &DataSet,
    scaling: &Scaling,
    deadline: Instant,
) -> Net {
    let mut rng = rand::rngs::StdRng::seed_from_u64(config.seed);
    let candidates: Vec<Net> = (0..config.restarts.max(1))
        .map(|_| Net::random(sizes, &mut rng, 1.0))
        .collect();
    if config.optimizer == Optimizer::Backprop || candidates.len() == 1 {
        return candidates
            .into_iter()
            .next()
            .unwrap_or_else(|| Net::random(sizes, &mut rng, 1.0));
    }
    // The race runs on every 8th example: enough to rank the starts, 8 times cheaper.
    let subsample = DataSet {
        inputs: set.inputs.iter().step_by(8).copied().collect(),
        targets: set.targets.iter().step_by(8).copied().collect(),
        case: set.case.iter().step_by(8).copied().collect(),
        cases: set.cases.clone(),
    };
    let mut best: Option<(f64, Net)> = None;
    for mut net in candidates {
        let problem = Problem::new(&net, &subsample, scaling, config.irradiance_weight);
        let mut state = Lm::new(&problem, net.params.clone(), Some(deadline));
        for _ in 0..5 {
            if !state.step(&problem) {
                break;
            }
        }
        net.params = state.params;
        if best.as_ref().is_none_or(|(c, _)| state.cost < *c) {
            best = Some((state.cost, net));
        }
    }
    best.map_or_else(|| Net::random(sizes, &mut rng, 1.0), |(_, n)| n)
}

/// Checkpoints: the iteration count, Levenberg-Marquardt's damping and the parameters, written
/// atomically after every iteration, so that a killed run resumes where it stopped and, with LM,
/// continues exactly as the run would have (backprop resumes with zero momentum).
pub mod checkpoint {
    use std::path::Path;

    use anyhow::{Result, bail};

    use super::Net;
    use crate::args::ParamError;
    use crate::image_io::write_text;

    /// What a checkpoint holds.
    #[derive(Debug, Clone, PartialEq)]
    pub struct Resume {
        /// The network after `iteration` iterations.
        pub net: Net,
        /// Iterations done.
        pub iteration: usize,
        /// LM's damping λ at that point (`None` for backprop or a version-1 file).
        pub lambda: Option<f64>,
    }

    /// Writes `net`, `iteration` and LM's `lambda` to `path`.
    ///
    /// # Errors
    /// On I/O errors.
    pub fn write(path: &Path, net: &Net, iteration: usize, lambda: Option<f64>) -> Result<()> {
        let sizes: Vec<String> = net.sizes.iter().map(ToString::to_string).collect();
        let params: Vec<String> = net.params.iter().map(|p| format!("{p:e}")).collect();
        let lambda = lambda.map_or_else(|| "none".to_string(), |l| format!("{l:e}"));
        write_text(
            path,
            &format!(
                "sky-train checkpoint 2\nsizes {}\niteration {iteration}\nlambda {lambda}\n{}\n",
                sizes.join(" "),
                params.join("\n")
            ),
        )
    }

    /// The checkpoint to resume from at `path` (`--checkpoint`), `None` when there is none yet.
    ///
    /// # Errors
    /// A [`ParamError`] (bad input, exit status 2) naming `--checkpoint` when the file cannot
    /// be read or is not a checkpoint of a network with `sizes`.
    pub fn resume(path: &Path, sizes: &[usize]) -> Result<Option<Resume>, ParamError> {
        if !path.exists() {
            return Ok(None);
        }
        read(path, sizes).map(Some).map_err(|e| {
            ParamError(format!(
                "--checkpoint {}: cannot resume: {e:#}",
                path.display()
            ))
        })
    }

    /// Reads a checkpoint of a network with `sizes` (version 2, or version 1 without λ).
    ///
    /// # Errors
    /// When the file cannot be read, is longer than a checkpoint of that shape can be, or is
    /// not one.
    pub fn read(path: &Path, sizes: &[usize]) -> Result<Resume> {
        use std::io::Read;
        // The header, then one parameter a line as `{:e}` writes an f64 (at most 24 bytes).
        let limit = 256 + 32 * Net::param_count(sizes) as u64;
        let mut text = String::new();
        crate::csv_input::open(path, limit)
            .and_then(|mut f| f.read_to_string(&mut text))
            .map_err(|e| {
                anyhow::anyhow!(
                    "{e} (a checkpoint of a {sizes:?} network has {limit} bytes at most)"
                )
            })?;
        if let Some(n) = text
            .lines()
            .position(|l| l.len() > crate::csv_input::MAX_LINE_BYTES)
        {
            bail!(
                "line {}: longer than {} bytes",
                n + 1,
                crate::csv_input::MAX_LINE_BYTES
            );
        }
        let mut lines = text.lines().peekable();
        let version = match lines.next() {
            Some("sky-train checkpoint 1") => 1,
            Some("sky-train checkpoint 2") => 2,
            _ => bail!("not a sky-train checkpoint (version 1 or 2)"),
        };
        let found: Vec<usize> = lines
            .next()
            .and_then(|l| l.strip_prefix("sizes "))
            .map(|l| l.split(' ').filter_map(|s| s.parse().ok()).collect())
            .unwrap_or_default();
        if found != sizes {
            bail!("the checkpoint is a {found:?} network, this run trains {sizes:?}");
        }
        let iteration = lines
            .next()
            .and_then(|l| l.strip_prefix("iteration "))
            .and_then(|l| l.parse().ok())
            .ok_or_else(|| anyhow::anyhow!("no iteration line"))?;
        let lambda = if version == 2 {
            match lines.next().and_then(|l| l.strip_prefix("lambda ")) {
                Some("none") => None,
                Some(l) => Some(
                    l.parse::<f64>()
                        .ok()
                        .filter(|l| l.is_finite() && *l > 0.0)
                        .ok_or_else(|| anyhow::anyhow!("lambda `{l}` is not a positive number"))?,
                ),
                None => bail!("no lambda line"),
            }
        } else {
            None
        };
        let params: Vec<f64> = lines.map(str::parse).collect::<Result<_, _>>()?;
        if params.len() != Net::param_count(sizes) {
            bail!(
                "the checkpoint holds {} parameters, a {sizes:?} network has {}",
                params.len(),
                Net::param_count(sizes)
            );
        }
        // A weight file holds f32: a parameter beyond f32's range could never be written.
        if let Some(p) = params
            .iter()
            .find(|p| p.is_nan() || p.abs() > f64::from(f32::MAX))
        {
            bail!("the checkpoint's parameter {p:e} is not a finite f32");
        }
        Ok(Resume {
            net: Net {
                sizes: sizes.to_vec(),
                params,
            },
            iteration,
            lambda,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A small Preetham training problem: 3 turbidities x 4 sun zeniths x 4 x 8 views.
    fn small() -> (TrainConfig, DataSet, Vec<TestImage>) {
        let mut config = TrainConfig::new(ModelKind::Preetham);
        config.sampling.turbidities = vec![2.0, 4.0, 6.0];
        config.sampling.sun_zeniths = 4;
        (config.sampling.view_zeniths, config.sampling.view_azimuths) = (4, 8);
        config.progress = false;
        config.restarts = 2;
        config.patience = 1000;
        let set = DataSet::training(ModelKind::Preetham, &config.sampling).expect("valid");
        let validation = dataset::test_set(ModelKind::Preetham, &[3.0], &[0.5]).expect("valid");
        (config, set, validation)
    }

    /// The same seed gives the same network bit for bit, whatever the threads did.
    #[test]
    fn training_is_deterministic() {
        let (mut config, set, validation) = small();
        config.max_iterations = 4;
        let a = train(&config, &set, validation.as_slice()).expect("trains");
        let b = train(&config, &set, validation.as_slice()).expect("trains");
        assert_eq!(a.net, b.net);
        config.seed += 1;
        let c = train(&config, &set, validation.as_slice()).expect("trains");
        assert_ne!(a.net, c.net, "another seed, another start");
    }

    /// A run stopped after 3 iterations and resumed from its checkpoint to 6 ends exactly where
    /// an uninterrupted run of 6 does.
    #[test]
    fn a_resumed_run_continues_exactly() {
        let dir = tempfile::tempdir().expect("temp dir");
        let (mut config, set, validation) = small();
        let sizes = [6, 12, 3];
        config.max_iterations = 6;
        config.checkpoint = Some(dir.path().join("straight.ckpt"));
        train(&config, &set, validation.as_slice()).expect("trains");
        let straight = checkpoint::read(&dir.path().join("straight.ckpt"), &sizes).expect("reads");

        config.checkpoint = Some(dir.path().join("resumed.ckpt"));
        config.max_iterations = 3;
        train(&config, &set, validation.as_slice()).expect("trains");
        let halfway = checkpoint::read(&dir.path().join("resumed.ckpt"), &sizes).expect("reads");
        assert_eq!(halfway.iteration, 3);
        config.max_iterations = 6;
        train(&config, &set, validation.as_slice()).expect("resumes");
        let resumed = checkpoint::read(&dir.path().join("resumed.ckpt"), &sizes).expect("reads");
        assert_eq!(resumed, straight);
        assert_eq!(resumed.iteration, 6);
        assert!(resumed.lambda.is_some());

        // A checkpoint of another shape is refused, naming both.
        let e = checkpoint::read(&dir.path().join("resumed.ckpt"), &[6, 24, 3])
            .expect_err("wrong shape")
            .to_string();
        assert!(e.contains("[6, 12, 3]") && e.contains("[6, 24, 3]"), "{e}");
    }
}
