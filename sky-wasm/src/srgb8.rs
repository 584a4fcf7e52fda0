//! 8-bit sRGB encoding by table lookup: the transfer function (seed 002 eq. 29, sky-core's
//! [`srgb_encode`]) costs a `powf` per channel, three per pixel; a frame needs a cheaper path.

use sky_core::color::srgb_encode;

/// Table entries: the table is indexed by √c, where the encoded value changes slowly enough
/// that one step moves it by at most 0.09 of an 8-bit code (largest near c = 0.0031, where
/// eq. 29's linear segment meets the power segment), so a lookup is within one code of
/// rounding the exact encoding.
const ENTRIES: usize = 4096;

/// The table of 8-bit sRGB codes.
#[derive(Debug, Clone)]
pub struct Srgb8 {
    codes: Box<[u8; ENTRIES]>,
}

impl Default for Srgb8 {
    fn default() -> Self {
        Self::new()
    }
}

impl Srgb8 {
    /// Builds the table from sky-core's [`srgb_encode`].
    #[must_use]
    #[allow(
        clippy::cast_precision_loss,
        clippy::cast_possible_truncation,
        clippy::cast_sign_loss
    )] // k < 4096 is exact in f32; codes lie in [0, 255]
    pub fn new() -> Self {
        let mut codes = Box::new([0u8; ENTRIES]);
        let last = (ENTRIES - 1) as f32;
        for (k, code) in codes.iter_mut().enumerate() {
            let s = k as f32 / last;
            *code = (255.0 * srgb_encode(s * s) + 0.5) as u8;
        }
        Self { codes }
    }

    /// The 8-bit sRGB code of the linear value `c` (clamped to [0, 1]; NaN gives 0).
    #[inline(always)]
    #[must_use]
    pub fn encode(&self, c: f32) -> u8 {
        self.code(Self::key(c))
    }

    /// The table index of the linear value `c`: arithmetic only, so that a loop of keys
    /// vectorises; [`code`](Self::code) then looks it up (a frame computes its keys first).
    #[inline(always)]
    #[must_use]
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)] // in [0.5, 4095.5]
    pub fn key(c: f32) -> u32 {
        // Compares and blends (NaN goes to 0): f32::max/min would also have to pick the non-NaN
        // operand, which costs several instructions per channel in WebAssembly.
        let c = if c > 0.0 { c } else { 0.0 };
        let c = if c < 1.0 { c } else { 1.0 };
        (c.sqrt() * (ENTRIES - 1) as f32 + 0.5) as u32
    }

    /// The 8-bit code of a [`key`](Self::key) (keys beyond the table give 255).
    #[inline(always)]
    #[must_use]
    pub fn code(&self, key: u32) -> u8 {
        self.codes.get(key as usize).copied().unwrap_or(u8::MAX)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn within_one_code_of_the_exact_encoding() {
        let table = Srgb8::new();
        let mut worst = 0.0f32;
        for k in 0..=200_000u32 {
            #[allow(clippy::cast_precision_loss)]
            let c = k as f32 / 200_000.0;
            let exact = 255.0 * srgb_encode(c);
            worst = worst.max((f32::from(table.encode(c)) - exact).abs());
        }
        // Rounding alone gives up to 0.5; the table's step adds at most 0.09.
        assert!(worst <= 0.6, "worst {worst} codes");
    }

    #[test]
    fn clamps_and_maps_nan_to_black() {
        let table = Srgb8::new();
        assert_eq!(table.encode(f32::NAN), 0);
        assert_eq!(table.encode(-3.0), 0);
        assert_eq!(table.encode(7.0), 255);
        assert_eq!(table.encode(f32::INFINITY), 255);
        assert_eq!(table.encode(1.0), 255);
    }
}
