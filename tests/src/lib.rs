//! End-to-end tests of the sky library. The library part holds the independent f64 reference
//! implementations the tests in `tests/` compare against.

pub mod fixtures;
pub mod reference;
