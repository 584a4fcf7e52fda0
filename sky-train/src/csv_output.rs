//! How numbers are written: one rule for every CSV column of every command, and a compact
//! form for the numbers that messages quote.
//!
//! **The CSV rule** ([`number`]): a value is written as the shortest decimal that reads back
//! as the same `f32` (Rust's shortest round-trip formatting, the `Debug` form of `f32`),
//! with an exponent below 1e-4 and from 1e16 up (`9.7e-10`, not `0.000000`), without a
//! trailing `.0` (`-18`, not `-18.0`) and with `-0` written `0`; a value that is not finite
//! is an empty field. So `0.1 + 0.2` is `0.3`, a twilight illuminance of 9.7e-10 lx keeps
//! its digits, and every value carries the same relative precision (f32's, about 7
//! significant digits, finer than any of the models' stated errors). Quoted fields that are
//! the user's own text (the view directions `sample` echoes, the chromaticities of `cct`)
//! are written as given.

use std::fmt::Write as _;

/// `v` as a CSV field by the module's rule: the shortest decimal that reads back as the same
/// `f32`, empty when `v` is not finite.
#[must_use]
pub fn number(v: f64) -> String {
    let mut s = String::new();
    push_number(&mut s, v);
    s
}

/// Appends [`number`]`(v)` to `out`.
pub fn push_number(out: &mut String, v: f64) {
    if !v.is_finite() {
        return;
    }
    #[allow(clippy::cast_possible_truncation)] // the rule: the f32 value
    let f = v as f32;
    if !f.is_finite() {
        // Beyond f32's range: the f64's own shortest form.
        let _ = write!(out, "{v:e}");
        return;
    }
    if f == 0.0 {
        out.push('0');
        return;
    }
    let start = out.len();
    let _ = write!(out, "{f:?}");
    if out[start..].ends_with(".0") {
        out.truncate(out.len() - 2);
    }
}

/// `v` for a message: as the user would type it, compactly (`1e9`, `3e38`, `0.0001`,
/// `100000`): the shortest round-trip decimal of the f64, with an exponent from 1e6 up
/// and below 1e-4.
#[must_use]
pub fn compact(v: f64) -> String {
    compact_of(v)
}

/// An f32 for a message, as [`compact`] writes an f64: its shortest round-trip decimal, with
/// an exponent from 1e6 up and below 1e-4 (`3.4028235e38`, not 39 digits).
#[must_use]
pub fn compact_f32(v: f32) -> String {
    compact_of(v)
}

/// [`compact`]'s rule for a float of either width (each prints its own shortest decimal).
fn compact_of<T>(v: T) -> String
where
    T: Copy + Into<f64> + std::fmt::Display + std::fmt::LowerExp,
{
    let x: f64 = v.into();
    if x == 0.0 {
        "0".into()
    } else if !x.is_finite() || !(1e-4..1e6).contains(&x.abs()) {
        format!("{v:e}")
    } else {
        format!("{v}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_rule_on_the_issues_cases() {
        assert_eq!(number(0.1 + 0.2), "0.3");
        assert_eq!(number(9.7e-10), "9.7e-10");
        assert_eq!(number(-18.0), "-18");
        assert_eq!(number(-0.0), "0");
        assert_eq!(number(f64::NAN), "");
        assert_eq!(number(f64::INFINITY), "");
        assert_eq!(number(1e300), "1e300");
        assert_eq!(number(123_456.79), "123456.79");
        // Round trip of the f32 value.
        for v in [1.234_567_9e-7, 6504.277, 0.312_72, 1.0e20, 3.0e38] {
            #[allow(clippy::cast_possible_truncation)]
            let f = v as f32;
            assert_eq!(number(v).parse::<f32>().ok(), Some(f), "{v}");
        }
        assert_eq!(compact(1e9), "1e9");
        assert_eq!(compact(3e38), "3e38");
        assert_eq!(compact(100_000.0), "100000");
        assert_eq!(compact(0.0001), "0.0001");
        assert_eq!(compact(-0.5), "-0.5");
        assert_eq!(compact_f32(f32::MAX), "3.4028235e38");
        assert_eq!(compact_f32(0.1), "0.1");
        assert_eq!(compact_f32(60.0), "60");
    }
}
