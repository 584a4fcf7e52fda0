//! The reconstruction error of seed 001, §3.2 (eqs. 2-3).
//!
//! For one sky, with `c_lm` the projection of the model and `c^rec_lm` the reconstruction from
//! the polynomials (unfiltered, sun at azimuth 0), over the coefficients of the first `N` bands:
//!
//! ```text
//! E_max(θ, τ)  = 1 / L_min · Σ_lm |c^rec_lm − c_lm|          (eq. 2)
//! E_mean(θ, τ) = 1 / L_min · √(Σ_lm (c^rec_lm − c_lm)²)      (eq. 3)
//! ```
//!
//! per linear sRGB channel, the value reported being the largest over the three (the paper's
//! Fig. 3 covers "all color channels"). `L_min`, "the minimum intensity of the original data",
//! is the sky's smallest **luminance** over the upper hemisphere
//! ([`super::projection::minimum_luminance`]), the same for the three channels: a channel's own
//! minimum is no intensity (linear sRGB channels of a sunset sky go negative, out of gamut,
//! and near zero the measure would blow up without meaning), whereas linear sRGB on the cd/m²
//! scale puts every channel on the luminance's scale (white (1, 1, 1) has luminance 1).
//! All `N²` coefficients count, the `m < 0` ones too (the reconstruction has them 0; the
//! projection has them at quadrature noise for a symmetric sky).

use super::projection::{BANDS, Coefficients};

/// `E_max` and `E_mean` (eqs. 2-3) for `N = 1..=7` bands (index `N − 1`), each the largest over
/// the three channels.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct BandErrors {
    /// Eq. 2 per band count.
    pub max: [f64; BANDS],
    /// Eq. 3 per band count.
    pub mean: [f64; BANDS],
}

/// Eqs. 2-3 between `reference` and `reconstructed`, relative to `l_min`.
#[must_use]
pub fn band_errors(
    reference: &Coefficients,
    reconstructed: &Coefficients,
    l_min: f64,
) -> BandErrors {
    let mut out = BandErrors::default();
    for k in 0..3 {
        let (mut abs, mut sq) = (0.0, 0.0);
        for n in 1..=BANDS {
            for i in (n - 1) * (n - 1)..n * n {
                let d = reconstructed[i][k] - reference[i][k];
                abs += d.abs();
                sq += d * d;
            }
            let scale = l_min;
            out.max[n - 1] = out.max[n - 1].max(abs / scale);
            out.mean[n - 1] = out.mean[n - 1].max(sq.sqrt() / scale);
        }
    }
    out
}

/// The worst case of each band count over many skies, with where it occurred.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct WorstCase {
    /// The largest eq. 2 per band count, and its (sun zenith in radians, turbidity).
    pub max: [(f64, (f64, f64)); BANDS],
    /// The largest eq. 3 per band count, and its (sun zenith in radians, turbidity).
    pub mean: [(f64, (f64, f64)); BANDS],
}

impl WorstCase {
    /// Takes the errors of the sky at `at` into account.
    pub fn update(&mut self, e: &BandErrors, at: (f64, f64)) {
        for n in 0..BANDS {
            if e.max[n].is_nan() || e.max[n] > self.max[n].0 {
                self.max[n] = (e.max[n], at);
            }
            if e.mean[n].is_nan() || e.mean[n] > self.mean[n].0 {
                self.mean[n] = (e.mean[n], at);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn errors_follow_eqs_2_and_3() {
        let reference = [[1.0; 3]; 49];
        let mut rec = reference;
        rec[0][1] += 0.3; // band 0, green
        rec[2][1] -= 0.4; // band 1, green
        rec[20][0] += 1.0; // band 4, red
        let e = band_errors(&reference, &rec, 0.5);
        assert!((e.max[0] - 0.6).abs() < 1e-12); // green: 0.3 / 0.5
        assert!((e.max[1] - 1.4).abs() < 1e-12); // green: 0.7 / 0.5
        assert!((e.mean[1] - 1.0).abs() < 1e-12); // green: 0.5 / 0.5
        assert!((e.max[4] - 2.0).abs() < 1e-12); // red: 1.0 / 0.5
        assert!((e.mean[6] - 2.0).abs() < 1e-12);
    }
}
