//! Colour spaces: CIE xyY and XYZ, linear sRGB and encoded sRGB (seed 002, eqs. 27-29).
//!
//! Luminance `Y` keeps whatever unit the caller uses (the sky models use cd/m²); linear sRGB
//! triples are on the same scale, so the luminance of `(1, 1, 1)` is 1.

use glam::{Mat3, Vec3};

use crate::math;

/// A colour as CIE 1931 chromaticity `x, y` and luminance `Y`.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Xyy {
    /// Chromaticity x.
    pub x: f32,
    /// Chromaticity y.
    pub y: f32,
    /// Luminance Y (the sky models report cd/m²).
    pub luminance: f32,
}

/// XYZ → linear sRGB, seed 002 eq. 28 (the matrix as given there). Stored column-major.
pub const XYZ_TO_LINEAR_SRGB: Mat3 = Mat3::from_cols_array(&[
    3.240_625_5,
    -0.968_930_7,
    0.055_710_1,
    -1.537_207_3,
    1.875_756_1,
    -0.204_021_1,
    -0.498_628_6,
    0.041_517_5,
    1.056_995_9,
]);

/// Linear sRGB → XYZ: the inverse of [`XYZ_TO_LINEAR_SRGB`], computed in exact rational
/// arithmetic and rounded to f32 (it equals the sRGB standard's matrix to 1e-7). Column-major.
pub const LINEAR_SRGB_TO_XYZ: Mat3 = Mat3::from_cols_array(&[
    0.412_399_94,
    0.212_599_96,
    0.019_300_014,
    0.357_599_8,
    0.715_199_9,
    0.119_200_03,
    0.180_499_99,
    0.072_200_01,
    0.950_500_1,
]);

/// xyY → XYZ, seed 002 eq. 27: X = x Y / y, Z = (1 − x − y) Y / y.
///
/// A chromaticity with `y ≤ 0` has no defined XYZ; it gives black (`0, 0, 0`), never NaN.
#[inline]
#[must_use]
pub fn xyy_to_xyz(c: Xyy) -> Vec3 {
    // Branch-free, so that loops over colours vectorise.
    let s = if c.y > 0.0 { c.luminance / c.y } else { 0.0 };
    let lum = if c.y > 0.0 { c.luminance } else { 0.0 };
    Vec3::new(c.x * s, lum, (1.0 - c.x - c.y) * s)
}

/// XYZ → xyY. Black (X + Y + Z ≤ 0) gets the chromaticity of D65 (0.3127, 0.3290) and Y = 0.
#[inline]
#[must_use]
pub fn xyz_to_xyy(xyz: Vec3) -> Xyy {
    let sum = xyz.x + xyz.y + xyz.z;
    if sum > 0.0 {
        Xyy {
            x: xyz.x / sum,
            y: xyz.y / sum,
            luminance: xyz.y,
        }
    } else {
        Xyy {
            x: 0.3127,
            y: 0.3290,
            luminance: 0.0,
        }
    }
}

/// XYZ → linear sRGB, seed 002 eq. 28. Out-of-gamut colours give negative components; they are
/// not clipped.
#[inline]
#[must_use]
pub fn xyz_to_linear_srgb(xyz: Vec3) -> Vec3 {
    XYZ_TO_LINEAR_SRGB * xyz
}

/// Linear sRGB → XYZ (the inverse of eq. 28).
#[inline]
#[must_use]
pub fn linear_srgb_to_xyz(rgb: Vec3) -> Vec3 {
    LINEAR_SRGB_TO_XYZ * rgb
}

/// The luminance Y of a linear sRGB colour (the middle row of [`LINEAR_SRGB_TO_XYZ`]).
#[inline]
#[must_use]
pub fn luminance(rgb: Vec3) -> f32 {
    LINEAR_SRGB_TO_XYZ.row(1).dot(rgb)
}

/// Encodes one linear sRGB component in `[0, 1]` with the sRGB transfer function, seed 002
/// eq. 29. Values outside `[0, 1]` are clamped first; NaN gives 0.
#[inline]
#[must_use]
pub fn srgb_encode(linear: f32) -> f32 {
    let c = if linear > 0.0 { linear.min(1.0) } else { 0.0 };
    if c <= 0.003_130_8 {
        12.92 * c
    } else {
        1.055 * math::powf(c, 1.0 / 2.4) - 0.055
    }
}

/// Decodes one sRGB-encoded component in `[0, 1]` to linear (the inverse of eq. 29). Values
/// outside `[0, 1]` are clamped first; NaN gives 0.
#[inline]
#[must_use]
pub fn srgb_decode(encoded: f32) -> f32 {
    let c = if encoded > 0.0 { encoded.min(1.0) } else { 0.0 };
    if c <= 0.040_45 {
        c / 12.92
    } else {
        math::powf((c + 0.055) / 1.055, 2.4)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn matrices_are_inverse() {
        let p = XYZ_TO_LINEAR_SRGB * LINEAR_SRGB_TO_XYZ;
        let err = (p - Mat3::IDENTITY).to_cols_array();
        assert!(err.iter().all(|e| e.abs() < 2e-6), "{p}");
    }

    #[test]
    fn d65_white_is_grey() {
        // D65 white point, Y = 1: linear sRGB (1, 1, 1) by construction of sRGB.
        let rgb = xyz_to_linear_srgb(xyy_to_xyz(Xyy {
            x: 0.3127,
            y: 0.3290,
            luminance: 1.0,
        }));
        assert!((rgb - Vec3::ONE).abs().max_element() < 1e-3, "{rgb}");
        assert!((luminance(Vec3::ONE) - 1.0).abs() < 1e-6);
    }

    #[test]
    fn xyy_round_trip() {
        let c = Xyy {
            x: 0.25,
            y: 0.27,
            luminance: 4000.0,
        };
        let back = xyz_to_xyy(xyy_to_xyz(c));
        assert!((back.x - c.x).abs() < 1e-6 && (back.y - c.y).abs() < 1e-6);
        assert!((back.luminance - c.luminance).abs() < 1e-3);
        assert_eq!(xyy_to_xyz(Xyy::default()), Vec3::ZERO);
    }

    #[test]
    fn transfer_function_round_trip_and_knee() {
        for i in 0..=1000u16 {
            let v = f32::from(i) / 1000.0;
            assert!((srgb_decode(srgb_encode(v)) - v).abs() < 1e-5, "{v}");
        }
        // Values from the sRGB standard (IEC 61966-2-1): encode(0.0031308) = 0.04045, encode(1) = 1.
        assert!((srgb_encode(0.003_130_8) - 0.040_45).abs() < 1e-6);
        assert!((srgb_encode(1.0) - 1.0).abs() < 1e-6);
        assert!((srgb_encode(0.5) - 0.735_356_6).abs() < 1e-5);
        assert_eq!(srgb_encode(f32::NAN), 0.0);
        assert_eq!(srgb_encode(7.0), srgb_encode(1.0));
    }
}
