//! `sky-train size-study`: what the network's size buys. Seed 000's 6-12-3 network against
//! narrower, wider and deeper ones, each trained the same way and measured the same way: mean
//! NRMSE and irradiance difference on the paper's test protocol (§IV-A), bytes of weights, and
//! nanoseconds per direction of the f32 batch evaluation.
//!
//! One-hidden-layer networks are evaluated by sky-core's own [`NeuralSky`] (the code that
//! ships); the two-hidden-layer network by [`TwoLayerSky`] below, written the same way (input
//! scaling and eq. 10's rotation folded into the first layer, 16 directions a step).

use std::sync::Arc;
use std::time::Instant;

use anyhow::{Result, bail};
use sky_core::neural::NeuralSky;
use sky_core::{Sun, Vec3};

use crate::bench;
use crate::dispatch;
use crate::export;
use crate::sources::{ModelKind, ParamError, SkyParams, SkySource};
use crate::train::{self, TrainConfig, Trained};

/// One network of the study.
#[derive(Debug, Clone)]
pub struct Row {
    /// Hidden layer sizes.
    pub hidden: Vec<usize>,
    /// Weights and biases.
    pub parameters: usize,
    /// Bytes of f32 weights and biases.
    pub bytes: usize,
    /// Mean NRMSE on the paper's test protocol (f32 evaluation).
    pub nrmse: f64,
    /// Mean relative irradiance difference (eq. 11).
    pub irradiance: f64,
    /// Nanoseconds per direction of the batch evaluation (median of runs, one thread).
    pub ns_per_direction: f64,
    /// Training iterations and wall seconds.
    pub iterations: usize,
    /// See `iterations`.
    pub seconds: f64,
}

/// Trains one network per entry of `layouts` on `model` (the defaults of
/// [`TrainConfig::new`] with `irradiance_weight`, at most `seconds` each) and measures it.
///
/// # Errors
/// For a layout the study cannot evaluate (one hidden layer of 6, 12, 24 or 48 neurons, or two
/// of 12), or when the model rejects a case.
pub fn run(
    model: ModelKind,
    layouts: &[Vec<usize>],
    seconds: f64,
    seed: u64,
    irradiance_weight: f64,
    progress: bool,
) -> Result<Vec<Row>> {
    for hidden in layouts {
        if !matches!(hidden.as_slice(), [6 | 12 | 24 | 48] | [12, 12]) {
            return Err(crate::args::ParamError(format!(
                "--layouts: hidden layers {hidden:?} are not one of 6, 12, 24, 48 or 12,12"
            ))
            .into());
        }
    }
    let mut config = TrainConfig::new(model);
    config.max_seconds = seconds;
    config.max_iterations = 100_000;
    config.seed = seed;
    config.sampling.seed = seed;
    config.irradiance_weight = irradiance_weight;
    config.progress = progress;
    let set = train::dataset::DataSet::training(model, &config.sampling)?;
    let validation = train::validation_set(model)?;
    let trained = layouts
        .iter()
        .map(|hidden| {
            config.hidden.clone_from(hidden);
            Ok(Arc::new(train::train(
                &config,
                &set,
                validation.as_slice(),
            )?))
        })
        .collect::<Result<Vec<_>>>()?;
    let ns = time_per_direction(model, &trained)?;
    trained
        .into_iter()
        .zip(ns)
        .map(|(trained, ns_per_direction)| {
            let net = Arc::clone(&trained);
            let network = move |p: &SkyParams| -> Result<Box<dyn SkySource>> {
                Ok(Box::new(StudySky::new(&net, model, p)?))
            };
            let evaluation = crate::eval::evaluate(model, &network)?;
            let parameters = trained.net.params.len();
            Ok(Row {
                hidden: trained.net.sizes[1..trained.net.sizes.len() - 1].to_vec(),
                parameters,
                bytes: 4 * parameters,
                nrmse: evaluation.mean_nrmse(),
                irradiance: evaluation.mean_irradiance_relative(),
                ns_per_direction,
                iterations: trained.iterations,
                seconds: trained.seconds,
            })
        })
        .collect()
}

/// Nanoseconds per direction of each network's batch evaluation over 1024 × 512 directions,
/// one thread: the median of 15 rounds, each round timing every network once in turn, so that
/// the machine's load drifts over all of them alike.
fn time_per_direction(model: ModelKind, trained: &[Arc<Trained>]) -> Result<Vec<f64>> {
    const ROUNDS: usize = 15;
    let dirs = bench::hemisphere_directions(1024, 512);
    let params = SkyParams::for_model(model, 0.9f64.to_degrees(), 17.0, 3.0);
    let skies = trained
        .iter()
        .map(|t| StudySky::new(t, model, &params))
        .collect::<Result<Vec<_>>>()?;
    let mut out = vec![Vec3::ZERO; dirs.len()];
    let mut times = vec![Vec::with_capacity(ROUNDS); skies.len()];
    for round in 0..=ROUNDS {
        for (sky, t) in skies.iter().zip(&mut times) {
            let start = Instant::now();
            sky.rgb_batch(std::hint::black_box(&dirs), &mut out);
            std::hint::black_box(&out);
            if round > 0 {
                // Round 0 warms up.
                t.push(start.elapsed());
            }
        }
    }
    Ok(times
        .into_iter()
        .map(|mut t| {
            t.sort();
            bench::per_direction(t[t.len() / 2], dirs.len())
        })
        .collect())
}

/// The study's table in Markdown.
#[must_use]
pub fn table(model: ModelKind, rows: &[Row]) -> String {
    let mut s = format!(
        "| {model}: hidden layers | weights | bytes | mean NRMSE | irradiance difference | ns/direction | training |\n|---|---:|---:|---:|---:|---:|---|\n"
    );
    for r in rows {
        let layers: Vec<String> = r.hidden.iter().map(ToString::to_string).collect();
        s += &format!(
            "| 6-{}-3 | {} | {} | {:.4} | {:.2} % | {:.2} | {} iterations, {:.0} s |\n",
            layers.join("-"),
            r.parameters,
            r.bytes,
            r.nrmse,
            100.0 * r.irradiance,
            r.ns_per_direction,
            r.iterations,
            r.seconds
        );
    }
    s
}

/// A trained network of the study as a sky for one sun and turbidity.
#[allow(clippy::large_enum_variant)] // one at a time, never in a collection
enum StudySky {
    H6(NeuralSky<6>),
    H12(NeuralSky<12>),
    H24(NeuralSky<24>),
    H48(NeuralSky<48>),
    TwoLayer(TwoLayerSky<12, 12>),
}

impl StudySky {
    fn new(trained: &Trained, model: ModelKind, p: &SkyParams) -> Result<Self> {
        let sun = p.required_sun(model)?;
        #[allow(clippy::cast_possible_truncation)]
        let t = p.turbidity.unwrap_or(0.0) as f32;
        let e = |e: sky_core::SkyError| ParamError(e.to_string());
        macro_rules! one_layer {
            ($h:literal, $variant:ident) => {
                Self::$variant(
                    NeuralSky::<$h>::new(&export::to_weights::<$h>(trained, model, 0)?, sun, t)
                        .map_err(e)?,
                )
            };
        }
        Ok(match trained.net.sizes.as_slice() {
            [6, 6, 3] => one_layer!(6, H6),
            [6, 12, 3] => one_layer!(12, H12),
            [6, 24, 3] => one_layer!(24, H24),
            [6, 48, 3] => one_layer!(48, H48),
            [6, 12, 12, 3] => Self::TwoLayer(TwoLayerSky::new(trained, sun, t)),
            other => bail!("size study: no evaluator for a {other:?} network"),
        })
    }
}

impl SkySource for StudySky {
    fn describe(&self) -> String {
        "size-study network".into()
    }

    fn rgb_batch(&self, dirs: &[Vec3], out: &mut [Vec3]) {
        match self {
            Self::H6(s) => dispatch::neural_batch(s, dirs, out),
            Self::H12(s) => dispatch::neural_batch(s, dirs, out),
            Self::H24(s) => dispatch::neural_batch(s, dirs, out),
            Self::H48(s) => dispatch::neural_batch(s, dirs, out),
            Self::TwoLayer(s) => dispatch::fastest(
                #[inline(always)]
                || s.rgb_batch(dirs, out),
            ),
        }
    }
}

/// A 6-A-B-3 network in f32 for one sky, evaluated like [`NeuralSky`]: the sky-dependent
/// inputs, the input scaling and eq. 10's rotation folded into the first layer; then a second
/// hidden layer with the same activation f(x) = 1/(1 + x²); radiance ½ z² · scale.
pub struct TwoLayerSky<const A: usize, const B: usize> {
    sun: Vec3,
    constant: [f32; A],
    coeff: [[f32; 4]; A],
    second: [[f32; A]; B],
    second_bias: [f32; B],
    output: [[f32; B]; 3],
    output_bias: [f32; 3],
    half_scale: f32,
}

impl<const A: usize, const B: usize> TwoLayerSky<A, B> {
    /// The sky of a trained 6-A-B-3 network for `sun` and `turbidity` (not range-checked).
    ///
    /// # Panics
    /// When `trained` is not a 6-A-B-3 network.
    #[must_use]
    #[allow(clippy::cast_possible_truncation)]
    pub fn new(trained: &Trained, sun: Sun, turbidity: f32) -> Self {
        assert_eq!(trained.net.sizes, [6, A, B, 3], "not a 6-{A}-{B}-3 network");
        let p = &trained.net.params;
        let s = &trained.scaling;
        let rotate = f64::from(sun.azimuth()) - std::f64::consts::PI;
        let (sin_r, cos_r) = rotate.sin_cos();
        let sky_inputs = [f64::from(turbidity).sqrt(), f64::from(sun.zenith())];
        let mut sky = Self {
            sun: sun.direction(),
            constant: [0.0; A],
            coeff: [[0.0; 4]; A],
            second: [[0.0; A]; B],
            second_bias: [0.0; B],
            output: [[0.0; B]; 3],
            output_bias: [0.0; 3],
            half_scale: (0.5 * s.output_scale) as f32,
        };
        for j in 0..A {
            // u_k = (V_k − off_k) sc_k folded into the weights, as in `NeuralSky::new`.
            let ws: [f64; 6] = std::array::from_fn(|k| p[j * 6 + k] * s.input_scale[k]);
            let shift: f64 = (0..6).map(|k| ws[k] * s.input_offset[k]).sum();
            let constant = p[6 * A + j] + ws[0] * sky_inputs[0] + ws[1] * sky_inputs[1] - shift;
            sky.constant[j] = constant as f32;
            sky.coeff[j] = [
                ws[2] * cos_r - ws[3] * sin_r,
                ws[2] * sin_r + ws[3] * cos_r,
                ws[4],
                ws[5],
            ]
            .map(|c| c as f32);
        }
        let base = 7 * A;
        for k in 0..B {
            sky.second[k] = std::array::from_fn(|j| p[base + k * A + j] as f32);
            sky.second_bias[k] = p[base + B * A + k] as f32;
        }
        let base = base + B * A + B;
        for c in 0..3 {
            sky.output[c] = std::array::from_fn(|k| p[base + c * B + k] as f32);
            sky.output_bias[c] = p[base + 3 * B + c] as f32;
        }
        sky
    }

    /// Linear RGB for each direction of `dirs` (normalised here), sixteen at a time.
    #[inline(always)]
    pub fn rgb_batch(&self, dirs: &[Vec3], out: &mut [Vec3]) {
        const L: usize = 16;
        for (d, o) in dirs.chunks(L).zip(out.chunks_mut(L)) {
            // A short last chunk is padded by repeating its first direction.
            let lane = |i: usize| d.get(i).copied().unwrap_or(d[0]);
            let rgb = self.lanes::<L>(
                std::array::from_fn(|i| lane(i).x),
                std::array::from_fn(|i| lane(i).y),
                std::array::from_fn(|i| lane(i).z),
            );
            for (slot, v) in o.iter_mut().zip(rgb) {
                *slot = v;
            }
        }
    }

    #[inline(always)]
    fn lanes<const L: usize>(&self, x: [f32; L], y: [f32; L], z: [f32; L]) -> [Vec3; L] {
        let mut u = [[0.0f32; L]; 4];
        for i in 0..L {
            let inv = 1.0 / (x[i] * x[i] + y[i] * y[i] + z[i] * z[i]).sqrt();
            u[0][i] = x[i] * inv;
            u[1][i] = y[i] * inv;
            u[2][i] = z[i] * inv;
            let (dx, dy, dz) = (
                u[0][i] - self.sun.x,
                u[1][i] - self.sun.y,
                u[2][i] - self.sun.z,
            );
            u[3][i] = (dx * dx + dy * dy + dz * dz).sqrt();
        }
        let mut first = [[0.0f32; L]; A];
        for (j, a) in first.iter_mut().enumerate() {
            let c = &self.coeff[j];
            for i in 0..L {
                let h = self.constant[j]
                    + c[0] * u[0][i]
                    + c[1] * u[1][i]
                    + c[2] * u[2][i]
                    + c[3] * u[3][i];
                a[i] = 1.0 / (1.0 + h * h);
            }
        }
        let [mut r, mut g, mut b] = self.output_bias.map(|bias| [bias; L]);
        for k in 0..B {
            let mut h = [self.second_bias[k]; L];
            for (j, a) in first.iter().enumerate() {
                for i in 0..L {
                    h[i] += self.second[k][j] * a[i];
                }
            }
            for i in 0..L {
                let a = 1.0 / (1.0 + h[i] * h[i]);
                r[i] += self.output[0][k] * a;
                g[i] += self.output[1][k] * a;
                b[i] += self.output[2][k] * a;
            }
        }
        std::array::from_fn(|i| Vec3::new(r[i] * r[i], g[i] * g[i], b[i] * b[i]) * self.half_scale)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::train::dataset::{self, SkyCase};
    use crate::train::net::Net;
    use rand::SeedableRng;

    /// The f32 two-layer sky agrees with the trainer's f64 forward pass of the same network.
    #[test]
    fn two_layer_sky_matches_the_f64_network() {
        let mut rng = rand::rngs::StdRng::seed_from_u64(5);
        let set = dataset::DataSet::training(
            ModelKind::Preetham,
            &dataset::Sampling::paper(ModelKind::Preetham),
        )
        .expect("valid");
        let trained = Trained {
            net: Net::random(&[6, 12, 12, 3], &mut rng, 1.0),
            scaling: train::Scaling::fit(&set),
            validation_nrmse: 0.0,
            iterations: 0,
            seconds: 0.0,
            examples: 0,
            milestone: None,
        };
        let case = SkyCase {
            turbidity: 3.5,
            sun_zenith: 0.8,
        };
        let sun = Sun::new(0.8, 0.7).expect("valid");
        let sky = TwoLayerSky::<12, 12>::new(&trained, sun, 3.5);
        let dirs = dataset::test_directions();
        let want = trained.predict(case, &dirs, 0.7);
        let mut got = vec![Vec3::ZERO; dirs.len()];
        sky.rgb_batch(&dirs, &mut got);
        let peak = want.iter().map(|v| v.max_element()).fold(0.0f32, f32::max);
        let worst = got
            .iter()
            .zip(&want)
            .map(|(g, w)| (*g - *w).abs().max_element() / peak)
            .fold(0.0f32, f32::max);
        assert!(worst < 1e-4, "largest difference {worst} of the peak");
    }
}
