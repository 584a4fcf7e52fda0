//! Correlated colour temperature (CCT) and Duv from chromaticity.
//!
//! CCT is the temperature of the Planckian radiator whose chromaticity lies nearest to the
//! given one in the CIE 1960 UCS diagram (u, v) (CIE 015:2018 §9.5); Duv is that distance,
//! signed as in ANSI C78.377: **positive above the Planckian locus** (greenish), negative below
//! (pinkish). This module finds the nearest point itself, by minimising the distance to the
//! locus over the reciprocal temperature (mired), which is what Ohno's table method (Ohno,
//! *Practical use and calculation of CCT and Duv*, LEUKOS 10(1), 2014) approximates; the locus
//! is Planck's law integrated against the CIE 1931 2° colour-matching functions (360-830 nm,
//! 5 nm steps, c₂ = 1.4388·10⁻² m·K as in CIE 015).
//!
//! **Accuracy** (tested against colour-science 0.4.7's Ohno 2013 implementation along and off
//! the locus, Duv −0.03 to 0.03, 1,700-25,000 K): CCT within 2 K below 10,000 K and 0.1 %
//! above, Duv within 1·10⁻⁴. CCT is computed over 1,000-100,000 K; it is meaningful only for
//! |Duv| ≤ 0.05 (ANSI C78.377), which is not enforced.
//!
//! The computation is in f64 (about 90 evaluations of the locus, each a 95-term sum): it is
//! meant for a controller's update every few seconds, not per pixel.

pub mod cmf;

use crate::error::SkyError;

/// The lowest CCT returned, in kelvin.
pub const MIN_CCT: f32 = 1_000.0;
/// The highest CCT returned, in kelvin.
pub const MAX_CCT: f32 = 100_000.0;

/// Planck's second radiation constant in µm·K (CIE 015:2018, ITS-90).
const C2_UM_K: f64 = 14_388.0;

/// A correlated colour temperature and the signed distance from the Planckian locus.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Cct {
    /// Correlated colour temperature in kelvin.
    pub kelvin: f32,
    /// Distance from the Planckian locus in CIE 1960 (u, v), positive above it (ANSI C78.377).
    pub duv: f32,
}

/// CIE 1960 UCS (u, v) from CIE 1931 (x, y): u = 4x / (−2x + 12y + 3), v = 6y / (−2x + 12y + 3).
#[must_use]
pub fn xy_to_uv(x: f64, y: f64) -> (f64, f64) {
    let d = -2.0 * x + 12.0 * y + 3.0;
    (4.0 * x / d, 6.0 * y / d)
}

/// CIE 1931 (x, y) from CIE 1960 UCS (u, v): x = 3u / (2u − 8v + 4), y = 2v / (2u − 8v + 4).
#[must_use]
pub fn uv_to_xy(u: f64, v: f64) -> (f64, f64) {
    let d = 2.0 * u - 8.0 * v + 4.0;
    (3.0 * u / d, 2.0 * v / d)
}

/// The Planckian radiator's chromaticity (u, v) at `kelvin` (any positive temperature).
///
/// ```
/// // D65, (u, v) = (0.19784, 0.31223), has CCT 6504 K and Duv 0.0032 (CIE 015:2018).
/// let (u, v) = sky_core::cct::planckian_uv(6504.0);
/// assert!(((u - 0.19784).hypot(v - 0.31223) - 0.0032).abs() < 1e-4);
/// ```
#[must_use]
pub fn planckian_uv(kelvin: f64) -> (f64, f64) {
    let mut xyz = [0.0f64; 3];
    for (i, row) in cmf::CMF.iter().enumerate() {
        #[allow(clippy::cast_precision_loss)] // i < 100
        let lambda_um = (cmf::FIRST_NM + cmf::STEP_NM * i as f64) * 1e-3;
        // Planck's law without c₁ (it cancels in chromaticity).
        let l2 = lambda_um * lambda_um;
        let m = 1.0 / (l2 * l2 * lambda_um * libm::expm1(C2_UM_K / (lambda_um * kelvin)));
        for c in 0..3 {
            xyz[c] += m * row[c];
        }
    }
    let sum = xyz[0] + xyz[1] + xyz[2];
    xy_to_uv(xyz[0] / sum, xyz[1] / sum)
}

/// The point of the locus at `mired` (10⁶ / kelvin) and its squared distance from (u, v).
fn locus_distance2(u: f64, v: f64, mired: f64) -> (f64, f64, f64) {
    let (lu, lv) = planckian_uv(1e6 / mired);
    let (du, dv) = (u - lu, v - lv);
    (du * du + dv * dv, lu, lv)
}

/// CCT and Duv of the chromaticity (`x`, `y`) (CIE 1931).
///
/// ```
/// use sky_core::cct::cct_duv;
/// let d65 = cct_duv(0.31271, 0.32902)?;
/// assert!((d65.kelvin - 6504.0).abs() < 2.0);   // D65's CCT
/// assert!((d65.duv - 0.0032).abs() < 1e-4);     // above the locus
/// # Ok::<(), sky_core::SkyError>(())
/// ```
///
/// # Errors
/// [`SkyError::OutOfRange`] for x outside [0, 1] or y outside (0, 1] (or NaN), or a
/// chromaticity whose CCT lies outside [[`MIN_CCT`], [`MAX_CCT`]].
#[allow(clippy::cast_possible_truncation)] // f64 result to the crate's f32
pub fn cct_duv(x: f32, y: f32) -> Result<Cct, SkyError> {
    let out = |parameter, value: f32, min, max| SkyError::OutOfRange {
        parameter,
        value,
        min,
        max,
    };
    // Not only physical colours: near 1,700 K the locus runs within 0.01 of the spectral
    // locus (x + y = 1), and points above it there have x + y > 1; their Duv is still defined.
    if !(0.0..=1.0).contains(&x) {
        return Err(out("chromaticity x", x, 0.0, 1.0));
    }
    if !(y > 0.0 && y <= 1.0) {
        return Err(out("chromaticity y", y, f32::MIN_POSITIVE, 1.0));
    }
    let (u, v) = xy_to_uv(f64::from(x), f64::from(y));
    // Coarse scan over the mired range, then golden-section search between the nearest grid
    // point's neighbours (the distance is unimodal there).
    const STEP: f64 = 20.0;
    let (lo, hi) = (1e6 / f64::from(MAX_CCT), 1e6 / f64::from(MIN_CCT));
    let mut best = (f64::INFINITY, lo);
    let mut m = lo;
    while m <= hi + 1e-9 {
        let (d2, _, _) = locus_distance2(u, v, m);
        if d2 < best.0 {
            best = (d2, m);
        }
        m += STEP;
    }
    let (mut a, mut b) = ((best.1 - STEP).max(lo), (best.1 + STEP).min(hi));
    const INV_PHI: f64 = 0.618_033_988_749_894_8;
    let mut c = b - INV_PHI * (b - a);
    let mut d = a + INV_PHI * (b - a);
    let (mut fc, mut fd) = (locus_distance2(u, v, c).0, locus_distance2(u, v, d).0);
    while b - a > 1e-7 {
        if fc < fd {
            (b, d, fd) = (d, c, fc);
            c = b - INV_PHI * (b - a);
            fc = locus_distance2(u, v, c).0;
        } else {
            (a, c, fc) = (c, d, fd);
            d = a + INV_PHI * (b - a);
            fd = locus_distance2(u, v, d).0;
        }
    }
    let mired = 0.5 * (a + b);
    let kelvin = 1e6 / mired;
    // At the ends of the range the nearest point is the end itself: the CCT lies outside.
    if mired - lo < 1e-3 || hi - mired < 1e-3 {
        return Err(out(
            "correlated colour temperature [K]",
            kelvin as f32,
            MIN_CCT,
            MAX_CCT,
        ));
    }
    let (d2, _, lv) = locus_distance2(u, v, mired);
    let duv = libm::sqrt(d2).copysign(v - lv);
    Ok(Cct {
        kelvin: kelvin as f32,
        duv: duv as f32,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn colour_matching_functions_are_the_standards() {
        // The standard's normalisation: ȳ peaks at 1 at 555 nm, and the three sums are equal to
        // within the table's rounding (equal-energy white at x = y = 1/3).
        let peak = cmf::CMF.iter().map(|r| r[1]).fold(0.0f64, f64::max);
        assert_eq!(peak, 1.0);
        let sums = [0, 1, 2].map(|c| cmf::CMF.iter().map(|r| r[c]).sum::<f64>());
        let total: f64 = sums.iter().sum();
        assert!((sums[0] / total - 1.0 / 3.0).abs() < 1e-3, "{sums:?}");
        assert!((sums[1] / total - 1.0 / 3.0).abs() < 1e-3, "{sums:?}");
    }

    #[test]
    fn uv_round_trip() {
        let (u, v) = xy_to_uv(0.3127, 0.3290);
        let (x, y) = uv_to_xy(u, v);
        assert!((x - 0.3127).abs() < 1e-12 && (y - 0.3290).abs() < 1e-12);
    }

    #[test]
    fn illuminant_a_is_on_the_locus() {
        // CIE illuminant A is the Planckian radiator at 2856 K (c₂ = 1.4388e-2 m·K); its
        // published chromaticity is (0.44757, 0.40745) (CIE 015:2018 Table 1).
        let a = cct_duv(0.44757, 0.40745).expect("valid");
        assert!((a.kelvin - 2856.0).abs() < 1.0, "{a:?}");
        assert!(a.duv.abs() < 2e-5, "{a:?}");
    }

    #[test]
    fn bad_chromaticities_are_errors() {
        assert!(cct_duv(f32::NAN, 0.3).is_err());
        assert!(cct_duv(0.3, 0.0).is_err());
        assert!(cct_duv(0.6, 1.5).is_err());
        // Deep red, far beyond 1000 K along the locus.
        assert!(cct_duv(0.7, 0.29).is_err());
    }
}
