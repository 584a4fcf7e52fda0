//! End-to-end tests of the sky library. The library part holds the independent f64 reference
//! implementations the tests in `tests/` compare against.

pub mod fixtures;
pub mod reference;

/// The Rust blocks of the front page and of every page in `docs/`, run as doctests: each
/// compiles and runs as written (`cargo test -p sky-tests --doc`).
#[cfg(doctest)]
pub mod pages {
    #[doc = include_str!("../../README.md")]
    pub mod readme {}
    #[doc = include_str!("../../docs/accuracy.md")]
    pub mod accuracy {}
    #[doc = include_str!("../../docs/browser.md")]
    pub mod browser {}
    #[doc = include_str!("../../docs/captures.md")]
    pub mod captures {}
    #[doc = include_str!("../../docs/controller.md")]
    pub mod controller {}
    #[doc = include_str!("../../docs/daylight.md")]
    pub mod daylight {}
    #[doc = include_str!("../../docs/firmware.md")]
    pub mod firmware {}
    #[doc = include_str!("../../docs/gpu.md")]
    pub mod gpu {}
    #[doc = include_str!("../../docs/performance.md")]
    pub mod performance {}
    #[doc = include_str!("../../docs/python.md")]
    pub mod python {}
    #[doc = include_str!("../../docs/sh.md")]
    pub mod sh {}
    #[doc = include_str!("../../docs/sh_errors.md")]
    pub mod sh_errors {}
    #[doc = include_str!("../../docs/testing.md")]
    pub mod testing {}
    #[doc = include_str!("../../docs/training.md")]
    pub mod training {}
    #[doc = include_str!("../../docs/weather.md")]
    pub mod weather {}
    #[doc = include_str!("../../sky-core/README.md")]
    pub mod sky_core_readme {}
    #[doc = include_str!("../../sky-gpu/README.md")]
    pub mod sky_gpu_readme {}
    #[doc = include_str!("../../sky-train/README.md")]
    pub mod sky_train_readme {}
}
