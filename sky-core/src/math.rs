//! The one front for floating-point functions.
//!
//! Every transcendental function the crate uses goes through here, so that all targets (firmware,
//! wasm, host) compute the same results.
//!
//! * Functions evaluated once per sky (in constructors) are [`libm`]'s: portable, deterministic
//!   and correctly rounded or nearly so; with the `micromath` feature (opt-in by a firmware
//!   binary) they are micromath's approximations, smaller and faster, whose effect on each
//!   model is stated in the crate docs and held by `tests/tests/micromath.rs`.
//! * Functions evaluated per view direction ([`exp`], [`exp2`], [`atan2`], [`rsqrt`],
//!   [`sqrt_kernel`]) are branch-free polynomial kernels written for SIMD: plain IEEE `+ - * /` and bit operations, no table and no branch,
//!   so a loop over directions compiles to vector code (SSE2 on any x86-64, AVX2 where the
//!   caller enables it, scalar on microcontrollers) and gives bit-identical results everywhere,
//!   because Rust never fuses `a * b + c`. Their accuracy is stated on each and tested against
//!   libm.

/// The functions evaluated once per sky, from [`libm`] (default): portable, correctly rounded
/// or nearly so.
#[cfg(not(feature = "micromath"))]
mod backend {
    pub(crate) fn sqrt(x: f32) -> f32 {
        libm::sqrtf(x)
    }
    pub(crate) fn sin(x: f32) -> f32 {
        libm::sinf(x)
    }
    pub(crate) fn cos(x: f32) -> f32 {
        libm::cosf(x)
    }
    pub(crate) fn tan(x: f32) -> f32 {
        libm::tanf(x)
    }
    pub(crate) fn atan2(y: f32, x: f32) -> f32 {
        libm::atan2f(y, x)
    }
    pub(crate) fn floor(x: f32) -> f32 {
        libm::floorf(x)
    }
}

/// The functions evaluated once per sky, from [`micromath`] (feature `micromath`): smaller
/// and faster, approximate (sin, cos, atan2 to about 2e-3 absolute; tan as sin/cos). √x is
/// this module's polynomial kernel instead of micromath's (whose error averages 5 %): 4e-7
/// relative, branch-free. [`powf`] stays libm's in both builds: micromath's, exp(y ln x), is
/// off by up to 25 % on the sRGB transfer curve (x^2.4 near x = 0.05).
#[cfg(feature = "micromath")]
mod backend {
    use micromath::F32;

    pub(crate) fn sqrt(x: f32) -> f32 {
        super::sqrt_kernel(x)
    }
    pub(crate) fn sin(x: f32) -> f32 {
        F32(x).sin().0
    }
    pub(crate) fn cos(x: f32) -> f32 {
        F32(x).cos().0
    }
    pub(crate) fn tan(x: f32) -> f32 {
        F32(x).tan().0
    }
    pub(crate) fn atan2(y: f32, x: f32) -> f32 {
        F32(y).atan2(F32(x)).0
    }
    pub(crate) fn floor(x: f32) -> f32 {
        F32(x).floor().0
    }
}

pub(crate) use backend::{cos, floor, sin, sqrt, tan};

/// x^y from libm, whatever the backend (see the micromath backend's docs).
#[inline]
pub(crate) fn powf(x: f32, y: f32) -> f32 {
    libm::powf(x, y)
}

/// e^x from libm, whatever the backend (for what is computed once per sky or per
/// measurement; the per-direction [`exp`] is the polynomial kernel below).
#[inline]
pub(crate) fn exp_libm(x: f32) -> f32 {
    libm::expf(x)
}

/// arccos from libm, whatever the backend.
#[inline]
pub(crate) fn acos(x: f32) -> f32 {
    libm::acosf(x)
}

/// The natural logarithm from libm, whatever the backend.
#[inline]
pub(crate) fn ln(x: f32) -> f32 {
    libm::logf(x)
}

/// atan2(y, x) of the backend (libm or micromath), for what is computed once; the per-direction
/// [`atan2`] is the polynomial kernel below.
#[inline]
pub(crate) fn atan2_libm(y: f32, x: f32) -> f32 {
    backend::atan2(y, x)
}

/// `x` rounded to the nearest integer, ties to even (f64: for fixed-point conversion).
#[inline]
pub(crate) fn rint64(x: f64) -> f64 {
    libm::rint(x)
}

/// 1.5 · 2²³: adding and subtracting it rounds an f32 of magnitude below 2²² to the nearest
/// integer (ties to even), and leaves that integer in the low mantissa bits.
const ROUND_MAGIC: f32 = 12_582_912.0;

/// `select(c, a, b)`: `a` where `c`, else `b`, written so that it compiles to a blend.
#[inline(always)]
fn select(c: bool, a: f32, b: f32) -> f32 {
    if c { a } else { b }
}

/// The smaller of `x` and `hi`; NaN gives `hi`. A compare and a blend: unlike [`f32::min`],
/// which must also return the non-NaN operand when `hi` is NaN, it is one instruction in
/// WebAssembly's SIMD (`f32x4.pmin`) and SSE (`minps`); `hi` must not be NaN.
#[inline(always)]
pub(crate) fn at_most(x: f32, hi: f32) -> f32 {
    select(x < hi, x, hi)
}

/// The larger of `x` and `lo`; NaN gives `lo`. The counterpart of [`at_most`]; `lo` must not be
/// NaN.
#[inline(always)]
pub(crate) fn at_least(x: f32, lo: f32) -> f32 {
    select(x > lo, x, lo)
}

/// 2^x, branch-free. Relative error at most 2.5e-7 (≈ 4 ulp) for x in [-126, 127.4] (tested
/// against libm); 0 below that range and NaN, 2^127.4 above it, so the result is always finite.
///
/// Method: x = n + r with n an integer and |r| ≤ ½ (exact in f32), 2^r by a degree-5 minimax
/// polynomial (relative error 7.5e-8 in exact arithmetic; coefficients from a Remez exchange),
/// 2ⁿ assembled in the exponent bits.
#[inline(always)]
#[allow(clippy::cast_possible_wrap, clippy::cast_sign_loss)] // bit patterns, by design
pub(crate) fn exp2(x: f32) -> f32 {
    const MIN_X: f32 = -126.0; // 2^-126: the smallest normal result
    const MAX_X: f32 = 127.4; // n stays ≤ 127
    // NaN becomes MIN_X, then 0 below.
    let xc = at_most(at_least(x, MIN_X), MAX_X);
    let t = xc + ROUND_MAGIC;
    let n = t - ROUND_MAGIC;
    let r = xc - n;
    let p = ((((1.327_647_2e-3 * r + 9.675_541e-3) * r + 5.550_713e-2) * r + 2.402_212e-1) * r
        + 6.931_469_4e-1)
        * r
        + 1.000_000_1;
    // t's low mantissa bits hold n + 2^22 (two's complement within the 23-bit field).
    let n_int = (t.to_bits() as i32) - (ROUND_MAGIC.to_bits() as i32);
    let scale = f32::from_bits(((n_int + 127) << 23) as u32);
    select(x >= MIN_X, p * scale, 0.0)
}

/// e^x = 2^(x log₂e), branch-free: the error of [`exp2`] plus |x| · 1.2e-7 relative from rounding
/// log₂e and x log₂e (so 4e-7 for |x| ≤ 1, 2e-6 for |x| ≤ 15); 0 for x below -87.3 and NaN.
#[inline(always)]
pub(crate) fn exp(x: f32) -> f32 {
    exp2(x * core::f32::consts::LOG2_E)
}

/// atan2(y, x) in radians, branch-free. Absolute error at most 3e-7 rad and relative error at
/// most 3e-7 (tested against libm); `atan2(0, 0)` is 0; NaN inputs give a finite value.
///
/// Method (after Cephes' `atanf`): the ratio of the smaller to the larger magnitude, t in [0, 1],
/// is reduced to |z| ≤ tan(π/8) by z = (t − 1)/(t + 1) when t > tan(π/8), atan z by an odd
/// polynomial, then the octant and quadrant are restored.
#[inline(always)]
pub(crate) fn atan2(y: f32, x: f32) -> f32 {
    use core::f32::consts::{FRAC_PI_2, FRAC_PI_4, PI};
    const TAN_PI_8: f32 = 0.414_213_57;
    let (ax, ay) = (x.abs(), y.abs());
    let swap = ay > ax;
    let num = select(swap, ax, ay);
    let den = select(swap, ay, ax);
    // t = num / den in [0, 1]; for t > tan(π/8), z = (t − 1)/(t + 1) = (num − den)/(num + den):
    // one division either way. 0/0 → 0; a NaN quotient also becomes 0 through max.
    let big = num > TAN_PI_8 * den;
    let z_num = select(big, num - den, num);
    let z_den = select(big, num + den, den);
    let z = at_least(z_num / select(z_den > 0.0, z_den, 1.0), -1.0);
    let z2 = z * z;
    let poly = (((8.053_744_5e-2 * z2 - 1.387_768_5e-1) * z2 + 1.997_771_1e-1) * z2 - 3.333_295e-1)
        * z2
        * z
        + z;
    let a = select(big, FRAC_PI_4 + poly, poly);
    let a = select(swap, FRAC_PI_2 - a, a);
    let a = select(x < 0.0, PI - a, a);
    select(y < 0.0, -a, a)
}

/// 1/√x for x ≥ 0, branch-free: a bit-level first guess (relative error ≤ 3.5e-2) refined by
/// three Newton steps (error ≈ 1.5 e² each: 1.8e-3, 5e-6, then below f32 rounding).
/// Relative error at most 3e-7 for x in [1e-30, 1e30] (tested against libm); 0 and subnormals
/// give a large finite value (so `x * rsqrt(x)` is 0 for x = 0), NaN gives a finite value.
#[inline(always)]
pub(crate) fn rsqrt(x: f32) -> f32 {
    let [r] = rsqrt_lanes([x]);
    r
}

/// [`rsqrt`] of `L` lanes: the same operations, each step done for every lane before the next
/// step starts. The lanes' dependency chains (three Newton steps, twelve operations deep) then
/// sit side by side in the instruction stream, so a CPU overlaps them instead of waiting on each.
#[inline(always)]
pub(crate) fn rsqrt_lanes<const L: usize>(x: [f32; L]) -> [f32; L] {
    let mut r = [0.0; L];
    let mut half = [0.0; L];
    for i in 0..L {
        // Clamp to the smallest normal (NaN also goes to the bound).
        let x = at_most(at_least(x[i], f32::MIN_POSITIVE), f32::MAX);
        r[i] = f32::from_bits(0x5f37_5a86 - (x.to_bits() >> 1));
        half[i] = 0.5 * x;
    }
    for _ in 0..3 {
        for i in 0..L {
            r[i] *= 1.5 - half[i] * r[i] * r[i];
        }
    }
    r
}

/// √x, branch-free: `x · rsqrt(x)`. Relative error at most 4e-7 for x in [1e-30, 1e30] (tested
/// against libm); exactly 0 for 0; negative numbers and NaN give 0, +∞ a large finite value.
#[inline(always)]
pub(crate) fn sqrt_kernel(x: f32) -> f32 {
    // NaN goes to 0.
    let x = at_most(at_least(x, 0.0), f32::MAX);
    x * rsqrt(x)
}

/// `x` rounded to the nearest integer n (ties to even), returned as the bits of the f32
/// `n + 1.5 · 2²³`, branch-free: a key that differs exactly when n differs, for |x| < 2²².
/// Larger magnitudes and NaN give some fixed-per-input key, never a panic.
#[inline(always)]
pub(crate) fn round_key(x: f32) -> u32 {
    (x + ROUND_MAGIC).to_bits()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rel(a: f32, b: f32) -> f32 {
        if b == 0.0 {
            a.abs()
        } else {
            ((a - b) / b).abs()
        }
    }

    #[test]
    fn exp2_matches_libm() {
        let mut worst = 0.0f32;
        let mut x = -126.0f32;
        while x < 127.4 {
            worst = worst.max(rel(exp2(x), libm::exp2(f64::from(x)) as f32));
            x += 0.000_371;
        }
        assert!(worst <= 2.5e-7, "exp2 relative error {worst}");
        assert_eq!(exp2(-200.0), 0.0);
        assert_eq!(exp2(f32::NEG_INFINITY), 0.0);
        assert_eq!(exp2(f32::NAN), 0.0);
        assert!(exp2(1000.0).is_finite() && exp2(f32::INFINITY).is_finite());
        assert!((exp2(0.0) - 1.0).abs() <= 2e-7 && exp2(1.0) == 2.0 * exp2(0.0));
    }

    #[test]
    fn exp_matches_libm() {
        // The documented bound: exp2's error (and the reference's rounding) plus |x| 1.2e-7 (rounding of log₂e and of the product).
        let mut x = -87.0f32;
        while x < 88.0 {
            let bound = 3e-7 + x.abs() * 1.2e-7;
            let e = rel(exp(x), libm::exp(f64::from(x)) as f32);
            assert!(e <= bound, "exp({x}) relative error {e} > {bound}");
            x += 0.000_731;
        }
        assert_eq!(exp(-200.0), 0.0);
    }

    #[test]
    fn atan2_matches_libm() {
        let mut worst_abs = 0.0f32;
        let mut worst_rel = 0.0f32;
        for i in 0..2000 {
            let a = -3.2 + 6.4 * (i as f32) / 2000.0;
            for r in [1e-6f32, 0.01, 0.7, 1.0, 3.0, 1e4] {
                let (y, x) = (r * libm::sinf(a), r * libm::cosf(a));
                let want = libm::atan2(f64::from(y), f64::from(x)) as f32;
                let got = atan2(y, x);
                worst_abs = worst_abs.max((got - want).abs());
                worst_rel = worst_rel.max(rel(got, want));
            }
        }
        // Near zero angles the relative error matters: sky-core's angle between nearby
        // directions is atan2(small, ~1).
        for k in 0..200 {
            let y = 1e-7f32 * 1.1f32.powi(k);
            let want = libm::atan2(f64::from(y), 1.0) as f32;
            worst_rel = worst_rel.max(rel(atan2(y, 1.0), want));
        }
        assert!(worst_abs <= 3e-7, "atan2 absolute error {worst_abs}");
        assert!(worst_rel <= 3e-7, "atan2 relative error {worst_rel}");
        assert_eq!(atan2(0.0, 0.0), 0.0);
        assert!(atan2(f32::NAN, 1.0).is_finite());
    }

    #[test]
    fn at_most_and_at_least_map_nan_to_the_bound() {
        assert_eq!(at_most(f32::NAN, 2.0), 2.0);
        assert_eq!(at_least(f32::NAN, -2.0), -2.0);
        assert_eq!(at_most(3.0, 2.0), 2.0);
        assert_eq!(at_most(-3.0, 2.0), -3.0);
        assert_eq!(at_least(-3.0, -2.0), -2.0);
        assert_eq!(at_least(3.0, -2.0), 3.0);
        assert_eq!(at_most(f32::INFINITY, f32::MAX), f32::MAX);
    }

    #[test]
    fn rsqrt_matches_libm() {
        let mut worst = 0.0f32;
        let mut x = 1e-30f32;
        while x < 1e30 {
            let want = (1.0 / libm::sqrt(f64::from(x))) as f32;
            worst = worst.max(rel(rsqrt(x), want));
            x *= 1.000_37;
        }
        assert!(worst <= 3e-7, "rsqrt relative error {worst}");
        assert_eq!(0.0 * rsqrt(0.0), 0.0);
        assert!(rsqrt(f32::NAN).is_finite() && rsqrt(f32::INFINITY).is_finite());
    }

    #[test]
    fn rsqrt_lanes_is_rsqrt_in_each_lane() {
        let x: [f32; 32] = core::array::from_fn(|i| match i {
            0 => 0.0,
            1 => f32::NAN,
            2 => f32::INFINITY,
            3 => -1.0,
            4 => 1e-45,
            _ => 1.7f32.powi(i as i32 - 16),
        });
        let lanes = rsqrt_lanes(x);
        for (x, r) in x.iter().zip(lanes) {
            assert_eq!(r.to_bits(), rsqrt(*x).to_bits(), "{x}");
        }
    }

    #[test]
    fn sqrt_kernel_matches_libm() {
        let mut worst = 0.0f32;
        let mut x = 1e-30f32;
        while x < 1e30 {
            let want = libm::sqrt(f64::from(x)) as f32;
            worst = worst.max(rel(sqrt_kernel(x), want));
            x *= 1.000_37;
        }
        assert!(worst <= 4e-7, "sqrt relative error {worst}");
        assert_eq!(sqrt_kernel(0.0), 0.0);
        assert_eq!(sqrt_kernel(-4.0), 0.0);
        assert_eq!(sqrt_kernel(f32::NAN), 0.0);
        assert!(sqrt_kernel(f32::INFINITY).is_finite());
    }

    #[test]
    fn round_key_separates_integers() {
        // Keys are equal exactly when the rounded integers are equal.
        let mut prev = round_key(-5000.0);
        for k in -4999..5000 {
            let x = k as f32;
            let key = round_key(x);
            assert_ne!(key, prev, "{x}");
            assert_eq!(round_key(x + 0.49), key, "{x} + 0.49");
            assert_eq!(round_key(x - 0.49), key, "{x} - 0.49");
            prev = key;
        }
        let _ = round_key(f32::NAN); // no panic
    }
}
