//! The one error type of the crate.

use core::fmt;

/// Why a sky could not be constructed from the parameters given.
///
/// Every constructor in the crate validates its parameters and returns this error; evaluation
/// after construction cannot fail.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum SkyError {
    /// A parameter that may take any finite value (such as an azimuth) is NaN or infinite.
    NotFinite {
        /// The parameter's name, with its unit.
        parameter: &'static str,
    },
    /// A parameter lies outside the range the model is defined or was fitted for, or is NaN.
    OutOfRange {
        /// The parameter's name, with its unit.
        parameter: &'static str,
        /// The value given.
        value: f32,
        /// The smallest valid value.
        min: f32,
        /// The largest valid value.
        max: f32,
    },
    /// The model is undefined with the sun below the horizon.
    SunBelowHorizon {
        /// The sun's zenith angle in radians (greater than π/2).
        zenith: f32,
    },
    /// A fixed-capacity collection (no allocation) has no room for what was added; nothing was
    /// added.
    CapacityExceeded {
        /// What the collection holds.
        collection: &'static str,
        /// How many items it holds at most.
        capacity: usize,
        /// How many items it would have needed.
        needed: usize,
    },
}

impl fmt::Display for SkyError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Self::NotFinite { parameter } => write!(f, "{parameter} must be a finite number"),
            Self::OutOfRange {
                parameter,
                value,
                min,
                max,
            } => write!(
                f,
                "{parameter} = {value} is outside the valid range [{min}, {max}]"
            ),
            Self::SunBelowHorizon { zenith } => write!(
                f,
                "the sun is below the horizon (zenith {zenith} rad > pi/2), where this model is undefined"
            ),
            Self::CapacityExceeded {
                collection,
                capacity,
                needed,
            } => write!(
                f,
                "{collection}: {needed} needed, but at most {capacity} fit (fixed capacity, no allocation)"
            ),
        }
    }
}

impl core::error::Error for SkyError {}

/// Checks that `value` lies inside `[min, max]` (NaN does not).
pub(crate) fn check_range(
    parameter: &'static str,
    value: f32,
    min: f32,
    max: f32,
) -> Result<f32, SkyError> {
    if !(min..=max).contains(&value) {
        Err(SkyError::OutOfRange {
            parameter,
            value,
            min,
            max,
        })
    } else {
        Ok(value)
    }
}
