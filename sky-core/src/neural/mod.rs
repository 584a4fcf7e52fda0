//! The neural sky of seed 000 (Satilmis et al., *A Machine Learning Driven Sky Model*): a
//! 6-H-3 network that maps the sun and a view direction to linear RGB radiance.
//!
//! # The network (seed 000 §III-B, eqs. 4-7)
//!
//! Input V = {√t, θ_sun, v_x, v_y, v_z, d}: turbidity t (zeroed for models without one, such as
//! captured skies), the sun's zenith angle, the unit view direction *rotated so that the sun's
//! azimuth is π* (eq. 10), and d = |v − s|, the Euclidean distance between the unit view and sun
//! directions (= 2 sin(γ/2)). Each input is normalised, u_k = (V_k − offset_k) · scale_k (the
//! affine map is stored with the weights and folded into the first layer when the sky is
//! built, so it costs nothing per direction). One hidden layer of H neurons with bias and the
//! activation f(x) = 1/(1 + x²) (eq. 5); three outputs y_c = f(z_c) in (0, 1], mapped to radiance
//! by L_s(y) = ½(1/y − 1) (eq. 7) and a per-channel scale.
//!
//! **Keeping y away from 0.** Since y = 1/(1 + z²), L_s(y) = ½(1/y − 1) = ½ z² exactly: the
//! evaluation computes ½ z² and never forms y, so there is no division by a y that could round to
//! 0, and the radiance is finite and non-negative for every input (finite weights are validated
//! at decoding; the result is clamped to `f32::MAX`).
//!
//! # Size
//!
//! H = 12 (the paper's choice) has 6·12 + 12 + 12·3 + 3 = 123 weights: **492 bytes** of f32, as
//! the paper states (§IV-C). The input/output normalisation adds 15 floats (60 bytes); the
//! binary file format ([`weights`]) adds a 128-byte header and a 4-byte checksum.
//!
//! # Shipped skies
//!
//! [`pretrained::PREETHAM`] and [`pretrained::HOSEK`] were trained by `sky-train` on the Preetham
//! sky (turbidity 2-6) and the Hosek-Wilkie sky (turbidity 1-10, ground albedo 0.5); their
//! accuracy on the paper's test protocol is in each constant's docs.

#[cfg(target_arch = "x86_64")]
pub mod avx2;
pub mod fixed;
pub mod pretrained;
pub mod weights;

use glam::Vec3;

use crate::error::{SkyError, check_range};
use crate::geom::{HORIZON_TOLERANCE, Sun};
use crate::math;

pub use fixed::{FixedNeuralSky, FixedNeuralWeights};
pub use weights::{NeuralWeights, WeightsError};

/// Number of network inputs: √t, θ_sun, v_x, v_y, v_z, d.
pub const INPUTS: usize = 6;
/// Number of network outputs: linear R, G, B.
pub const OUTPUTS: usize = 3;

/// The order of [`NeuralSky::rgb_batch`]'s operations. Step by step (each step of eqs. 4-7 done
/// for every lane before the next, the hidden layer pipelined one neuron ahead) puts the lanes'
/// long dependency chains (square roots, divisions) side by side, which an out-of-order CPU
/// overlaps: 30 % faster on x86-64 than lane by lane. WebAssembly engines compile the
/// instructions in the order given and spill the many live vectors that order has: there, lane
/// by lane (each lane's whole chain, the compiler vectorising across lanes) is 10 % faster.
/// Either order performs the same operations on each lane, with identical results.
pub(crate) const STEP_BY_STEP: bool = !cfg!(target_arch = "wasm32");

/// The network inputs that depend only on the sky, and eq. 10's rotation, checked against the
/// trained domain: shared by [`NeuralSky`] and [`FixedNeuralSky`].
struct SkyInputs {
    /// √t (0 for networks without a turbidity input).
    sqrt_t: f32,
    /// The sun's zenith angle.
    theta_s: f32,
    /// Sine and cosine of eq. 10's rotation −(φ_sun − π) about z, which puts the sun at
    /// azimuth π.
    sin_r: f32,
    cos_r: f32,
}

impl SkyInputs {
    /// `turbidity` is the turbidity and its trained range, or `None` for networks without it.
    ///
    /// Never inlined, like the other constructor helpers here: once per sky, so compiled
    /// once at this crate's optimisation level rather than into every caller (the .wasm's
    /// kernels are built for speed, its constructors need not be).
    #[inline(never)]
    fn new(
        sun_zenith_range: (f32, f32),
        turbidity: Option<(f32, (f32, f32))>,
        sun: Sun,
    ) -> Result<Self, SkyError> {
        let (zmin, zmax) = sun_zenith_range;
        let theta_s = check_range("sun zenith [rad]", sun.zenith(), zmin, zmax)?;
        let sqrt_t = match turbidity {
            Some((t, (tmin, tmax))) => math::sqrt(check_range("turbidity", t, tmin, tmax)?),
            None => 0.0,
        };
        // Eq. 10: the view is rotated by −(φ_sun − π) about z, so that the sun's azimuth is π.
        let rotate = sun.azimuth() - core::f32::consts::PI;
        Ok(Self {
            sqrt_t,
            theta_s,
            sin_r: math::sin(rotate),
            cos_r: math::cos(rotate),
        })
    }
}

/// A [`NeuralSky`] with √t, θ_sun, eq. 10's rotation and the input scaling folded into the
/// first layer ([`NeuralSky::folded`]). For a unit view direction v (not rotated) and
/// d = |v − sun|, hidden neuron j's pre-activation is
/// `h_j = constant[j] + coeff_x[j] v_x + coeff_y[j] v_y + coeff_z[j] v_z + coeff_d[j] d`,
/// its activation `a_j = 1/(1 + h_j²)` (eq. 5), channel c's output sum
/// `z_c = output_bias[c] + Σ_j output[c][j] a_j` (eq. 6), and the radiance `half_scale[c] · z_c²`
/// (eq. 7, see the module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FoldedNetwork<const H: usize = 12> {
    /// The unit direction towards the sun.
    pub sun: Vec3,
    /// The part of each hidden neuron's pre-activation that depends only on the sky.
    pub constant: [f32; H],
    /// Each hidden neuron's coefficient of v_x (eq. 10's rotation and the input scaling folded in).
    pub coeff_x: [f32; H],
    /// Each hidden neuron's coefficient of v_y.
    pub coeff_y: [f32; H],
    /// Each hidden neuron's coefficient of v_z.
    pub coeff_z: [f32; H],
    /// Each hidden neuron's coefficient of d.
    pub coeff_d: [f32; H],
    /// Output weights, a row per channel (R, G, B).
    pub output: [[f32; H]; OUTPUTS],
    /// Output biases.
    pub output_bias: [f32; OUTPUTS],
    /// ½ · output scale per channel.
    pub half_scale: [f32; OUTPUTS],
}

/// The neural sky for one sun position and turbidity, with `H` hidden neurons (12 by default).
///
/// ```
/// use sky_core::neural::{pretrained, NeuralSky};
/// use sky_core::{geom, Sun};
///
/// let sun = Sun::new(50f32.to_radians(), 1.0)?;
/// let sky = NeuralSky::new(&pretrained::PREETHAM, sun, 3.0)?;
/// let rgb = sky.rgb(geom::direction(0.2, 0.0)); // linear sRGB, cd/m² scale
/// assert!(rgb.min_element() > 0.0);
/// # Ok::<(), sky_core::SkyError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NeuralSky<const H: usize = 12> {
    /// The sun direction (for d).
    sun: Vec3,
    /// Per hidden neuron: the part of the pre-activation that depends only on the sky, and the
    /// coefficients of v_x, v_y, v_z (rotation of eq. 10 and input scaling folded in) and d.
    constant: [f32; H],
    coeff_x: [f32; H],
    coeff_y: [f32; H],
    coeff_z: [f32; H],
    coeff_d: [f32; H],
    /// Output layer weights and biases.
    output: [[f32; H]; OUTPUTS],
    output_bias: [f32; OUTPUTS],
    /// ½ · output scale per channel: radiance = half_scale · z².
    half_scale: [f32; OUTPUTS],
}

/// The first layer of a network folded for the sky of `inputs` (see [`FoldedNetwork`]): for
/// each hidden neuron (`hidden`, `hidden_bias`; the inputs' offsets `off` and scales `sc`)
/// its `constant`, `coeff_x`, `coeff_y`, `coeff_z` and `coeff_d`. Over slices, not generic over
/// H, and never inlined (see [`SkyInputs::new`]).
#[inline(never)]
fn fold_neurons(
    inputs: &SkyInputs,
    hidden: &[[f32; INPUTS]],
    hidden_bias: &[f32],
    off: &[f32; INPUTS],
    sc: &[f32; INPUTS],
    [constant, coeff_x, coeff_y, coeff_z, coeff_d]: [&mut [f32]; 5],
) {
    let &SkyInputs {
        sqrt_t,
        theta_s,
        sin_r,
        cos_r,
    } = inputs;
    let neurons = hidden
        .iter()
        .zip(hidden_bias)
        .zip(constant.iter_mut().zip(coeff_x));
    for (((w, bias), (c, x)), (y, (z, d))) in
        neurons.zip(coeff_y.iter_mut().zip(coeff_z.iter_mut().zip(coeff_d)))
    {
        // Scaled weights: u_k = (V_k − off_k) sc_k, so w_k u_k = (w_k sc_k) V_k − w_k sc_k off_k.
        let ws: [f32; INPUTS] = core::array::from_fn(|k| w[k] * sc[k]);
        let shift: f32 = (0..INPUTS).map(|k| ws[k] * off[k]).sum();
        *c = bias + ws[0] * sqrt_t + ws[1] * theta_s - shift;
        // v_x = v_x0 cos r + v_y0 sin r, v_y = v_y0 cos r − v_x0 sin r (eq. 10).
        *x = ws[2] * cos_r - ws[3] * sin_r;
        *y = ws[2] * sin_r + ws[3] * cos_r;
        *z = ws[4];
        *d = ws[5];
    }
}

/// Whether every value of every group is finite. Never inlined (see [`SkyInputs::new`]).
#[inline(never)]
fn all_finite(groups: &[&[f32]]) -> bool {
    groups.iter().all(|g| g.iter().all(|x| x.is_finite()))
}

impl<const H: usize> NeuralSky<H> {
    /// The sky of `weights` for `sun` and `turbidity`.
    ///
    /// The sun's zenith angle and the turbidity must lie inside the ranges the weights were
    /// trained for ([`NeuralWeights::sun_zenith_range`], [`NeuralWeights::turbidity_range`]).
    /// Weights trained without a turbidity input (captured skies) ignore `turbidity`.
    ///
    /// # Errors
    /// [`SkyError::OutOfRange`] for a sun zenith or turbidity outside the trained ranges (or
    /// NaN); [`SkyError::NotFinite`] for weights, biases or scalings that are NaN or infinite,
    /// or so large that the network folded for this sky overflows f32 (a decoded weight file
    /// has finite values; weights built by hand may not).
    pub fn new(weights: &NeuralWeights<H>, sun: Sun, turbidity: f32) -> Result<Self, SkyError> {
        let inputs = SkyInputs::new(
            weights.sun_zenith_range,
            weights
                .uses_turbidity
                .then_some((turbidity, weights.turbidity_range)),
            sun,
        )?;
        let mut sky = Self {
            sun: sun.direction(),
            constant: [0.0; H],
            coeff_x: [0.0; H],
            coeff_y: [0.0; H],
            coeff_z: [0.0; H],
            coeff_d: [0.0; H],
            output: weights.output,
            output_bias: weights.output_bias,
            half_scale: weights.output_scale.map(|s| 0.5 * s),
        };
        fold_neurons(
            &inputs,
            &weights.hidden,
            &weights.hidden_bias,
            &weights.input_offset,
            &weights.input_scale,
            [
                &mut sky.constant,
                &mut sky.coeff_x,
                &mut sky.coeff_y,
                &mut sky.coeff_z,
                &mut sky.coeff_d,
            ],
        );
        // A NaN or infinity anywhere in the weights reaches one of these (0 · ∞ is NaN too).
        if all_finite(&[
            &sky.constant,
            &sky.coeff_x,
            &sky.coeff_y,
            &sky.coeff_z,
            &sky.coeff_d,
            &sky.output_bias,
            &sky.half_scale,
            sky.output.as_flattened(),
        ]) {
            Ok(sky)
        } else {
            Err(SkyError::NotFinite {
                parameter: "network weights",
            })
        }
    }

    /// The network with everything that depends only on the sky folded into the first layer,
    /// exactly as [`rgb`](Self::rgb) evaluates it: for GPU shaders (sky-gpu) that take these
    /// values as uniforms and compute only the per-direction part.
    #[must_use]
    pub fn folded(&self) -> FoldedNetwork<H> {
        FoldedNetwork {
            sun: self.sun,
            constant: self.constant,
            coeff_x: self.coeff_x,
            coeff_y: self.coeff_y,
            coeff_z: self.coeff_z,
            coeff_d: self.coeff_d,
            output: self.output,
            output_bias: self.output_bias,
            half_scale: self.half_scale,
        }
    }

    /// Linear sRGB radiance towards `dir` (need not be normalised if its length lies in
    /// [1e-18, 1e18]), in the units of the training data (cd/m² for the shipped Preetham sky).
    /// 0 below the horizon (the crate's rule, [`geom::below_horizon`](crate::geom::below_horizon):
    /// the network is trained on the sky above it and its output there means nothing).
    /// Finite and non-negative for every input (0 for a NaN direction). The accuracy is that of the weights (see
    /// [`pretrained`]).
    #[inline]
    #[must_use]
    pub fn rgb(&self, dir: Vec3) -> Vec3 {
        let [r, g, b] = self.rgb_lanes::<1, STEP_BY_STEP>([dir.x], [dir.y], [dir.z]);
        Vec3::new(r[0], g[0], b[0])
    }

    /// [`rgb`](Self::rgb) for many directions: fills `out[i]` for every `i` below
    /// `min(dirs.len(), out.len())`, with the same results as `rgb` bit for bit. Directions are
    /// evaluated in groups of SIMD-friendly lanes: thirty-two (eight SSE or four AVX2 vector
    /// registers per quantity), each step of the network done for all of them before the next,
    /// so that the CPU overlaps their square roots and divisions; in WebAssembly sixteen (four
    /// SIMD registers), one direction's chain after another, the order WebAssembly engines run
    /// fastest. Both orders give the same results.
    ///
    /// On x86-64 CPUs with AVX2 and FMA, [`rgb_batch_avx2`](Self::rgb_batch_avx2) is about 30 %
    /// faster than this function compiled for AVX2, with the same accuracy but not the same bits.
    #[inline(always)]
    pub fn rgb_batch(&self, dirs: &[Vec3], out: &mut [Vec3]) {
        const LANES: usize = if STEP_BY_STEP { 32 } else { 16 };
        let n = dirs.len().min(out.len());
        let (dirs, out) = (&dirs[..n], &mut out[..n]);
        let mut chunks = dirs.chunks_exact(LANES);
        let mut outs = out.chunks_exact_mut(LANES);
        for (d, o) in (&mut chunks).zip(&mut outs) {
            let (mut x, mut y, mut z) = ([0.0; LANES], [0.0; LANES], [0.0; LANES]);
            for i in 0..LANES {
                (x[i], y[i], z[i]) = (d[i].x, d[i].y, d[i].z);
            }
            let [r, g, b] = self.rgb_lanes::<LANES, STEP_BY_STEP>(x, y, z);
            for (i, slot) in o.iter_mut().enumerate() {
                *slot = Vec3::new(r[i], g[i], b[i]);
            }
        }
        for (d, o) in chunks.remainder().iter().zip(outs.into_remainder()) {
            *o = self.rgb(*d);
        }
    }

    /// Eqs. 4-7 for `L` directions given as coordinate lanes, without a branch on the data, in
    /// either order of [`STEP_BY_STEP`]. Every lane performs the same operations in the same
    /// order whatever `L` and `STEP` are, so one direction and a batch give identical results.
    #[inline(always)]
    pub(crate) fn rgb_lanes<const L: usize, const STEP: bool>(
        &self,
        x: [f32; L],
        y: [f32; L],
        z: [f32; L],
    ) -> [[f32; L]; 3] {
        // The inputs of eq. 4: the view direction normalised, and d = |v − s|.
        let (mut vx, mut vy, mut vz, mut d) = ([0.0; L], [0.0; L], [0.0; L], [0.0; L]);
        // The three output sums (eq. 6), each lane's starting from the bias.
        let [mut r, mut g, mut b] = self.output_bias.map(|bias| [bias; L]);
        if STEP {
            let mut norm2 = [0.0; L];
            for i in 0..L {
                norm2[i] = x[i] * x[i] + y[i] * y[i] + z[i] * z[i];
            }
            let inv = math::rsqrt_lanes(norm2);
            let mut q = [0.0; L];
            for i in 0..L {
                (vx[i], vy[i], vz[i]) = (x[i] * inv[i], y[i] * inv[i], z[i] * inv[i]);
                let (dx, dy, dz) = (vx[i] - self.sun.x, vy[i] - self.sun.y, vz[i] - self.sun.z);
                q[i] = dx * dx + dy * dy + dz * dz;
            }
            let inv_d = math::rsqrt_lanes(q);
            for i in 0..L {
                d[i] = q[i] * inv_d[i];
            }
            // The hidden layer, pipelined: neuron j + 1's activation is computed before neuron
            // j's is added to the outputs, so its divisions overlap that work.
            let v = [vx, vy, vz, d];
            let mut a = if H > 0 {
                self.activation(0, &v)
            } else {
                [0.0; L]
            };
            for j in 0..H {
                let next = if j + 1 < H {
                    self.activation(j + 1, &v)
                } else {
                    a
                };
                for i in 0..L {
                    r[i] += self.output[0][j] * a[i];
                }
                for i in 0..L {
                    g[i] += self.output[1][j] * a[i];
                }
                for i in 0..L {
                    b[i] += self.output[2][j] * a[i];
                }
                a = next;
            }
        } else {
            for i in 0..L {
                let inv = math::rsqrt(x[i] * x[i] + y[i] * y[i] + z[i] * z[i]);
                (vx[i], vy[i], vz[i]) = (x[i] * inv, y[i] * inv, z[i] * inv);
                let (dx, dy, dz) = (vx[i] - self.sun.x, vy[i] - self.sun.y, vz[i] - self.sun.z);
                let q = dx * dx + dy * dy + dz * dz;
                d[i] = q * math::rsqrt(q);
            }
            for j in 0..H {
                for i in 0..L {
                    // Eqs. 4-5, as in `activation`.
                    let h = self.constant[j]
                        + self.coeff_x[j] * vx[i]
                        + self.coeff_y[j] * vy[i]
                        + self.coeff_z[j] * vz[i]
                        + self.coeff_d[j] * d[i];
                    let a = 1.0 / (1.0 + h * h);
                    r[i] += self.output[0][j] * a;
                    g[i] += self.output[1][j] * a;
                    b[i] += self.output[2][j] * a;
                }
            }
        }
        // Eq. 7 through eq. 6's output activation: L_s(f(z)) = ½ z² (see the module docs);
        // NaN (only from NaN directions) becomes f32::MAX. Then the crate's below-horizon rule
        // (crate docs, "Conventions"): 0 where the unit view's z < −HORIZON_TOLERANCE, and for
        // a NaN direction (whose comparison is false).
        let [sr, sg, sb] = self.half_scale;
        for i in 0..L {
            let above = if vz[i] >= -HORIZON_TOLERANCE {
                1.0
            } else {
                0.0
            };
            r[i] = math::at_most(sr * r[i] * r[i], f32::MAX) * above;
            g[i] = math::at_most(sg * g[i] * g[i], f32::MAX) * above;
            b[i] = math::at_most(sb * b[i] * b[i], f32::MAX) * above;
        }
        [r, g, b]
    }

    /// Hidden neuron `j`'s activation (eqs. 4-5) in each lane, from the inputs `[v_x, v_y, v_z,
    /// d]`: the weighted sum (input scaling and eq. 10 folded in), then f(h) = 1/(1 + h²).
    #[inline(always)]
    fn activation<const L: usize>(&self, j: usize, [vx, vy, vz, d]: &[[f32; L]; 4]) -> [f32; L] {
        let mut h = [self.constant[j]; L];
        for i in 0..L {
            h[i] += self.coeff_x[j] * vx[i];
        }
        for i in 0..L {
            h[i] += self.coeff_y[j] * vy[i];
        }
        for i in 0..L {
            h[i] += self.coeff_z[j] * vz[i];
        }
        for i in 0..L {
            h[i] += self.coeff_d[j] * d[i];
        }
        for h in &mut h {
            *h = 1.0 / (1.0 + *h * *h);
        }
        h
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom;

    /// The paper's equations 4-7 and 10 written out in f64, straight from the text: rotate the
    /// view (eq. 10), build V, normalise, one hidden layer with f(x) = 1/(1+x²), output
    /// y = f(z), radiance = scale · ½(1/y − 1).
    fn reference(w: &NeuralWeights<12>, sun: (f64, f64), t: f64, view: (f64, f64)) -> [f64; 3] {
        let (ts, ps) = sun;
        let (tv, pv) = view;
        let v0 = [tv.sin() * pv.cos(), tv.sin() * pv.sin(), tv.cos()];
        let r = ps - core::f64::consts::PI;
        let v = [
            v0[0] * r.cos() + v0[1] * r.sin(),
            v0[1] * r.cos() - v0[0] * r.sin(),
            v0[2],
        ];
        let s = [-ts.sin(), 0.0, ts.cos()]; // the sun at azimuth π
        let d = ((v[0] - s[0]).powi(2) + (v[1] - s[1]).powi(2) + (v[2] - s[2]).powi(2)).sqrt();
        let input = [libm::sqrt(t), ts, v[0], v[1], v[2], d];
        let u: [f64; 6] = core::array::from_fn(|k| {
            (input[k] - f64::from(w.input_offset[k])) * f64::from(w.input_scale[k])
        });
        let f = |x: f64| 1.0 / (1.0 + x * x);
        let a: [f64; 12] = core::array::from_fn(|j| {
            f(f64::from(w.hidden_bias[j])
                + (0..6)
                    .map(|k| f64::from(w.hidden[j][k]) * u[k])
                    .sum::<f64>())
        });
        core::array::from_fn(|c| {
            let z = f64::from(w.output_bias[c])
                + (0..12)
                    .map(|j| f64::from(w.output[c][j]) * a[j])
                    .sum::<f64>();
            let y = f(z);
            f64::from(w.output_scale[c]) * 0.5 * (1.0 / y - 1.0)
        })
    }

    fn weights() -> NeuralWeights<12> {
        let v = |i: usize| ((i * 7919 % 1000) as f32 - 500.0) / 400.0;
        NeuralWeights {
            hidden: core::array::from_fn(|j| core::array::from_fn(|k| v(j * 6 + k))),
            hidden_bias: core::array::from_fn(|j| v(100 + j)),
            output: core::array::from_fn(|c| core::array::from_fn(|j| v(200 + c * 12 + j))),
            output_bias: [0.4, -0.2, 0.3],
            input_offset: [1.9, 0.8, 0.0, 0.0, 0.5, 1.2],
            input_scale: [2.0, 1.5, 1.4, 1.4, 3.0, 1.1],
            output_scale: [1.0, 2.0, 3.0],
            uses_turbidity: true,
            turbidity_range: (2.0, 6.0),
            sun_zenith_range: (0.0, core::f32::consts::FRAC_PI_2),
            source: [0; 32],
            seed: 0,
            nrmse: 0.0,
        }
    }

    #[test]
    fn matches_the_papers_equations_in_f64() {
        let w = weights();
        let mut worst = 0.0f64;
        for (ts, ps, t) in [
            (0.0, 0.0, 2.0),
            (0.7, 2.0, 3.3),
            (1.5, -1.0, 6.0),
            (1.2, 3.0, 4.0),
        ] {
            let sky = NeuralSky::new(&w, Sun::new(ts, ps).expect("valid"), t).expect("valid");
            for i in 0..=9 {
                for k in 0..24 {
                    let (tv, pv) = (f64::from(i) * 0.17, f64::from(k) * 0.26);
                    #[allow(clippy::cast_possible_truncation)]
                    let got = sky.rgb(geom::direction(tv as f32, pv as f32));
                    let want =
                        reference(&w, (f64::from(ts), f64::from(ps)), f64::from(t), (tv, pv));
                    for c in 0..3 {
                        let e = (f64::from(got[c]) - want[c]).abs() / want[c].abs().max(1e-3);
                        worst = worst.max(e);
                    }
                }
            }
        }
        assert!(worst < 2e-4, "max relative error {worst}");
    }

    #[test]
    fn batch_equals_single_and_outputs_are_finite() {
        let w = weights();
        let sky = NeuralSky::new(&w, Sun::new(0.4, 1.0).expect("valid"), 2.5).expect("valid");
        let special = [
            Vec3::new(0.0, 0.0, 1.0),
            Vec3::new(1.0, 2.0, -3.0),
            Vec3::ZERO,
            Vec3::splat(f32::NAN),
            Vec3::new(f32::INFINITY, 0.0, 1.0),
            Vec3::new(1e-30, 0.0, 0.0),
        ];
        // Two full lane groups and a remainder: the special directions spread over the lanes,
        // between ordinary ones.
        let dirs: [Vec3; 70] = core::array::from_fn(|i| match i % 7 {
            6 => geom::direction(0.02 * i as f32, 0.3 * i as f32),
            k => special[(k + i / 7) % special.len()],
        });
        let mut out = [Vec3::ONE; 70];
        sky.rgb_batch(&dirs, &mut out);
        // Both orders of the operations (the batch uses one, by target) agree.
        let lanes: [[f32; 32]; 3] = core::array::from_fn(|k| core::array::from_fn(|i| dirs[i][k]));
        let step_by_step = sky.rgb_lanes::<32, true>(lanes[0], lanes[1], lanes[2]);
        let lane_by_lane = sky.rgb_lanes::<32, false>(lanes[0], lanes[1], lanes[2]);
        assert_eq!(
            step_by_step.map(|c| c.map(f32::to_bits)),
            lane_by_lane.map(|c| c.map(f32::to_bits))
        );
        for (d, o) in dirs.iter().zip(out) {
            assert_eq!(
                o.to_array().map(f32::to_bits),
                sky.rgb(*d).to_array().map(f32::to_bits)
            );
            assert!(o.is_finite() && o.min_element() >= 0.0, "{d} -> {o}");
        }
    }

    #[test]
    fn validates_the_trained_domain() {
        let w = weights();
        let sun = Sun::new(0.4, 0.0).expect("valid");
        assert!(matches!(
            NeuralSky::new(&w, sun, 7.0),
            Err(SkyError::OutOfRange {
                parameter: "turbidity",
                ..
            })
        ));
        assert!(NeuralSky::new(&w, sun, f32::NAN).is_err());
        assert!(matches!(
            NeuralSky::new(&w, Sun::new(1.7, 0.0).expect("valid"), 3.0),
            Err(SkyError::OutOfRange {
                parameter: "sun zenith [rad]",
                ..
            })
        ));
        let captured = NeuralWeights {
            uses_turbidity: false,
            ..w
        };
        assert!(
            NeuralSky::new(&captured, sun, f32::NAN).is_ok(),
            "turbidity unused"
        );
    }

    #[test]
    fn refuses_weights_that_are_not_finite() {
        let sun = Sun::new(0.4, 0.0).expect("valid");
        let refused = |w: &NeuralWeights<12>| {
            matches!(
                NeuralSky::new(w, sun, 3.0),
                Err(SkyError::NotFinite {
                    parameter: "network weights"
                })
            )
        };
        type Set = fn(&mut NeuralWeights<12>, f32);
        let fields: [(&str, Set); 7] = [
            ("hidden", |w, v| w.hidden[3][4] = v),
            ("hidden bias", |w, v| w.hidden_bias[11] = v),
            ("output", |w, v| w.output[2][7] = v),
            ("output bias", |w, v| w.output_bias[1] = v),
            ("input offset", |w, v| w.input_offset[5] = v),
            ("input scale", |w, v| w.input_scale[0] = v),
            ("output scale", |w, v| w.output_scale[2] = v),
        ];
        for bad in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
            for (name, set) in fields {
                let mut w = weights();
                set(&mut w, bad);
                assert!(refused(&w), "{name} {bad}");
            }
        }
        // Finite, but the input scaling times the weight overflows f32.
        let mut w = weights();
        w.hidden[0][2] = 1e30;
        w.input_scale[2] = 1e30;
        assert!(refused(&w), "overflow");
        assert!(NeuralSky::new(&weights(), sun, 3.0).is_ok());
    }
}
