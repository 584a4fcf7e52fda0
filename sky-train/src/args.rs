//! Command-line values, parsed and checked in one place for the subcommands and the libraries
//! below them: numbers in a range, dates, clock times, durations, `a,b` lines on stdin, and the
//! [`ParamError`] that names the flag and its valid range (exit status 2).
//!
//! The `fn(&str) -> Result<T, String>` parsers are clap value parsers
//! (`#[arg(value_parser = args::latitude)]`); clap puts the flag's name before their message.

use std::fmt;

use anyhow::Result;
use sky_core::solar::UtcTime;

/// A parameter the user gave that the model rejects, phrased in the command line's terms.
#[derive(Debug, Clone, PartialEq)]
pub struct ParamError(pub String);

impl fmt::Display for ParamError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for ParamError {}

/// Describes a sky-core error with each parameter named by `name` (given the parameter's name
/// without its unit) and `separator` between the name and its value; angles in degrees.
pub(crate) fn describe(
    e: sky_core::SkyError,
    name: impl Fn(&str) -> String,
    separator: &str,
) -> String {
    use sky_core::SkyError as E;
    // "clouds.radius [rad]" -> ("clouds.radius", "rad")
    let split = |parameter: &'static str| match parameter.rsplit_once(" [") {
        Some((base, unit)) => (base, unit.trim_end_matches(']')),
        None => (parameter, ""),
    };
    match e {
        E::NotFinite { parameter } => {
            format!("{} must be a finite number", name(split(parameter).0))
        }
        E::OutOfRange {
            parameter,
            value,
            min,
            max,
        } => {
            let (base, unit) = split(parameter);
            // The ends as they were checked: `f32::MIN_POSITIVE` stands for "above 0", and a
            // refused value at an end means that end is excluded.
            let positive = min == f32::MIN_POSITIVE;
            let (open_min, open_max) = (positive || value == min, value == max);
            let min = if positive { 0.0 } else { min };
            if positive && max >= f32::MAX {
                let value = crate::csv_output::compact_f32(value);
                return format!("{}{separator}{value} must be positive", name(base));
            }
            let (value, min, max, unit) = match unit {
                "rad" => (
                    value.to_degrees(),
                    min.to_degrees(),
                    max.to_degrees(),
                    " deg".to_owned(),
                ),
                "" => (value, min, max, String::new()),
                other => (value, min, max, format!(" {other}")),
            };
            if max >= f32::MAX && value < min {
                // No upper end worth printing (sky-core's "at least min").
                return format!(
                    "{}{separator}{value}{unit} is below the lowest valid value {min}{unit}",
                    name(base)
                );
            }
            let (low, high) = (
                if open_min { "(" } else { "[" },
                if open_max { ")" } else { "]" },
            );
            let [value, min, max] = [value, min, max].map(crate::csv_output::compact_f32);
            format!(
                "{}{separator}{value}{unit} is outside the valid range {low}{min}, {max}{high}{unit}",
                name(base)
            )
        }
        other => other.to_string(),
    }
}

/// Checks before long work that `path` (given as `flag`) names a `.{extension}` file in an
/// existing folder.
///
/// # Errors
/// `{flag} {path}: expected a .{extension} file in an existing folder`.
pub fn check_output(flag: &str, path: &std::path::Path, extension: &str) -> Result<(), ParamError> {
    let dir = path
        .parent()
        .filter(|d| !d.as_os_str().is_empty())
        .unwrap_or(std::path::Path::new("."));
    if path.extension().is_none_or(|e| e != extension) || !dir.is_dir() {
        return Err(ParamError(format!(
            "{flag} {}: expected a .{extension} file in an existing folder",
            path.display()
        )));
    }
    Ok(())
}

/// Converts degrees to radians in f64 and rounds once to f32.
#[allow(clippy::cast_possible_truncation)] // the point of the function
#[must_use]
pub fn radians(deg: f64) -> f32 {
    deg.to_radians() as f32
}

/// `s` as a number in `[min, max]`; the error names `what` and the range.
///
/// # Errors
/// `expected {what} in [{min}, {max}]`.
pub fn in_range(s: &str, min: f64, max: f64, what: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(v) if (min..=max).contains(&v) => Ok(v),
        _ => Err(format!(
            "expected {what} in [{}, {}]",
            crate::csv_output::compact(min),
            crate::csv_output::compact(max)
        )),
    }
}

/// Any finite number.
///
/// # Errors
/// Not a number, or infinite.
pub fn finite(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        _ => Err("expected a finite number".into()),
    }
}

/// Any finite number at least 0.
///
/// # Errors
/// Not a number, infinite or negative.
pub fn non_negative(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(v) if v.is_finite() && v >= 0.0 => Ok(v),
        _ => Err("expected a finite number, at least 0".into()),
    }
}

/// A latitude in degrees, north positive (-90 to 90).
///
/// # Errors
/// Outside the range, or not a number.
pub fn latitude(s: &str) -> Result<f64, String> {
    in_range(s, -90.0, 90.0, "a latitude in degrees")
}

/// A longitude in degrees, east positive (-180 to 180).
///
/// # Errors
/// Outside the range, or not a number.
pub fn longitude(s: &str) -> Result<f64, String> {
    in_range(s, -180.0, 180.0, "a longitude in degrees")
}

/// A site's elevation in metres above sea level (-500 to 10000).
///
/// # Errors
/// Outside the range, or not a number.
pub fn elevation(s: &str) -> Result<f64, String> {
    in_range(s, -500.0, 10_000.0, "an elevation in metres")
}

/// A wall-time budget in seconds (1 to 86400).
///
/// # Errors
/// Outside the range, or not a number.
pub fn seconds(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(v) if (1.0..=86400.0).contains(&v) => Ok(v),
        _ => Err("expected seconds in [1, 86400]".into()),
    }
}

/// The Levenberg-Marquardt weight of each sky's irradiance residual (0 to 100).
///
/// # Errors
/// Outside the range, or not a number.
pub fn irradiance_weight(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(v) if (0.0..=100.0).contains(&v) => Ok(v),
        _ => Err("expected a weight in [0, 100]".into()),
    }
}

/// Parses `YYYY-MM-DD` into a valid calendar date.
///
/// # Errors
/// A [`ParamError`] naming `--date` and the expected form or the field out of range.
pub fn parse_date(s: &str) -> Result<(i32, u32, u32), ParamError> {
    let bad = || {
        ParamError(format!(
            "--date `{s}`: expected YYYY-MM-DD, e.g. 2026-06-21"
        ))
    };
    let (y, m, d) = date_fields(s).ok_or_else(bad)?;
    UtcTime::new(y, m, d, 0, 0, 0.0).map_err(|e| {
        ParamError(format!(
            "--date {s}: {} (the supported years)",
            describe(e, str::to_owned, " = ")
        ))
    })?;
    Ok((y, m, d))
}

/// The fields of `YYYY-MM-DD`, when `s` has that form (whatever their values).
#[must_use]
pub fn date_fields(s: &str) -> Option<(i32, u32, u32)> {
    let mut parts = s.trim().split('-');
    let (Some(y), Some(m), Some(d), None) =
        (parts.next(), parts.next(), parts.next(), parts.next())
    else {
        return None;
    };
    if y.len() != 4 || m.len() != 2 || d.len() != 2 {
        return None;
    }
    let (Ok(y), Ok(m), Ok(d)) = (y.parse::<i32>(), m.parse::<u32>(), d.parse::<u32>()) else {
        return None;
    };
    Some((y, m, d))
}

/// [`parse_date`] as a clap value parser.
///
/// # Errors
/// As [`parse_date`].
pub fn date(s: &str) -> Result<(i32, u32, u32), String> {
    parse_date(s).map_err(|e| e.0)
}

/// `HH:MM` as minutes after midnight.
///
/// # Errors
/// Not of that form, or out of 00:00 to 23:59.
pub fn clock(s: &str) -> Result<u32, String> {
    let bad = || format!("`{s}`: expected HH:MM (00:00 to 23:59)");
    let (h, m) = s.split_once(':').ok_or_else(bad)?;
    match (h.parse::<u32>(), m.parse::<u32>()) {
        (Ok(h), Ok(m)) if h < 24 && m < 60 => Ok(h * 60 + m),
        _ => Err(bad()),
    }
}

/// A duration (`30s`, `1min`, `2m`, `1h`; a bare number is minutes) in minutes, 1 s to 24 h.
///
/// # Errors
/// An unknown unit, or a duration out of the range.
pub fn duration_minutes(s: &str) -> Result<f64, String> {
    let s = s.trim();
    let split = s
        .find(|c: char| !(c.is_ascii_digit() || c == '.'))
        .unwrap_or(s.len());
    let (number, unit) = s.split_at(split);
    let factor = match unit.trim() {
        "" | "m" | "min" => 1.0,
        "s" | "sec" => 1.0 / 60.0,
        "h" => 60.0,
        _ => {
            return Err(format!(
                "`{s}`: expected a duration such as 30s, 1min or 1h"
            ));
        }
    };
    match number.parse::<f64>() {
        Ok(v) if (1.0 / 60.0..=1440.0).contains(&(v * factor)) => Ok(v * factor),
        _ => Err(format!("`{s}`: expected a duration from 1s to 24h")),
    }
}
