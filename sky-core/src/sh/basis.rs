//! The real spherical-harmonics basis Y_lm, its indexing, and the clamped-cosine convolution
//! constants Â_l.
//!
//! **Definition.** For band `l ≥ 0` and order `-l ≤ m ≤ l`, with a unit direction
//! `(x, y, z) = (sin θ cos φ, sin θ sin φ, cos θ)` in sky-core's frame (+z up, azimuth φ from +x
//! towards +y):
//!
//! ```text
//! Y_l0  =      K_l0 P_l^0(cos θ)
//! Y_lm  = √2 · K_lm P_l^m(cos θ) cos(m φ)     m > 0
//! Y_l-m = √2 · K_lm P_l^m(cos θ) sin(m φ)     m > 0
//! K_lm  = √((2l + 1) / (4π) · (l − m)! / (l + m)!)
//! ```
//!
//! where `P_l^m` is the associated Legendre function **without** the Condon-Shortley phase
//! (−1)^m, so that `Y_11 ∝ +x`, `Y_1-1 ∝ +y`, `Y_10 ∝ +z`. The basis is orthonormal over the
//! sphere: `∫ Y_lm Y_l'm' dω = δ_ll' δ_mm'`. Coefficient `(l, m)` is stored at index
//! `l² + l + m` ([`index`]), so the first `N²` entries hold the first `N` bands.
//!
//! The functions are evaluated without trigonometry: `sin^m θ cos mφ` and `sin^m θ sin mφ` are the
//! real and imaginary parts of `(x + i y)^m`, and `P_l^m / sin^m θ` follows the usual three-term
//! recurrence in `z`.

use glam::Vec3;

use crate::math;

/// The most bands the crate's tables and functions handle (l = 0..=6).
pub const MAX_BANDS: usize = 7;
/// Coefficients of [`MAX_BANDS`] bands: `MAX_BANDS²`.
pub const MAX_COEFFICIENTS: usize = MAX_BANDS * MAX_BANDS;

/// The index of coefficient `(l, m)`, `|m| ≤ l`: `l² + l + m`.
///
/// ```
/// use sky_core::sh::basis::index;
/// assert_eq!(index(0, 0), 0);
/// assert_eq!(index(1, -1), 1);
/// assert_eq!(index(6, 6), 48);
/// ```
#[inline]
#[must_use]
#[allow(clippy::cast_sign_loss, clippy::cast_possible_wrap)] // l² + l + m ≥ 0 for |m| ≤ l
pub const fn index(l: usize, m: isize) -> usize {
    ((l * l + l) as isize + m) as usize
}

/// `(2m − 1)!!`: `P_m^m / sin^m θ` without the Condon-Shortley phase.
pub const DOUBLE_FACTORIAL: [f32; MAX_BANDS] = [1.0, 1.0, 3.0, 15.0, 105.0, 945.0, 10395.0];

/// `[(2l − 1) / (l − m), (l + m − 1) / (l − m)]` for `l > m`: the recurrence
/// `P_l^m = ((2l − 1) z P_{l−1}^m − (l + m − 1) P_{l−2}^m) / (l − m)` without a division.
pub const RECURRENCE: [[[f32; 2]; MAX_BANDS]; MAX_BANDS] = {
    let mut r = [[[0.0; 2]; MAX_BANDS]; MAX_BANDS];
    let mut l = 1;
    while l < MAX_BANDS {
        let mut m = 0;
        while m < l {
            #[allow(clippy::cast_precision_loss)] // l, m ≤ 6
            let (a, b, d) = ((2 * l - 1) as f32, (l + m - 1) as f32, (l - m) as f32);
            r[l][m] = [a / d, b / d];
            m += 1;
        }
        l += 1;
    }
    r
};

/// The normalisation `K_lm` (times √2 for m > 0), indexed `[l][m]` for `0 ≤ m ≤ l`; f32 roundings
/// of the f64 values of the formula in the module docs (checked by a test).
#[rustfmt::skip]
#[allow(clippy::unreadable_literal, clippy::excessive_precision)]
pub const NORMALISATION: [[f32; MAX_BANDS]; MAX_BANDS] = [
    [0.28209479177387814, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [0.4886025119029199, 0.48860251190292, 0.0, 0.0, 0.0, 0.0, 0.0],
    [0.6307831305050401, 0.36418281019735976, 0.18209140509867988, 0.0, 0.0, 0.0, 0.0],
    [0.7463526651802308, 0.3046971996429772, 0.09635371475468515, 0.03933623932844291, 0.0, 0.0, 0.0],
    [0.8462843753216345, 0.2676186174229157, 0.063078313050504, 0.016858388283618388, 0.005960340337611203, 0.0, 0.0],
    [0.9356025796273888, 0.2415715473043717, 0.045652731285460234, 0.009318824751147628, 0.002196468058075176, 0.0006945841871324552, 0.0],
    [1.0171072362820548, 0.22195099524523101, 0.03509353369580661, 0.005848922282634435, 0.0010678622237644956, 0.00022766899107568562, 6.57223766418388e-05],
];

/// The real SH basis `Y_lm(dir)` for every `(l, m)` with `l < bands` (at [`index`]`(l, m)`);
/// entries of higher bands are 0. `bands` above [`MAX_BANDS`] counts as `MAX_BANDS`.
///
/// `dir` is normalised first; a zero or non-finite vector gives a finite, meaningless result.
///
/// ```
/// use sky_core::{geom, sh::basis};
/// let y = basis::evaluate(geom::direction(0.0, 0.0), 3); // the zenith
/// assert!((y[0] - 0.282_094_8).abs() < 1e-6);             // 1 / √(4π)
/// assert!((y[basis::index(1, 0)] - 0.488_602_5).abs() < 1e-6);
/// assert_eq!(y[basis::index(3, 0)], 0.0);                 // band 3 not requested
/// ```
#[inline]
#[must_use]
pub fn evaluate(dir: Vec3, bands: usize) -> [f32; MAX_COEFFICIENTS] {
    let dir = dir * math::rsqrt(dir.length_squared());
    // A vector too long or too short for f32's squares (or not finite) is not unit length
    // after that: each coordinate is clamped to [-1, 1] (NaN to -1), so that every basis value
    // stays finite whatever the input.
    let [x, y, z] = dir
        .to_array()
        .map(|c| math::at_most(math::at_least(c, -1.0), 1.0));
    let bands = bands.min(MAX_BANDS);
    let mut out = [0.0; MAX_COEFFICIENTS];
    // (x + i y)^m = sin^m θ (cos mφ + i sin mφ).
    let (mut re, mut im) = (1.0f32, 0.0f32);
    for m in 0..bands {
        if m > 0 {
            (re, im) = (x * re - y * im, x * im + y * re);
        }
        // q_l = P_l^m(z) / sin^m θ, by the recurrence in l.
        let mut q_prev = 0.0f32;
        let mut q = DOUBLE_FACTORIAL[m];
        for l in m..bands {
            if l > m {
                let [a, b] = RECURRENCE[l][m];
                (q_prev, q) = (q, a * z * q - b * q_prev);
            }
            let n = NORMALISATION[l][m] * q;
            #[allow(clippy::cast_possible_wrap)] // m ≤ 6
            let mi = m as isize;
            out[index(l, mi)] = n * re;
            if m > 0 {
                out[index(l, -mi)] = n * im;
            }
        }
    }
    out
}

/// The band `l` of every coefficient index (`0, 1, 1, 1, 2, …`).
pub(crate) const BAND_OF: [usize; MAX_COEFFICIENTS] = {
    let mut out = [0; MAX_COEFFICIENTS];
    let mut i = 0;
    while i < MAX_COEFFICIENTS {
        let mut l = 0;
        while (l + 1) * (l + 1) <= i {
            l += 1;
        }
        out[i] = l;
        i += 1;
    }
    out
};

/// Â_l: the SH coefficients of the clamped cosine `max(cos θ, 0)` scaled for convolution, after
/// Ramamoorthi and Hanrahan, "An Efficient Representation for Irradiance Environment Maps"
/// (SIGGRAPH 2001), eqs. 8-9: Â_0 = π, Â_1 = 2π/3, Â_l = 0 for odd l > 1, and for even l
/// Â_l = 2π (−1)^{l/2−1} / ((l + 2)(l − 1)) · l! / (2^l ((l/2)!)²), i.e. π/4, −π/24, π/64 for
/// l = 2, 4, 6. The irradiance for a normal `n` is `E(n) = Σ Â_l c_lm Y_lm(n)`.
#[allow(clippy::unreadable_literal)]
pub const CLAMPED_COSINE: [f32; MAX_BANDS] = [
    core::f32::consts::PI,
    2.0 * core::f32::consts::FRAC_PI_3,
    core::f32::consts::FRAC_PI_4,
    0.0,
    -core::f32::consts::PI / 24.0,
    0.0,
    core::f32::consts::PI / 64.0,
];

#[cfg(test)]
#[allow(clippy::needless_range_loop, clippy::cast_precision_loss)] // index arithmetic
mod tests {
    use super::*;

    fn factorial(n: usize) -> f64 {
        (1..=n).fold(1.0, |p, k| p * k as f64)
    }

    #[test]
    fn normalisation_matches_the_formula() {
        for l in 0..MAX_BANDS {
            for m in 0..=l {
                let k = libm::sqrt(
                    (2 * l + 1) as f64 / (4.0 * core::f64::consts::PI) * factorial(l - m)
                        / factorial(l + m),
                );
                let k = if m > 0 {
                    k * core::f64::consts::SQRT_2
                } else {
                    k
                };
                assert_eq!(NORMALISATION[l][m], k as f32, "K_{l}{m}");
            }
        }
    }

    #[test]
    fn low_bands_match_closed_forms() {
        // Closed forms of the orthonormal real SH (no Condon-Shortley phase).
        let d = Vec3::new(0.3, -0.5, 0.8).normalize();
        let (x, y, z) = (d.x, d.y, d.z);
        let pi = core::f32::consts::PI;
        let y_lm = evaluate(d, 3);
        let want = [
            0.5 / libm::sqrtf(pi),
            libm::sqrtf(3.0 / (4.0 * pi)) * y,
            libm::sqrtf(3.0 / (4.0 * pi)) * z,
            libm::sqrtf(3.0 / (4.0 * pi)) * x,
            0.5 * libm::sqrtf(15.0 / pi) * x * y,
            0.5 * libm::sqrtf(15.0 / pi) * y * z,
            0.25 * libm::sqrtf(5.0 / pi) * (3.0 * z * z - 1.0),
            0.5 * libm::sqrtf(15.0 / pi) * x * z,
            0.25 * libm::sqrtf(15.0 / pi) * (x * x - y * y),
        ];
        for (i, (g, w)) in y_lm.iter().zip(want).enumerate() {
            assert!((g - w).abs() < 1e-6, "Y[{i}] = {g}, want {w}");
        }
    }

    #[test]
    fn band_of_and_clamped_cosine() {
        assert_eq!(BAND_OF[0], 0);
        assert_eq!(BAND_OF[3], 1);
        assert_eq!(BAND_OF[4], 2);
        assert_eq!(BAND_OF[48], 6);
        // Â_l from the general formula of Ramamoorthi and Hanrahan's eq. 9.
        for l in (2..MAX_BANDS).step_by(2) {
            let sign = if (l / 2 - 1) % 2 == 0 { 1.0 } else { -1.0 };
            let h = factorial(l / 2);
            let a = 2.0 * core::f64::consts::PI * sign / (((l + 2) * (l - 1)) as f64)
                * factorial(l)
                / (libm::pow(2.0, l as f64) * h * h);
            assert!((f64::from(CLAMPED_COSINE[l]) - a).abs() < 1e-7, "l = {l}");
        }
    }
}
