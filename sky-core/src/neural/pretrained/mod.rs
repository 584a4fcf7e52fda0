//! Neural skies trained by `sky-train` and shipped as Rust constants.
//!
//! The constants are generated from the weight files in `sky-core/weights/` by
//! `sky-train export`; a test regenerates them and fails on any difference. [`PREETHAM_FIXED`]
//! and [`HOSEK_FIXED`] are the same networks quantised for
//! [`FixedNeuralSky`](super::FixedNeuralSky) (`sky-train export --format fixed`). Their accuracy on
//! seed 000's test protocol (held by tests in `tests/tests/neural.rs`):
//!
//! | constant | trained on | mean NRMSE | mean irradiance difference |
//! |---|---|---|---|
//! | [`PREETHAM`] | Preetham, turbidity 2-6 | 0.0083 | 0.20 % |
//! | [`HOSEK`] | Hosek-Wilkie, turbidity 1-10, albedo 0.5 | 0.0239 | 1.5 % |
//!
//! [`DAYLIGHT_DAY`], [`DAYLIGHT_DUSK`] and [`DAYLIGHT_NIGHT`] (6-24-3) are the sky of
//! [`Daylight::sky`](crate::daylight::Daylight::sky), trained by `sky-train daylight-sky` on the
//! physical atmosphere's radiance over its diffuse illuminance, CIE X, Y, Z, with the aerosol
//! optical depth τ₅₅₀ as the "turbidity" input (its accuracy is
//! [`DaylightSky`](crate::daylight::DaylightSky)'s).

mod daylight_day;
mod daylight_dusk;
mod daylight_night;
mod hosek;
mod hosek_fixed;
mod preetham;
mod preetham_fixed;

pub use daylight_day::DAYLIGHT_DAY;
pub use daylight_dusk::DAYLIGHT_DUSK;
pub use daylight_night::DAYLIGHT_NIGHT;
pub use hosek::HOSEK;
pub use hosek_fixed::HOSEK_FIXED;
pub use preetham::PREETHAM;
pub use preetham_fixed::PREETHAM_FIXED;
