//! Numbers in error messages, written as Rust's `Display` writes an `f32` but by the JavaScript
//! engine (`js/f32-text.js`, a wasm-bindgen snippet beside the bindings): `core::fmt`'s float
//! formatting (Grisu with the Dragon fallback, their tables) is 8.6 KB of the .wasm that only
//! error messages used, and the same in Rust through `js_sys` 4 KB (docs/browser.md, "Size").

use core::fmt;

use sky_core::SkyError;
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
