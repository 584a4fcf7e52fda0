//! sky-core for Python: the extension module `skymodels._skymodels` of the `skymodels` wheel.
//!
//! A thin layer: each sky-core type is bound in one place (`time`: UTC instants and sites;
//! `series`: the daylight, the sun and the controller over arrays of times; `sky`: the sky
//! models and their images; `physical`: sky-train's spectral atmosphere, behind the `physical`
//! feature). The Python package (`python/skymodels/__init__.py`) turns Python's and numpy's
//! times into microseconds since 1970 UTC and documents the functions taking times; everything
//! else is documented here, and those docs are the Python docstrings.
//!
//! Values are sky-core's own: the same functions, in f32 as sky-core computes them (widened to
//! float64 exactly where a result is a time series). Every parameter sky-core refuses becomes a
//! `ValueError` carrying sky-core's message (the parameter, its value and its range); nothing a
//! Python caller passes can panic (sky-core never panics, and this layer indexes only within
//! lengths it has checked).

#![deny(unsafe_code)]

mod series;
mod sky;
mod time;

#[cfg(feature = "physical")]
mod physical;

use core::fmt::Display;

use pyo3::exceptions::{PyMemoryError, PyValueError};
use pyo3::prelude::*;
use sky_core::daylight;

/// A `ValueError` with `message`, prefixed by `context` (the Python parameter or the element of
/// an array it concerns) unless that is empty.
pub(crate) fn value_error(context: &str, message: impl Display) -> PyErr {
    if context.is_empty() {
        PyValueError::new_err(message.to_string())
    } else {
        PyValueError::new_err(format!("{context}: {message}"))
    }
}

/// Room for `n` more items in `v`, or Python's `MemoryError` (never an abort).
pub(crate) fn reserve<T>(v: &mut Vec<T>, n: usize) -> PyResult<()> {
    v.try_reserve_exact(n)
        .map_err(|_| PyMemoryError::new_err(format!("{n} values do not fit in memory")))
}

/// The `n` items of `items` in a vector, or Python's `MemoryError`.
pub(crate) fn collect<T>(n: usize, items: impl IntoIterator<Item = T>) -> PyResult<Vec<T>> {
    let mut v = Vec::new();
    reserve(&mut v, n)?;
    v.extend(items);
    Ok(v)
}

/// The extension module.
#[pymodule]
fn _skymodels(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(series::daylight_series, m)?)?;
    m.add_function(wrap_pyfunction!(series::daylight_at_sun, m)?)?;
    m.add_function(wrap_pyfunction!(series::sun_position_series, m)?)?;
    m.add_function(wrap_pyfunction!(series::controller_series, m)?)?;
    m.add_function(wrap_pyfunction!(sky::direction, m)?)?;
    m.add_function(wrap_pyfunction!(sky::equirect_directions, m)?)?;
    m.add_class::<sky::Sky>()?;
    m.add("DEFAULT_AOD", f64::from(daylight::DEFAULT_AOD))?;
    m.add("MIN_AOD", f64::from(daylight::MIN_AOD))?;
    m.add("MAX_AOD", f64::from(daylight::MAX_AOD))?;
    m.add("OZONE_DU", f64::from(daylight::OZONE_DU))?;
    m.add("GROUND_ALBEDO", f64::from(daylight::GROUND_ALBEDO))?;
    m.add("HAS_PHYSICAL", cfg!(feature = "physical"))?;
    #[cfg(feature = "physical")]
    m.add_class::<physical::PhysicalAtmosphere>()?;
    Ok(())
}
