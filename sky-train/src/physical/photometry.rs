//! From spectra to what eyes and clocks see: CIE 1931 XYZ (683 lm/W), chromaticity, CCT and Duv
//! (through sky-core's [`sky_core::cct`]) and melanopic equivalent daylight (D65) illuminance
//! (CIE S 026:2018).

use sky_core::cct::cmf::{CMF, FIRST_NM, STEP_NM};

use super::constituents::{BIN_NM, FIRST_EDGE_NM, N_WAVELENGTHS, Spectrum};
use super::spectra::MELANOPIC;

/// Maximum luminous efficacy of photopic vision, lm/W (CIE 015:2018; 683.002, rounded as the SI
/// definition of the candela has it at 540 THz).
pub const KM: f64 = 683.0;
/// Melanopic efficacy of luminous radiation of D65, W/lm (CIE S 026:2018: 1.3262 mW/lm).
pub const K_MEL_D65: f64 = 1.3262e-3;

/// The CIE 1931 2° colour-matching functions averaged over each 10 nm bin: the integral of the
/// 5 nm table's piecewise-linear interpolant over [λ, λ + 10) divided by 10 nm, i.e. weights
/// ¼, ½, ¼ on the rows at λ, λ + 5, λ + 10.
#[must_use]
pub fn cmf_bins() -> [[f64; 3]; N_WAVELENGTHS] {
    std::array::from_fn(|i| {
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let row = ((FIRST_EDGE_NM + BIN_NM * i as f64 - FIRST_NM) / STEP_NM) as usize;
        std::array::from_fn(|c| 0.25 * CMF[row][c] + 0.5 * CMF[row + 1][c] + 0.25 * CMF[row + 2][c])
    })
}

/// Weights that turn a spectrum per nm (radiance or irradiance, per bin) into the four
/// channels X, Y, Z (cd/m² or lux) and melanopic EDL / EDI (cd/m² or lux, D65-equivalent):
/// channel c = Σ_bins w_c(λ) S(λ).
#[must_use]
pub fn channel_weights() -> [Spectrum; 4] {
    let cmf = cmf_bins();
    std::array::from_fn(|c| {
        std::array::from_fn(|i| {
            if c < 3 {
                KM * cmf[i][c] * BIN_NM
            } else {
                MELANOPIC[i] * BIN_NM / K_MEL_D65
            }
        })
    })
}

/// X, Y, Z and melanopic D65-equivalent of a spectrum (W m⁻² nm⁻¹ → lux; W m⁻² sr⁻¹ nm⁻¹ →
/// cd/m²).
#[must_use]
pub fn channels(spectrum: &Spectrum) -> [f64; 4] {
    let w = channel_weights();
    std::array::from_fn(|c| w[c].iter().zip(spectrum).map(|(a, b)| a * b).sum())
}

/// Illuminance and colour of a light.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Colorimetry {
    /// CIE 1931 X, Y (lux or cd/m²), Z.
    pub xyz: [f64; 3],
    /// Chromaticity x, y (NaN when the light is black).
    pub xy: (f64, f64),
    /// CCT (K) and Duv where the chromaticity has a CCT in 1,000-100,000 K and |Duv| ≤ 0.05.
    pub cct_duv: Option<(f64, f64)>,
    /// Melanopic equivalent daylight (D65) illuminance or luminance (CIE S 026:2018).
    pub melanopic_edi: f64,
}

/// The |Duv| above which a CCT is not reported (ANSI C78.377, CIE 015:2018 §9.5).
pub const MAX_DUV: f64 = 0.05;

impl Colorimetry {
    /// The colorimetry of a spectrum per nm (irradiance or radiance).
    #[must_use]
    pub fn of(spectrum: &Spectrum) -> Self {
        Self::from_channels(channels(spectrum))
    }

    /// The colorimetry of channels X, Y, Z, melanopic.
    #[must_use]
    #[allow(clippy::cast_possible_truncation)]
    pub fn from_channels(c: [f64; 4]) -> Self {
        let sum = c[0] + c[1] + c[2];
        let xy = if sum > 0.0 {
            (c[0] / sum, c[1] / sum)
        } else {
            (f64::NAN, f64::NAN)
        };
        let cct_duv = sky_core::cct::cct_duv(xy.0 as f32, xy.1 as f32)
            .ok()
            .map(|t| (f64::from(t.kelvin), f64::from(t.duv)))
            .filter(|&(k, duv)| {
                duv.abs() <= MAX_DUV
                    && k > f64::from(sky_core::cct::MIN_CCT)
                    && k < f64::from(sky_core::cct::MAX_CCT)
            });
        Self {
            xyz: [c[0], c[1], c[2]],
            xy,
            cct_duv,
            melanopic_edi: c[3],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An equal-energy spectrum has chromaticity (1/3, 1/3) (CIE illuminant E), and 1 W m⁻² nm⁻¹
    /// of it gives 683 · ∫ȳ dλ = 683 · 106.857 lx (∫ȳ over 360-830 nm of the 1 nm table, CIE
    /// 018:2019).
    #[test]
    fn illuminant_e() {
        let c = Colorimetry::of(&[1.0; N_WAVELENGTHS]);
        assert!((c.xy.0 - 1.0 / 3.0).abs() < 2e-3, "{:?}", c.xy);
        assert!((c.xy.1 - 1.0 / 3.0).abs() < 2e-3, "{:?}", c.xy);
        assert!(
            (c.xyz[1] / (683.0 * 106.857) - 1.0).abs() < 3e-3,
            "{}",
            c.xyz[1]
        );
    }

    /// Planck's radiator at 6504 K has CCT 6504 K, Duv 0, through the bins.
    #[test]
    fn planckian_cct() {
        let s: Spectrum = std::array::from_fn(|i| {
            let l = super::super::constituents::wavelength_nm(i) * 1e-3;
            1.0 / (l.powi(5) * ((14_388.0 / (l * 6504.0)).exp() - 1.0))
        });
        let (k, duv) = Colorimetry::of(&s).cct_duv.expect("has a CCT");
        assert!((k - 6504.0).abs() < 40.0, "{k}");
        assert!(duv.abs() < 1e-3, "{duv}");
    }
}
