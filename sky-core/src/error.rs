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
    /// Writes the message (the text of [`Display`](fmt::Display)) into `out`, each `f32` in it
    /// (a value, a range's ends, a zenith angle) written by `number`. [`Display`](fmt::Display)
    /// writes them with `f32`'s own `Display`; a caller with another formatter (a smaller one
    /// for a size-bound build such as the browser's) passes it here. The rest of the message
    /// (names, integers) is written without `core::fmt`'s formatting machinery, so that a
    /// `number` without it keeps all of it out of the build; `out` is a trait object so that
    /// the message code is compiled once, in this crate, whatever the caller writes into.
    ///
    /// ```
    /// use core::fmt::Write;
    /// use sky_core::SkyError;
    ///
    /// let e = SkyError::OutOfRange { parameter: "turbidity", value: 9.0, min: 2.0, max: 6.0 };
    /// let mut text = String::new();
    /// e.write_message(&mut text, &|out, v| write!(out, "{v:.1}"))?;
    /// assert_eq!(text, "turbidity = 9.0 is outside the valid range [2.0, 6.0]");
    /// assert_eq!(e.to_string(), "turbidity = 9 is outside the valid range [2, 6]");
    /// # Ok::<(), core::fmt::Error>(())
    /// ```
    ///
    /// # Errors
    /// What `out` or `number` return.
    pub fn write_message(
        &self,
        out: &mut dyn fmt::Write,
        number: &dyn Fn(&mut dyn fmt::Write, f32) -> fmt::Result,
    ) -> fmt::Result {
        match *self {
            Self::NotFinite { parameter } => {
                out.write_str(parameter)?;
                out.write_str(" must be a finite number")
            }
            Self::OutOfRange {
                parameter,
                value,
                min,
                max,
            } => {
                out.write_str(parameter)?;
                out.write_str(" = ")?;
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
            } => {
                out.write_str(collection)?;
                out.write_str(": ")?;
                write_decimal(out, needed as u64)?;
                out.write_str(" needed, but at most ")?;
                write_decimal(out, capacity as u64)?;
                out.write_str(" fit (fixed capacity, no allocation)")
            }
        }
    }
}

impl fmt::Display for SkyError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.write_message(f, &|f, v| write!(f, "{v}"))
    }
}

impl core::error::Error for SkyError {}

/// Writes `n` in decimal, as its `Display` does, one digit at a time (no `core::fmt` integer
/// formatting, its digit-pair table and padding).
pub(crate) fn write_decimal(out: &mut dyn fmt::Write, n: u64) -> fmt::Result {
    if n >= 10 {
        write_decimal(out, n / 10)?;
    }
    #[allow(clippy::cast_possible_truncation)] // a digit
    out.write_char(char::from(b'0' + (n % 10) as u8))
}

/// Writes `n` as `{n:#010x}` does (`0x` and eight lower-case hexadecimal digits), without
/// `core::fmt`'s formatting machinery.
pub(crate) fn write_hex32(out: &mut dyn fmt::Write, n: u32) -> fmt::Result {
    out.write_str("0x")?;
    for shift in (0..8).rev() {
        let digit = (n >> (4 * shift)) & 0xF;
        out.write_char(char::from_digit(digit, 16).unwrap_or('?'))?;
    }
    Ok(())
}

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

#[cfg(test)]
mod tests {
    use super::*;

    /// The messages with integers and names, written without `core::fmt`'s formatting, against
    /// the same text written by `format!`.
    #[test]
    fn messages_match_core_fmt() {
        extern crate std;
        use std::format;
        use std::string::ToString;

        for (needed, capacity) in [(0, 0), (65, 64), (usize::MAX, 1_234_567_890)] {
            let e = SkyError::CapacityExceeded {
                collection: "cloud segments",
                capacity,
                needed,
            };
            assert_eq!(
                e.to_string(),
                format!(
                    "{}: {needed} needed, but at most {capacity} fit (fixed capacity, no allocation)",
                    "cloud segments"
                )
            );
        }
        let e = SkyError::NotFinite {
            parameter: "sun azimuth [rad]",
        };
        assert_eq!(
            e.to_string(),
            format!("{} must be a finite number", "sun azimuth [rad]")
        );
        let mut hex = std::string::String::new();
        for n in [0, 1, 0xABCD_EF01, u32::MAX] {
            hex.clear();
            write_hex32(&mut hex, n).expect("a String takes any text");
            assert_eq!(hex, format!("{n:#010x}"));
        }
    }
}
