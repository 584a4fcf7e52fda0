//! Independent f64 references shared by the end-to-end tests.
//!
//! Everything here is written from the seed papers' text, in f64, with no code or types taken
//! from `sky-core`: the tests compare `sky-core` and `sky-train` against it.

pub mod daylight;
pub mod neural;
pub mod preetham;
pub mod weather;
