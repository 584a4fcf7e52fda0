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

impl SkyError {
    /// Writes the message (the text of [`Display`](fmt::Display)) into `out`, each number in it
    /// (a value, a range's ends, a zenith angle) written by `number`. [`Display`](fmt::Display)
    /// writes them with `f32`'s own `Display`; a caller with another formatter (a smaller one
    /// for a size-bound build such as the browser's) passes it here.
    ///
    /// ```
    /// use core::fmt::Write;
    /// use sky_core::SkyError;
    ///
    /// let e = SkyError::OutOfRange { parameter: "turbidity", value: 9.0, min: 2.0, max: 6.0 };
    /// let mut text = String::new();
    /// e.write_message(&mut text, &|out: &mut String, v| write!(out, "{v:.1}"))?;
    /// assert_eq!(text, "turbidity = 9.0 is outside the valid range [2.0, 6.0]");
    /// assert_eq!(e.to_string(), "turbidity = 9 is outside the valid range [2, 6]");
    /// # Ok::<(), core::fmt::Error>(())
    /// ```
    ///
    /// # Errors
    /// What `out` or `number` return.
    pub fn write_message<W: fmt::Write + ?Sized>(
        &self,
        out: &mut W,
        number: &dyn Fn(&mut W, f32) -> fmt::Result,
    ) -> fmt::Result {
        match *self {
            Self::NotFinite { parameter } => write!(out, "{parameter} must be a finite number"),
            Self::OutOfRange {
                parameter,
                value,
                min,
                max,
            } => {
                write!(out, "{parameter} = ")?;
                number(out, value)?;
                out.write_str(" is outside the valid range [")?;
                number(out, min)?;
                out.write_str(", ")?;
                number(out, max)?;
                out.write_str("]")
            }
            Self::SunBelowHorizon { zenith } => {
                out.write_str("the sun is below the horizon (zenith ")?;
                number(out, zenith)?;
                out.write_str(" rad > pi/2), where this model is undefined")
            }
            Self::CapacityExceeded {
                collection,
                capacity,
                needed,
            } => write!(
                out,
                "{collection}: {needed} needed, but at most {capacity} fit (fixed capacity, no allocation)"
            ),
        }
    }
}

impl fmt::Display for SkyError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.write_message(f, &|f, v| write!(f, "{v}"))
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
