//! Numbers in error messages, written as Rust's `Display` writes an `f32` but with the digits
//! found by the JavaScript engine: `core::fmt`'s float formatting (Grisu with the Dragon
//! fallback and their tables) is 18 KB of the .wasm that only error messages used
//! (docs/browser.md, "Size").

use core::fmt;

use js_sys::{Math, Number};
use sky_core::SkyError;
use wasm_bindgen::JsError;

/// Significant digits that always read back as the same `f32`.
const F32_DIGITS: u8 = 9;

/// `v` as `format!("{v}")` writes it: the shortest decimal that reads back as `v` (by
/// JavaScript's `toPrecision`, which rounds the exact value correctly, and `parseFloat` then
/// `Math.fround` for reading back), in positional notation (no exponent), `NaN`, `inf`, `-inf`.
/// `tests/wasm.rs` compares it with Rust's own on a thousand values across the range.
#[must_use]
pub fn f32_text(v: f32) -> String {
    if v.is_nan() {
        return "NaN".into();
    }
    let sign = if v.is_sign_negative() { "-" } else { "" };
    if v.is_infinite() {
        return [sign, "inf"].concat();
    }
    if v == 0.0 {
        return [sign, "0"].concat();
    }
    let x = f64::from(v.abs());
    let js = Number::from(x);
    let mut shortest = String::new();
    for precision in 1..=F32_DIGITS {
        let Ok(text) = js.to_precision(precision) else {
            break;
        };
        shortest = text.into();
        if Math::fround(js_sys::parse_float(&shortest)) == v.abs() {
            break;
        }
    }
    positional(sign, &shortest)
}

/// The number JavaScript wrote as `text` ("8.64e+4", "0.00123", "123.5") in positional
/// notation after `sign`, without leading or trailing zeros beyond the point's (byte by byte:
/// `str`'s splitting and parsing would cost the .wasm more than this).
fn positional(sign: &str, text: &str) -> String {
    let mut digits = Vec::with_capacity(16);
    // The value is 0.digits × 10^point.
    let (mut point, mut exponent, mut exponent_sign) = (0i32, 0i32, 1);
    let (mut after_point, mut in_exponent) = (false, false);
    for &c in text.as_bytes() {
        match c {
            b'.' => after_point = true,
            b'e' => in_exponent = true,
            b'-' => exponent_sign = -1,
            b'0'..=b'9' if in_exponent => exponent = 10 * exponent + i32::from(c - b'0'),
            b'0' if digits.is_empty() => point -= i32::from(after_point),
            b'0'..=b'9' => {
                digits.push(c);
                point += i32::from(!after_point);
            }
            _ => {}
        }
    }
    while digits.last() == Some(&b'0') {
        digits.pop();
    }
    point += exponent_sign * exponent;
    let mut out = Vec::from(sign.as_bytes());
    if point <= 0 {
        out.extend_from_slice(b"0.");
        out.resize(out.len() + point.unsigned_abs() as usize, b'0');
        out.extend_from_slice(&digits);
    } else {
        let point = point.unsigned_abs() as usize;
        if point >= digits.len() {
            digits.resize(point, b'0');
        } else {
            digits.insert(point, b'.');
        }
        out.extend_from_slice(&digits);
    }
    String::from_utf8(out).unwrap_or_default()
}

/// sky-core's error as a JavaScript `Error` with sky-core's message (its numbers by
/// [`f32_text`]).
pub(crate) fn js_error(e: SkyError) -> JsError {
    let mut text = String::new();
    // Writing into a String cannot fail.
    let _ = e.write_message(&mut text, &|out: &mut String, v| {
        out.push_str(&f32_text(v));
        Ok(())
    });
    JsError::new(&text)
}

/// An error of another type (no numbers to format) as a JavaScript `Error` with its message.
pub(crate) fn display_error(e: impl fmt::Display) -> JsError {
    JsError::new(&e.to_string())
}
