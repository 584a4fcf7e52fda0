//! Numbers in error messages, written as Rust's `Display` writes an `f32` but by the JavaScript
//! engine (`js/f32-text.js`, a wasm-bindgen snippet beside the bindings): `core::fmt`'s float
//! formatting (Grisu with the Dragon fallback, their tables) is 8.6 KB of the .wasm that only
//! error messages used, and the same in Rust through `js_sys` 4 KB (docs/browser.md, "Size").
//! Integers are written digit by digit, and no message goes through `format!` or `Display`: the
//! .wasm links none of `core::fmt`'s formatting.

use sky_core::SkyError;
#[cfg(feature = "neural-file")]
use sky_core::neural::WeightsError;
use wasm_bindgen::JsError;
use wasm_bindgen::prelude::wasm_bindgen;

#[wasm_bindgen(module = "/js/f32-text.js")]
extern "C" {
    /// `v` as `format!("{v}")` writes it: the shortest decimal that reads back as `v` (by
    /// `toPrecision`, which rounds the exact value correctly, and `parseFloat` then
    /// `Math.fround` for reading back) in positional notation (no exponent), `NaN`, `inf`,
    /// `-inf`. `tests/wasm.rs` compares it with Rust's own on a thousand values across the
    /// range.
    #[wasm_bindgen(js_name = f32Text)]
    pub fn f32_text(v: f32) -> String;
}

/// sky-core's error as a JavaScript `Error` with sky-core's message (its numbers by
/// [`f32_text`]).
pub(crate) fn js_error(e: SkyError) -> JsError {
    let mut text = String::new();
    // Writing into a String cannot fail.
    let _ = e.write_message(&mut text, &|out, v| out.write_str(&f32_text(v)));
    JsError::new(&text)
}

/// A weight file's error as a JavaScript `Error` with sky-core's message.
#[cfg(feature = "neural-file")]
pub(crate) fn weights_error(e: WeightsError) -> JsError {
    let mut text = String::new();
    // Writing into a String cannot fail.
    let _ = e.write_message(&mut text);
    JsError::new(&text)
}

/// Appends `n` in decimal, as its `Display` does.
pub(crate) fn push_decimal(out: &mut String, n: usize) {
    if n >= 10 {
        push_decimal(out, n / 10);
    }
    #[allow(clippy::cast_possible_truncation)] // a digit
    out.push(char::from(b'0' + (n % 10) as u8));
}
