//! The neural sky in fixed point, for microcontrollers without an FPU (Cortex-M0, Cortex-M3).
//!
//! [`FixedNeuralSky`] evaluates the same 6-H-3 network as [`NeuralSky`](super::NeuralSky)
//! (seed 000, eqs. 4-7 and 10) with integer arithmetic only: per direction there is no
//! floating-point operation at all, so on a part without an FPU no soft-float routine runs.
//! Only [`FixedNeuralSky::new`] (once per sun position) touches `f32`, to convert the sun and
//! the turbidity to fixed point.
//!
//! # Number formats
//!
//! * Weights and biases ([`FixedNeuralWeights`]) are `i32` in Q7.24 (value · 2²⁴, range ±128,
//!   step 6·10⁻⁸), with the input normalisation u = (V − offset) · scale folded into the hidden
//!   layer by [`FixedNeuralWeights::quantise`], so they act on the raw inputs
//!   V = {√t, θ_sun, v_x, v_y, v_z, d}.
//! * View directions are `[i16; 3]` of any non-zero length (normalised inside, by an integer
//!   square root); [`direction_q15`] makes one from a [`Vec3`].
//! * Unit vectors and d are Q1.30 in `i64`, hidden pre-activations Q20, activations
//!   f(h) = 1/(1 + h²) (eq. 5) Q23 through one 64-bit division, output sums Q47 in `i64`.
//! * Radiance comes out as `u64` in units of 2^−[`radiance_frac`](FixedNeuralWeights::radiance_frac)
//!   of the f32 network's unit, the fraction chosen when quantising so that no radiance the
//!   network can produce saturates (2⁻³⁷ cd/m² for the shipped Preetham sky).
//!
//! Every operation that could overflow for some weights or input saturates, so evaluation never
//! panics and never wraps.
//!
//! # Why 32-bit weights
//!
//! The shipped networks cancel large terms in the output layer (weights up to 69 in magnitude
//! sum to z of order 1), and radiance is ½ z², so 1 % in radiance needs z to about 0.5 %, that
//! is about 10⁻⁵ of the largest weight: more than int8 (2⁻⁷) or Q15 (2⁻¹⁵ of the largest weight,
//! about 3 % radiance error for the shipped skies) can hold. Q7.24 keeps the
//! quantisation error far below the network's own error against its reference.
//!
//! # Accuracy
//!
//! Against the f32 [`NeuralSky`](super::NeuralSky) over the upper hemisphere and the trained
//! domain (273 600 samples per network), the largest relative difference per channel is
//! 3.1·10⁻³ for [`PREETHAM_FIXED`](super::pretrained::PREETHAM_FIXED) and 1.3·10⁻³ for
//! [`HOSEK_FIXED`](super::pretrained::HOSEK_FIXED), wherever the radiance is at least 10⁻⁴ of
//! the channel's largest in that sky. Below that (6 samples, where the network's output z
//! crosses 0 near the horizon with the sun setting, and the f32 network is itself up to 21 %
//! off its f64 evaluation) the difference is below 2.4·10⁻⁷ of that largest radiance.
//! `tests/tests/neural_fixed.rs` holds 1 % and 10⁻⁶.
//!
//! ```
//! use sky_core::neural::fixed::{self, FixedNeuralSky};
//! use sky_core::neural::pretrained;
//! use sky_core::{geom, Sun};
//!
//! let sun = Sun::new(50f32.to_radians(), 1.0)?;
//! let weights = &pretrained::PREETHAM_FIXED;
//! let sky = FixedNeuralSky::new(weights, sun, 3.0)?;
//! let view = fixed::direction_q15(geom::direction(0.2, 0.0)); // or any integer vector
//! let rgb = sky.rgb(view); // linear sRGB · 2^radiance_frac, integers
//! let red = rgb[0] as f64 / (1u64 << weights.radiance_frac) as f64; // cd/m², for display only
//! assert!(red > 100.0);
//! # Ok::<(), sky_core::SkyError>(())
//! ```

use glam::Vec3;

use super::{INPUTS, NeuralWeights, OUTPUTS, SkyInputs};
use crate::error::SkyError;
use crate::geom::Sun;
use crate::math;

/// Fraction bits of the weights and biases (Q7.24).
pub const WEIGHT_FRAC: u32 = 24;
/// Fraction bits of unit vectors, d, √t and θ_sun (Q1.30).
const UNIT_FRAC: u32 = 30;
/// Fraction bits of the hidden pre-activations fed to the activation.
const PRE_FRAC: u32 = 20;
/// Fraction bits of the activations f(h) ∈ (0, 1].
const ACT_FRAC: u32 = 23;

/// A neural sky's weights in fixed point (Q7.24), with the input normalisation folded into the
/// hidden layer. Made by [`quantise`](Self::quantise); the shipped ones are
/// [`pretrained::PREETHAM_FIXED`](super::pretrained::PREETHAM_FIXED) and
/// [`pretrained::HOSEK_FIXED`](super::pretrained::HOSEK_FIXED).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct FixedNeuralWeights<const H: usize = 12> {
    /// Hidden layer weights acting on the raw inputs {√t, θ_sun, v_x, v_y, v_z, d}, Q7.24.
    pub hidden: [[i32; INPUTS]; H],
    /// Hidden layer biases (the normalisation offsets folded in), Q7.24.
    pub hidden_bias: [i32; H],
    /// Output layer weights, Q7.24.
    pub output: [[i32; H]; OUTPUTS],
    /// Output layer biases, Q7.24.
    pub output_bias: [i32; OUTPUTS],
    /// Fraction bits of the radiance [`FixedNeuralSky::rgb`] returns.
    pub radiance_frac: u8,
    /// Per channel, ½ · output scale · 2^(radiance_frac + factor_shift − 48): radiance =
    /// z² · this / 2^factor_shift with z² in Q48.
    pub radiance_factor: [u64; OUTPUTS],
    /// See [`radiance_factor`](Self::radiance_factor).
    pub factor_shift: u8,
    /// Whether the network takes the turbidity as an input.
    pub uses_turbidity: bool,
    /// The trained turbidity range.
    pub turbidity_range: (f32, f32),
    /// The trained sun zenith range, radians.
    pub sun_zenith_range: (f32, f32),
}

/// `x · 2^frac` rounded to an `i32`, or an error naming `parameter` if it does not fit.
fn to_fixed(parameter: &'static str, x: f64) -> Result<i32, SkyError> {
    let limit = f64::from(1u32 << (31 - WEIGHT_FRAC));
    if x.abs() >= limit || x.is_nan() {
        #[allow(clippy::cast_possible_truncation)] // for the message only
        return Err(SkyError::OutOfRange {
            parameter,
            value: x as f32,
            min: -limit as f32,
            max: limit as f32,
        });
    }
    #[allow(clippy::cast_possible_truncation)] // |x| < 2^7, so |x 2^24| < 2^31
    Ok(math::rint64(x * pow2(WEIGHT_FRAC)) as i32)
}

impl<const H: usize> FixedNeuralWeights<H> {
    /// Quantises f32 weights: folds the input normalisation u_k = (V_k − offset_k) · scale_k
    /// into the hidden layer (in f64), rounds every weight and bias to Q7.24, and picks the
    /// radiance fraction so that the largest radiance the network can produce,
    /// ½ · scale · (|b| + Σ|w|)², fits in a `u64`.
    ///
    /// # Errors
    /// [`SkyError::OutOfRange`] when a folded weight or bias lies outside ±128 (Q7.24's range),
    /// or when the output scale is not positive or so large that no radiance fraction fits.
    pub fn quantise(weights: &NeuralWeights<H>) -> Result<Self, SkyError> {
        let mut hidden = [[0; INPUTS]; H];
        let mut hidden_bias = [0; H];
        for j in 0..H {
            let scaled: [f64; INPUTS] = core::array::from_fn(|k| {
                f64::from(weights.hidden[j][k]) * f64::from(weights.input_scale[k])
            });
            let shift: f64 = (0..INPUTS)
                .map(|k| scaled[k] * f64::from(weights.input_offset[k]))
                .sum();
            for k in 0..INPUTS {
                hidden[j][k] = to_fixed("hidden weight · input scale", scaled[k])?;
            }
            hidden_bias[j] = to_fixed(
                "hidden bias − Σ weight · scale · offset",
                f64::from(weights.hidden_bias[j]) - shift,
            )?;
        }
        let mut output = [[0; H]; OUTPUTS];
        let mut output_bias = [0; OUTPUTS];
        let mut peak = 0.0f64; // the largest ½ · scale · z² the network can produce
        for c in 0..OUTPUTS {
            for j in 0..H {
                output[c][j] = to_fixed("output weight", f64::from(weights.output[c][j]))?;
            }
            output_bias[c] = to_fixed("output bias", f64::from(weights.output_bias[c]))?;
            // Every activation lies in (0, 1], so |z| ≤ |b| + Σ|w|.
            let z_max = output[c]
                .iter()
                .chain([&output_bias[c]])
                .map(|&w| f64::from(w).abs())
                .sum::<f64>()
                / pow2(WEIGHT_FRAC);
            let scale = f64::from(weights.output_scale[c]);
            if scale <= 0.0 || scale.is_nan() {
                return Err(SkyError::OutOfRange {
                    parameter: "output scale",
                    value: weights.output_scale[c],
                    min: f32::MIN_POSITIVE,
                    max: f32::MAX,
                });
            }
            peak = peak.max(0.5 * scale * z_max * z_max);
        }
        // The largest fraction (at most 63) with peak · 2^frac < 2^64: no radiance saturates.
        let radiance_frac = (0..64u8)
            .rev()
            .find(|&f| peak * pow2(u32::from(f)) < pow2(64))
            .ok_or(SkyError::OutOfRange {
                parameter: "largest radiance of the network",
                #[allow(clippy::cast_possible_truncation)] // for the message only
                value: peak as f32,
                min: 0.0,
                max: f32::MAX,
            })?;
        // The factors in [2^62, 2^63) for the largest output scale (≥ 2^-40 of it for the
        // others): 62 bits of precision. The shift then lies in [0, 127] for any f32 scale.
        let largest = weights.output_scale.iter().fold(0.0f32, |m, &s| m.max(s));
        let mut factor_shift = 62 + 48 - i32::from(radiance_frac);
        while f64::from(largest) * 0.5 * pow2_signed(factor_shift + i32::from(radiance_frac) - 48)
            >= pow2(63)
        {
            factor_shift -= 1;
        }
        let factor_shift = u8::try_from(factor_shift.clamp(0, 127)).unwrap_or(127);
        let exponent = i32::from(factor_shift) + i32::from(radiance_frac) - 48;
        let radiance_factor = weights.output_scale.map(|s| {
            #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)] // 0 < f < 2^63
            {
                math::rint64(0.5 * f64::from(s) * pow2_signed(exponent)) as u64
            }
        });
        Ok(Self {
            hidden,
            hidden_bias,
            output,
            output_bias,
            radiance_frac,
            radiance_factor,
            factor_shift,
            uses_turbidity: weights.uses_turbidity,
            turbidity_range: weights.turbidity_range,
            sun_zenith_range: weights.sun_zenith_range,
        })
    }
}

/// `x` in Q1.30, as an `i64` (saturating for |x| ≥ 2³³; NaN gives 0).
#[allow(clippy::cast_possible_truncation)] // `as` saturates and maps NaN to 0, by design
fn to_unit_fixed(x: f32) -> i64 {
    math::rint64(f64::from(x) * pow2(UNIT_FRAC)) as i64
}

/// 2ⁿ as an f64, exactly (n ≤ 1023).
fn pow2(n: u32) -> f64 {
    f64::from_bits((1023 + u64::from(n)) << 52)
}

/// 2ⁿ as an f64, exactly (−1022 ≤ n ≤ 1023; clamped to that range).
fn pow2_signed(n: i32) -> f64 {
    #[allow(clippy::cast_sign_loss)] // 1023 + n ≥ 1
    f64::from_bits(((1023 + n.clamp(-1022, 1023)) as u64) << 52)
}

/// A view direction as the `[i16; 3]` [`FixedNeuralSky::rgb`] takes: `dir` normalised and scaled
/// by 32767 (the zero vector and non-finite components give 0). Uses `f32`: for tables made on
/// a host or once at start-up; firmware may equally build its integer directions itself.
#[must_use]
pub fn direction_q15(dir: Vec3) -> [i16; 3] {
    let n = dir.length();
    let unit = if n > 0.0 && n.is_finite() {
        dir / n
    } else {
        Vec3::ZERO
    };
    #[allow(clippy::cast_possible_truncation)] // |32767 · u| ≤ 32767; NaN → 0
    unit.to_array()
        .map(|u| math::rint64(f64::from(u) * 32767.0) as i16)
}

/// The neural sky for one sun position and turbidity, evaluated in fixed point (see the
/// [module docs](self)).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct FixedNeuralSky<const H: usize = 12> {
    /// The sun direction, Q1.30 (for d).
    sun: [i64; 3],
    /// Per hidden neuron: the part of the pre-activation that depends only on the sky, Q54.
    constant: [i64; H],
    /// Per hidden neuron: the coefficients of v_x, v_y, v_z (eq. 10's rotation folded in) and
    /// d, Q7.24.
    coeff: [[i32; 4]; H],
    output: [[i32; H]; OUTPUTS],
    /// Output biases, Q47.
    output_bias: [i64; OUTPUTS],
    radiance_factor: [u64; OUTPUTS],
    factor_shift: u8,
}

/// Fraction bits of a weight times a unit-vector component (Q7.24 · Q1.30).
const PRODUCT_FRAC: u32 = WEIGHT_FRAC + UNIT_FRAC;

/// `x` in Q`from` rounded to Q`to` (to < from), saturating instead of overflowing.
fn round_shift(x: i64, from: u32, to: u32) -> i64 {
    let shift = from - to;
    x.saturating_add(1 << (shift - 1)) >> shift
}

/// Rounds a Q54 value to Q24 and saturates it to an `i32`.
fn q54_to_q24(x: i64) -> i32 {
    let rounded = round_shift(x, PRODUCT_FRAC, WEIGHT_FRAC);
    #[allow(clippy::cast_possible_truncation)] // clamped into i32's range first
    {
        rounded.clamp(i64::from(i32::MIN), i64::from(i32::MAX)) as i32
    }
}

impl<const H: usize> FixedNeuralSky<H> {
    /// The sky of `weights` for `sun` and `turbidity`: the same domain checks as
    /// [`NeuralSky::new`](super::NeuralSky::new); the sun direction, θ_sun, √t and the sine and
    /// cosine of eq. 10's rotation are converted to Q1.30 here (the only `f32` work), everything
    /// else is integer.
    ///
    /// # Errors
    /// [`SkyError::OutOfRange`] for a sun zenith or turbidity outside the trained ranges (or
    /// NaN).
    pub fn new(
        weights: &FixedNeuralWeights<H>,
        sun: Sun,
        turbidity: f32,
    ) -> Result<Self, SkyError> {
        let inputs = SkyInputs::new(
            weights.sun_zenith_range,
            weights
                .uses_turbidity
                .then_some((turbidity, weights.turbidity_range)),
            sun,
        )?;
        let [sqrt_t, theta_s, sin_r, cos_r] =
            [inputs.sqrt_t, inputs.theta_s, inputs.sin_r, inputs.cos_r].map(to_unit_fixed);
        let mut coeff = [[0; 4]; H];
        let mut constant = [0; H];
        for j in 0..H {
            let w = weights.hidden[j].map(i64::from);
            constant[j] = (w[0].saturating_mul(sqrt_t))
                .saturating_add(w[1].saturating_mul(theta_s))
                .saturating_add(i64::from(weights.hidden_bias[j]) << UNIT_FRAC);
            // v_x = v_x0 cos r + v_y0 sin r, v_y = v_y0 cos r − v_x0 sin r (eq. 10).
            coeff[j] = [
                q54_to_q24(w[2].saturating_mul(cos_r) - w[3].saturating_mul(sin_r)),
                q54_to_q24(w[2].saturating_mul(sin_r) + w[3].saturating_mul(cos_r)),
                weights.hidden[j][4],
                weights.hidden[j][5],
            ];
        }
        Ok(Self {
            sun: sun.direction().to_array().map(to_unit_fixed),
            constant,
            coeff,
            output: weights.output,
            output_bias: weights.output_bias.map(|b| i64::from(b) << (ACT_FRAC)),
            radiance_factor: weights.radiance_factor,
            factor_shift: weights.factor_shift,
        })
    }

    /// Linear sRGB radiance towards `dir`, as `u64` in units of 2^−`radiance_frac` of the f32
    /// network's unit (cd/m² for the shipped Preetham sky): integer arithmetic only. `dir` may
    /// have any length; the zero vector is evaluated as the f32 sky evaluates it (v = 0).
    /// Within 0.31 % of [`NeuralSky::rgb`](super::NeuralSky::rgb) for the shipped networks
    /// (see the module docs for where); saturates at `u64::MAX` instead of overflowing. 0 below
    /// the horizon, by the crate's rule as `NeuralSky::rgb` applies it
    /// ([`geom::below_horizon`](crate::geom::below_horizon), on the Q1.30 unit vector).
    #[must_use]
    pub fn rgb(&self, dir: [i16; 3]) -> [u64; 3] {
        let v = unit_q30(dir);
        if v[2] < HORIZON_Q30 {
            return [0; 3];
        }
        // d = |v − s| (seed 000's input), Q1.30; |v − s|² ≤ 4 · 2⁶⁰ fits a u64.
        let q = (0..3).fold(0u64, |acc, i| {
            let diff = (v[i] - self.sun[i]).unsigned_abs();
            acc.saturating_add(diff.saturating_mul(diff))
        });
        #[allow(clippy::cast_possible_wrap)] // isqrt of a u64 is below 2^32
        let d = q.isqrt() as i64;
        let inputs = [v[0], v[1], v[2], d];
        let mut z = self.output_bias;
        for j in 0..H {
            // Q7.24 · Q1.30 = Q54; |product| < 2^62.
            let h = (0..4).fold(self.constant[j], |acc, k| {
                acc.saturating_add(i64::from(self.coeff[j][k]) * inputs[k])
            });
            let a = activation(round_shift(h, PRODUCT_FRAC, PRE_FRAC));
            for (zc, w) in z.iter_mut().zip(&self.output) {
                // Q7.24 · Q23 = Q47; |product| < 2^54.
                *zc = zc.saturating_add(i64::from(w[j]) * a);
            }
        }
        // Eq. 7 through eq. 6's output activation: L_s(f(z)) = ½ z² (see the neural module).
        core::array::from_fn(|c| {
            let z24 = round_shift(z[c], WEIGHT_FRAC + ACT_FRAC, 24);
            let z_abs = z24.unsigned_abs();
            let z2 = z_abs.saturating_mul(z_abs); // Q48
            let product = u128::from(z2) * u128::from(self.radiance_factor[c]);
            u64::try_from(product >> self.factor_shift.min(127)).unwrap_or(u64::MAX)
        })
    }
}

/// The crate's below-horizon rule in Q1.30: z < −HORIZON_TOLERANCE ⇔ z · 2³⁰ < −1073.74 ⇔
/// the integer z · 2³⁰ < −1073.
#[allow(clippy::cast_possible_truncation)] // 1073.74 truncated towards zero, as intended
const HORIZON_Q30: i64 =
    -((crate::geom::HORIZON_TOLERANCE as f64 * (1u64 << UNIT_FRAC) as f64) as i64);

/// Eq. 5, f(h) = 1/(1 + h²), for h in Q20: the result in Q23, in (0, 2²³].
#[inline]
fn activation(h: i64) -> i64 {
    let m = h.unsigned_abs();
    let denominator = (1u64 << (2 * PRE_FRAC)).saturating_add(m.saturating_mul(m));
    // 2^63 / (2^40 (1 + h²)) = 2^23 f(h), rounded; the denominator is at least 2^40.
    let a = ((1u64 << 63) + denominator / 2) / denominator;
    #[allow(clippy::cast_possible_wrap)] // a ≤ 2^23
    {
        a as i64
    }
}

/// `dir` normalised to a Q1.30 unit vector by an integer square root; 0 for the zero vector.
fn unit_q30(dir: [i16; 3]) -> [i64; 3] {
    let v = dir.map(i64::from);
    #[allow(clippy::cast_sign_loss)] // a sum of squares
    let n2 = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) as u64; // ≤ 3 · 2^30
    // |v| · 2^16, exact to the integer: n2 · 2^32 < 2^64.
    #[allow(clippy::cast_possible_wrap)] // below 2^33
    let length = (n2 << 32).isqrt() as i64;
    // v · 2^46 / (|v| 2^16) = v/|v| · 2^30; |v 2^46| ≤ 2^61.
    v.map(|c| (c << 46).checked_div(length).unwrap_or(0))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn activation_matches_the_formula() {
        for i in -4000..=4000 {
            let h = f64::from(i) / 200.0;
            #[allow(clippy::cast_possible_truncation)]
            let hq = (h * f64::from(1u32 << PRE_FRAC)) as i64;
            let got = activation(hq);
            let h = hq as f64 / f64::from(1u32 << PRE_FRAC); // the value actually passed
            let want = 1.0 / (1.0 + h * h) * f64::from(1u32 << ACT_FRAC);
            assert!(
                (got as f64 - want).abs() <= 1.0,
                "f({h}) = {got}, want {want}"
            );
        }
        assert_eq!(activation(0), 1 << ACT_FRAC);
        assert!(activation(i64::MIN) <= 1); // 2^63 / (2^64 − 1), rounded
        assert!(activation(i64::MAX) <= 1);
    }

    #[test]
    fn unit_vectors_have_unit_length() {
        for dir in [
            [3, 4, 0],
            [1, 0, 0],
            [-32768, -32768, -32768],
            [32767, -5, 9],
            [0, 0, -1],
        ] {
            let v = unit_q30(dir);
            let n2: f64 = v
                .iter()
                .map(|&c| (c as f64 / f64::from(1u32 << 30)).powi(2))
                .sum();
            assert!((n2 - 1.0).abs() < 1e-8, "{dir:?} -> {v:?}");
        }
        assert_eq!(unit_q30([3, 4, 0])[0], (3 << 30) / 5);
        assert_eq!(unit_q30([0, 0, 0]), [0, 0, 0]);
    }
}
