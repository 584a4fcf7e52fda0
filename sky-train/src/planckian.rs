//! The Planckian locus computed exactly, in f64, and what is made of it: the exact CCT and Duv
//! by minimising the distance to the locus, and the generator of sky-core's table of the locus
//! (`sky-core/src/cct/locus.rs`, which `sky_core::cct::cct_duv` searches).
//!
//! The locus is Planck's law integrated against the CIE 1931 2° colour-matching functions
//! (sky-core's [`cmf`] table: 360-830 nm in 5 nm steps) with c₂ = 1.4388·10⁻² m·K (CIE
//! 015:2018), in CIE 1960 (u, v), parametrised by mired (10⁶ / kelvin). [`exact_cct_duv`] is
//! the method sky-core used before the table (about 90 locus evaluations of 95 terms each, 200
//! to 330 µs a call): kept here as the reference the table method is tested and benchmarked
//! against.

use std::fmt::Write as _;

use sky_core::cct::cmf;

/// Planck's second radiation constant in µm·K (CIE 015:2018, ITS-90).
const C2_UM_K: f64 = 14_388.0;

/// The command that writes sky-core's locus table (named in the file's header).
pub const LOCUS_TABLE_COMMAND: &str = "sky-train locus-table --out sky-core/src/cct/locus.rs";
/// The lowest mired of the table (100,000 K).
const FIRST_MIRED: f64 = 10.0;
/// Mired per cubic piece of the table.
const STEP_MIRED: f64 = 10.0;
/// Pieces of the table: 10 to 1000 mired (100,000 to 1,000 K).
const PIECES: usize = 99;

/// A point of the locus and its derivative in mired.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LocusPoint {
    /// CIE 1960 u.
    pub u: f64,
    /// CIE 1960 v.
    pub v: f64,
    /// du / dmired.
    pub du: f64,
    /// dv / dmired.
    pub dv: f64,
}

/// The Planckian radiator's chromaticity at `mired` (positive) and its derivative: X, Y, Z and
/// their derivatives summed over the colour-matching functions, then u = 4X / (X + 15Y + 3Z),
/// v = 6Y / (X + 15Y + 3Z) and the quotient rule.
#[must_use]
pub fn locus(mired: f64) -> LocusPoint {
    let (mut xyz, mut dxyz) = ([0.0f64; 3], [0.0f64; 3]);
    for (i, row) in cmf::CMF.iter().enumerate() {
        #[allow(clippy::cast_precision_loss)] // i < 100
        let lambda_um = (cmf::FIRST_NM + cmf::STEP_NM * i as f64) * 1e-3;
        // Planck's law without c₁ (it cancels in chromaticity): M = λ⁻⁵ / (e^(a·mired) − 1)
        // with a = c₂ / (λ · 10⁶); dM/dmired = −λ⁻⁵ a e^(a·mired) / (e^(a·mired) − 1)².
        let a = C2_UM_K / (lambda_um * 1e6);
        let l5 = 1.0 / lambda_um.powi(5);
        let em1 = libm::expm1(a * mired);
        let m = l5 / em1;
        let dm = -l5 * a * (1.0 + em1) / (em1 * em1);
        for c in 0..3 {
            xyz[c] += m * row[c];
            dxyz[c] += dm * row[c];
        }
    }
    let d = xyz[0] + 15.0 * xyz[1] + 3.0 * xyz[2];
    let dd = dxyz[0] + 15.0 * dxyz[1] + 3.0 * dxyz[2];
    LocusPoint {
        u: 4.0 * xyz[0] / d,
        v: 6.0 * xyz[1] / d,
        du: 4.0 * (dxyz[0] * d - xyz[0] * dd) / (d * d),
        dv: 6.0 * (dxyz[1] * d - xyz[1] * dd) / (d * d),
    }
}

/// CIE 1960 (u, v) from CIE 1931 (x, y).
#[must_use]
pub fn xy_to_uv(x: f64, y: f64) -> (f64, f64) {
    let d = -2.0 * x + 12.0 * y + 3.0;
    (4.0 * x / d, 6.0 * y / d)
}

/// CIE 1931 (x, y) from CIE 1960 (u, v).
#[must_use]
pub fn uv_to_xy(u: f64, v: f64) -> (f64, f64) {
    let d = 2.0 * u - 8.0 * v + 4.0;
    (3.0 * u / d, 2.0 * v / d)
}

/// The chromaticity (x, y) at `duv` from the locus at `kelvin`, along the locus's normal
/// (towards larger v for positive `duv`, as Duv is signed).
#[must_use]
pub fn off_locus(kelvin: f64, duv: f64) -> (f64, f64) {
    let p = locus(1e6 / kelvin);
    let s = p.du.hypot(p.dv);
    uv_to_xy(p.u - p.dv / s * duv, p.v + p.du / s * duv)
}

/// The squared distance of (u, v) from the locus at `mired`, and the locus point.
fn distance2(u: f64, v: f64, mired: f64) -> (f64, LocusPoint) {
    let p = locus(mired);
    ((u - p.u).powi(2) + (v - p.v).powi(2), p)
}

/// CCT (kelvin) and Duv (positive above the locus) of (`x`, `y`) by minimising the distance to
/// the exact locus over 10-1000 mired: a scan in 20-mired steps, then golden-section search to
/// 10⁻⁷ mired between the nearest grid point's neighbours. `None` for x outside [0, 1], y
/// outside (0, 1], or a nearest point at an end of the range (CCT outside 1,000-100,000 K).
#[must_use]
pub fn exact_cct_duv(x: f64, y: f64) -> Option<(f64, f64)> {
    const STEP: f64 = 20.0;
    const INV_PHI: f64 = 0.618_033_988_749_894_8;
    if !((0.0..=1.0).contains(&x) && y > 0.0 && y <= 1.0) {
        return None;
    }
    let (u, v) = xy_to_uv(x, y);
    let (lo, hi) = (FIRST_MIRED, FIRST_MIRED + STEP_MIRED * 99.0);
    let mut best = (f64::INFINITY, lo);
    let mut m = lo;
    while m <= hi + 1e-9 {
        let d2 = distance2(u, v, m).0;
        if d2 < best.0 {
            best = (d2, m);
        }
        m += STEP;
    }
    let (mut a, mut b) = ((best.1 - STEP).max(lo), (best.1 + STEP).min(hi));
    let mut c = b - INV_PHI * (b - a);
    let mut d = a + INV_PHI * (b - a);
    let (mut fc, mut fd) = (distance2(u, v, c).0, distance2(u, v, d).0);
    while b - a > 1e-7 {
        if fc < fd {
            (b, d, fd) = (d, c, fc);
            c = b - INV_PHI * (b - a);
            fc = distance2(u, v, c).0;
        } else {
            (a, c, fc) = (c, d, fd);
            d = a + INV_PHI * (b - a);
            fd = distance2(u, v, d).0;
        }
    }
    let mired = 0.5 * (a + b);
    if mired - lo < 1e-3 || hi - mired < 1e-3 {
        return None;
    }
    let (d2, p) = distance2(u, v, mired);
    Some((1e6 / mired, d2.sqrt().copysign(v - p.v)))
}

/// The cubic c₀ + c₁t + c₂t² + c₃t³ on t ∈ [0, 1] with values `p0`, `p1` and derivatives (per
/// unit t) `d0`, `d1` at its ends (cubic Hermite interpolation).
fn hermite(p0: f64, p1: f64, d0: f64, d1: f64) -> [f64; 4] {
    [
        p0,
        d0,
        3.0 * (p1 - p0) - 2.0 * d0 - d1,
        2.0 * (p0 - p1) + d0 + d1,
    ]
}

/// Rust source of `sky-core/src/cct/locus.rs`: the locus over 10-1000 mired as 99 cubic pieces
/// of 10 mired, each the Hermite interpolant of [`locus`] and its derivative at the piece's
/// ends, computed in f64 and rounded to f32 coefficient by coefficient (rounding the knots
/// instead would tilt the pieces' tangents by up to 2·10⁻⁵ rad, which moves the nearest point
/// of a chromaticity 0.05 off the locus by 0.1 K at 10,000 K).
#[must_use]
pub fn locus_table_source() -> String {
    let mut s = format!("// Generated by `{LOCUS_TABLE_COMMAND}`; do not edit.\n\n");
    s += "//! The Planckian locus in CIE 1960 (u, v) from 10 to 1000 mired (100,000 to 1,000 K) as\n\
          //! 99 cubic pieces of 10 mired: on piece i, at mired 10 + 10 (i + t) with t in [0, 1],\n\
          //! u = u[0] + u[1] t + u[2] t² + u[3] t³, and v likewise. Each piece is the cubic Hermite\n\
          //! interpolant of the exact locus (Planck's law against the CIE 1931 2° colour-matching\n\
          //! functions, c₂ = 1.4388e-2 m·K, in f64) and its derivative at the piece's ends; its\n\
          //! distance from the exact locus is at most 1.2e-8 in (u, v).\n\n\
          use super::LocusPiece;\n\n\
          /// The mired at the start of the first piece.\n";
    let _ = writeln!(s, "pub(super) const FIRST_MIRED: f32 = {FIRST_MIRED:?};");
    s += "/// Mired per piece.\n";
    let _ = writeln!(s, "pub(super) const STEP_MIRED: f32 = {STEP_MIRED:?};");
    s += "/// The pieces, from 10 mired up.\n#[rustfmt::skip]\n";
    let _ = writeln!(s, "pub(super) const PIECES: [LocusPiece; {PIECES}] = [");
    #[allow(clippy::cast_precision_loss)] // i ≤ 99
    let knot = |i: usize| locus(FIRST_MIRED + STEP_MIRED * i as f64);
    let floats = |c: [f64; 4]| {
        #[allow(clippy::cast_possible_truncation)] // rounded to the table's f32
        c.map(|x| format!("{:?}", x as f32)).join(", ")
    };
    for i in 0..PIECES {
        let (a, b) = (knot(i), knot(i + 1));
        let u = hermite(a.u, b.u, a.du * STEP_MIRED, b.du * STEP_MIRED);
        let v = hermite(a.v, b.v, a.dv * STEP_MIRED, b.dv * STEP_MIRED);
        let _ = writeln!(
            s,
            "    LocusPiece {{ u: [{}], v: [{}] }},",
            floats(u),
            floats(v)
        );
    }
    s += "];\n";
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn derivative_is_the_slope() {
        for mired in [12.0, 100.0, 333.0, 990.0] {
            let (a, b) = (locus(mired - 1e-4), locus(mired + 1e-4));
            let p = locus(mired);
            // Central differences: truncation and rounding errors below 1e-10 (|L′| ~ 3e-4).
            let (eu, ev) = ((b.u - a.u) / 2e-4 - p.du, (b.v - a.v) / 2e-4 - p.dv);
            assert!(
                eu.abs() < 1e-10 && ev.abs() < 1e-10,
                "{mired}: {eu:e} {ev:e}"
            );
        }
    }

    #[test]
    fn illuminant_a_is_on_the_locus() {
        // CIE illuminant A is the Planckian radiator at 2856 K (c₂ = 1.4388e-2 m·K); its
        // published chromaticity is (0.44757, 0.40745) (CIE 015:2018 Table 1).
        let (t, duv) = exact_cct_duv(0.44757, 0.40745).expect("valid");
        assert!((t - 2856.0).abs() < 1.0 && duv.abs() < 2e-5, "{t} {duv}");
    }
}
