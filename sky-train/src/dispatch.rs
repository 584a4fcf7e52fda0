//! Runtime CPU-feature dispatch for the batch evaluators.
//!
//! sky-core's batch loops are branch-free and compile to SIMD code for whatever the build
//! targets: SSE2 (4 lanes) on any x86-64. [`fastest`] runs such a loop compiled a second time
//! with AVX2 (8 lanes) when the CPU running the program has it, so one binary runs everywhere
//! and at full width where it can. Both paths perform the same IEEE operations (no fused
//! multiply-add), so their results are identical bit for bit.

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
