//! Suppression of the ringing below the horizon (seed 001, §3.3, eq. 5).
//!
//! A sky is defined on the upper hemisphere and zero below; its finite SH expansion overshoots
//! and rings across that jump (the Gibbs phenomenon). The jump does not depend on the azimuth,
//! so only the zonal coefficients are filtered:
//!
//! ```text
//! c'_l0 = c_l0 · sinc(π l / N)     (eq. 5)
//! ```
//!
//! with `N` the number of bands used. **Reading of eq. 5:** `sinc(x) = sin(x) / x` (the
//! unnormalised sinc), so the factor is Lanczos' σ-factor `sin(πl/N) / (πl/N)`: 1 for l = 0,
//! decreasing to `sin(π/N) / (π/N) > 0` for the last band `l = N − 1`. This is the σ-factor of a
//! box filter of width `2π / N` in θ, which is what the paper states eq. 5 is equivalent to;
//! the normalised sinc, `sin(π x) / (π x)` with `x = πl/N`, would turn negative for
//! `l > N/π` and is not a box filter's.

use glam::Vec3;

use super::basis::{MAX_BANDS, MAX_COEFFICIENTS, index};

/// `sin(πl/N) / (πl/N)` for `N = 1..=7` (row `N − 1`) and `l < N` (0 beyond): f32 roundings of
/// the f64 values (checked by a test).
#[rustfmt::skip]
#[allow(clippy::unreadable_literal, clippy::excessive_precision, clippy::approx_constant)]
const LANCZOS: [[f32; MAX_BANDS]; MAX_BANDS] = [
    [1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [1.0, 0.6366197723675814, 0.0, 0.0, 0.0, 0.0, 0.0],
    [1.0, 0.8269933431326881, 0.4134966715663441, 0.0, 0.0, 0.0, 0.0],
    [1.0, 0.9003163161571061, 0.6366197723675814, 0.3001054387190354, 0.0, 0.0, 0.0],
    [1.0, 0.935489283788639, 0.756826728640657, 0.5045511524271047, 0.23387232094715982, 0.0, 0.0],
    [1.0, 0.954929658551372, 0.8269933431326881, 0.6366197723675814, 0.4134966715663441, 0.19098593171027436, 0.0],
    [1.0, 0.9667663853085522, 0.8710264156975602, 0.7241014497826596, 0.5430760873369946, 0.3484105662790241, 0.16112773088475874],
];

/// The factor eq. 5 applies to `c_l0` when `bands` bands are used (1 for `l = 0`; 0 for
/// `l ≥ bands` or `bands` outside `1..=7`).
///
/// ```
/// use sky_core::sh::filter::zonal_factor;
/// assert_eq!(zonal_factor(0, 7), 1.0);
/// let f = zonal_factor(3, 4); // sin(3π/4) / (3π/4)
/// assert!((f - 0.300_105_4).abs() < 1e-6);
/// ```
#[inline]
#[must_use]
pub fn zonal_factor(l: usize, bands: usize) -> f32 {
    if bands == 0 || bands > MAX_BANDS || l >= MAX_BANDS {
        return 0.0;
    }
    LANCZOS[bands - 1][l]
}

/// Applies eq. 5 to the zonal coefficients of the first `bands` bands of `c`, in place.
#[inline]
pub fn apply(c: &mut [Vec3; MAX_COEFFICIENTS], bands: usize) {
    for l in 0..bands.min(MAX_BANDS) {
        c[index(l, 0)] *= zonal_factor(l, bands);
    }
}

#[cfg(test)]
#[allow(clippy::needless_range_loop, clippy::cast_precision_loss)] // index arithmetic
mod tests {
    use super::*;

    #[test]
    fn factors_match_eq_5() {
        for n in 1..=MAX_BANDS {
            for l in 0..MAX_BANDS {
                let want = if l >= n {
                    0.0
                } else if l == 0 {
                    1.0
                } else {
                    let x = core::f64::consts::PI * l as f64 / n as f64;
                    libm::sin(x) / x
                };
                assert_eq!(zonal_factor(l, n), want as f32, "l = {l}, N = {n}");
            }
        }
        assert_eq!(zonal_factor(0, 0), 0.0);
        assert_eq!(zonal_factor(0, 8), 0.0);
    }
}
