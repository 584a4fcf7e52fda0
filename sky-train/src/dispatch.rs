//! Runtime CPU-feature dispatch for the batch evaluators.
//!
//! sky-core's batch loops are branch-free and compile to SIMD code for whatever the build
//! targets: SSE2 (4 lanes) on any x86-64. [`fastest`] runs such a loop compiled a second time
//! with AVX2 (8 lanes) when the CPU running the program has it, so one binary runs everywhere
//! and at full width where it can. Both paths perform the same IEEE operations (no fused
//! multiply-add), so their results are identical bit for bit.
//!
//! The neural sky has a kernel of its own for AVX2 with fused multiply-add
//! ([`sky_core::NeuralSky::rgb_batch_avx2`], about 30 % faster, rounding differently):
//! [`neural_batch`] picks it. So has the daylight sky's
//! ([`sky_core::daylight::DaylightSky::rgb_batch_avx2`]): [`daylight_batch`].

use sky_core::daylight::DaylightSky;
use sky_core::{NeuralSky, Vec3};

/// Runs `f`, compiled with AVX2 enabled when the CPU supports it.
///
/// `f` should call an `#[inline(always)]` batch function (such as
/// [`sky_core::PreethamSky::rgb_batch`]) so that its loop is compiled inside the AVX2 context.
#[inline(always)]
pub fn fastest<R>(f: impl FnOnce() -> R) -> R {
    #[cfg(target_arch = "x86_64")]
    if std::is_x86_feature_detected!("avx2") {
        #[target_feature(enable = "avx2")]
        fn avx2<R>(f: impl FnOnce() -> R) -> R {
            f()
        }
        // SAFETY: `avx2` may only run on CPUs with AVX2, which was detected just above.
        #[allow(unsafe_code)]
        return unsafe { avx2(f) };
    }
    f()
}

/// Fills `out` with `sky`'s radiance towards `dirs` by the fastest kernel this CPU runs:
/// [`NeuralSky::rgb_batch_avx2`] where it has AVX2 and FMA, else [`NeuralSky::rgb_batch`] through
/// [`fastest`].
pub fn neural_batch<const H: usize>(sky: &NeuralSky<H>, dirs: &[Vec3], out: &mut [Vec3]) {
    #[cfg(target_arch = "x86_64")]
    if has_avx2_fma() {
        // SAFETY: the CPU has AVX2 and FMA, which was detected just above.
        #[allow(unsafe_code)]
        unsafe {
            sky.rgb_batch_avx2(dirs, out);
        }
        return;
    }
    fastest(
        #[inline(always)]
        || sky.rgb_batch(dirs, out),
    );
}

/// Fills `out` with the daylight sky's linear sRGB radiance towards `dirs` by the fastest
/// kernel this CPU runs: [`DaylightSky::rgb_batch_avx2`] where it has AVX2 and FMA, else
/// [`DaylightSky::rgb_batch`] through [`fastest`].
pub fn daylight_batch(sky: &DaylightSky, dirs: &[Vec3], out: &mut [Vec3]) {
    #[cfg(target_arch = "x86_64")]
    if has_avx2_fma() {
        // SAFETY: the CPU has AVX2 and FMA, which was detected just above.
        #[allow(unsafe_code)]
        unsafe {
            sky.rgb_batch_avx2(dirs, out);
        }
        return;
    }
    fastest(
        #[inline(always)]
        || sky.rgb_batch(dirs, out),
    );
}

/// [`daylight_batch`] for CIE X, Y, Z ([`DaylightSky::xyz_batch_avx2`] or
/// [`DaylightSky::xyz_batch`]).
pub fn daylight_xyz_batch(sky: &DaylightSky, dirs: &[Vec3], out: &mut [Vec3]) {
    #[cfg(target_arch = "x86_64")]
    if has_avx2_fma() {
        // SAFETY: the CPU has AVX2 and FMA, which was detected just above.
        #[allow(unsafe_code)]
        unsafe {
            sky.xyz_batch_avx2(dirs, out);
        }
        return;
    }
    fastest(
        #[inline(always)]
        || sky.xyz_batch(dirs, out),
    );
}

/// Whether this CPU has AVX2 and FMA (the features of [`NeuralSky::rgb_batch_avx2`] and
/// [`DaylightSky::rgb_batch_avx2`]).
#[must_use]
pub fn has_avx2_fma() -> bool {
    #[cfg(target_arch = "x86_64")]
    return std::is_x86_feature_detected!("avx2") && std::is_x86_feature_detected!("fma");
    #[cfg(not(target_arch = "x86_64"))]
    false
}

/// The instruction set [`fastest`] uses on this CPU.
#[must_use]
pub fn describe() -> &'static str {
    #[cfg(target_arch = "x86_64")]
    if std::is_x86_feature_detected!("avx2") {
        return "AVX2, 8 lanes";
    }
    if cfg!(target_arch = "x86_64") {
        "SSE2, 4 lanes"
    } else {
        "the build's baseline"
    }
}
