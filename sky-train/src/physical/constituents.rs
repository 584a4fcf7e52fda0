//! The constituents of the clear atmosphere: the wavelength grid, the planet's shell, air
//! (Rayleigh scattering, US Standard Atmosphere 1976 density), ozone (absorption) and aerosol
//! (extinction, single-scattering albedo, Henyey-Greenstein phase), each with its source.
//!
//! Units: metres, m², m⁻³; wavelengths in nm (µm where the formula is written in µm).

use std::f64::consts::PI;

/// The number of wavelength bins: 10 nm bins [360, 370), ..., [820, 830) nm.
pub const N_WAVELENGTHS: usize = 47;
/// The first bin's lower edge, nm.
pub const FIRST_EDGE_NM: f64 = 360.0;
/// The width of a bin, nm.
pub const BIN_NM: f64 = 10.0;

/// One value per wavelength bin.
pub type Spectrum = [f64; N_WAVELENGTHS];

/// The centre of bin `i` in nm (365, 375, ..., 825).
#[must_use]
#[allow(clippy::cast_precision_loss)] // i < 47
pub fn wavelength_nm(i: usize) -> f64 {
    FIRST_EDGE_NM + BIN_NM * (i as f64 + 0.5)
}

/// The bin centres, nm.
#[must_use]
pub fn wavelengths_nm() -> Spectrum {
    std::array::from_fn(wavelength_nm)
}

/// Mean Earth radius, m (IUGG mean radius R1 = 6,371,008.8 m, rounded).
pub const EARTH_RADIUS_M: f64 = 6_371_000.0;
/// Height of the top of the modelled atmosphere, m. The US Standard Atmosphere's density at
/// 100 km is 4.6·10⁻⁷ of sea level's; what lies above scatters nothing that reaches the ground
/// down to a sun 18° below the horizon at the precision of this model.
pub const TOP_ALTITUDE_M: f64 = 100_000.0;
/// Radius of the top of the atmosphere, m.
pub const TOP_RADIUS_M: f64 = EARTH_RADIUS_M + TOP_ALTITUDE_M;

/// Boltzmann's constant, J/K (SI 2019, exact).
pub const BOLTZMANN: f64 = 1.380_649e-23;
/// One Dobson unit in molecules per m² (2.687·10²⁰; WMO).
pub const DOBSON_UNIT: f64 = 2.687e20;
/// CO₂ mixing ratio used in the Rayleigh cross-section, ppm (Bodhaine et al. 1999's 360 ppm).
pub const CO2_PPM: f64 = 360.0;

/// Refractive index of dry air minus one at 288.15 K, 1013.25 hPa, for `co2_ppm` of CO₂:
/// Peck & Reeder 1972 for 300 ppm (Bodhaine et al. 1999, eq. 18), scaled to the CO₂ content by
/// Edlén's factor 1 + 0.54 (C − 0.0003) (Bodhaine et al. 1999, eq. 19). `lambda_um` in µm.
#[must_use]
pub fn air_refractivity(lambda_um: f64, co2_ppm: f64) -> f64 {
    let s2 = 1.0 / (lambda_um * lambda_um);
    let n300 = (8060.51 + 2_480_990.0 / (132.274 - s2) + 17_455.7 / (39.329_57 - s2)) * 1e-8;
    n300 * (1.0 + 0.54 * (co2_ppm * 1e-6 - 0.0003))
}

/// The King correction factor of air, F_air (Bodhaine et al. 1999, eqs. 22-23: N₂ and O₂ after
/// Bates 1984, Ar 1.00, CO₂ 1.15, weighted by volume). `lambda_um` in µm.
#[must_use]
pub fn king_factor(lambda_um: f64, co2_ppm: f64) -> f64 {
    let s2 = 1.0 / (lambda_um * lambda_um);
    let f_n2 = 1.034 + 3.17e-4 * s2;
    let f_o2 = 1.096 + 1.385e-3 * s2 + 1.448e-4 * s2 * s2;
    let co2 = co2_ppm * 1e-4; // percent by volume
    (78.084 * f_n2 + 20.946 * f_o2 + 0.934 * 1.00 + co2 * 1.15) / (78.084 + 20.946 + 0.934 + co2)
}

/// Molecular number density of the standard air of [`air_refractivity`] (288.15 K,
/// 1013.25 hPa), m⁻³ (Bodhaine et al. 1999: 2.546899·10¹⁹ cm⁻³).
pub const STANDARD_AIR_DENSITY: f64 = 2.546_899e25;

/// Rayleigh scattering cross-section per air molecule, m² (Bodhaine et al. 1999, eq. 2:
/// σ = 24π³ (n² − 1)² / (λ⁴ N_s² (n² + 2)²) · F_air). `lambda_um` in µm.
#[must_use]
pub fn rayleigh_cross_section(lambda_um: f64, co2_ppm: f64) -> f64 {
    let n = 1.0 + air_refractivity(lambda_um, co2_ppm);
    let n2 = n * n;
    let lambda_m = lambda_um * 1e-6;
    let l4 = lambda_m.powi(4);
    24.0 * PI.powi(3) * (n2 - 1.0).powi(2)
        / (l4 * STANDARD_AIR_DENSITY * STANDARD_AIR_DENSITY * (n2 + 2.0).powi(2))
        * king_factor(lambda_um, co2_ppm)
}

/// The depolarisation ratio ρ of air from its King factor, F = (6 + 3ρ) / (6 − 7ρ).
#[must_use]
pub fn depolarisation(king: f64) -> f64 {
    6.0 * (king - 1.0) / (3.0 + 7.0 * king)
}

/// Chandrasekhar's Rayleigh phase function with depolarisation ρ, per steradian, as its two
/// terms (a, b) of P(θ) = a + b cos²θ: with γ = ρ / (2 − ρ),
/// P = 3 / (16π (1 + 2γ)) · ((1 + 3γ) + (1 − γ) cos²θ) (Chandrasekhar 1950, as in Bodhaine et al.
/// 1999 §2); ∫ P dΩ = 1.
#[must_use]
pub fn rayleigh_phase_terms(rho: f64) -> (f64, f64) {
    let gamma = rho / (2.0 - rho);
    let k = 3.0 / (16.0 * PI * (1.0 + 2.0 * gamma));
    (k * (1.0 + 3.0 * gamma), k * (1.0 - gamma))
}

/// The Henyey-Greenstein phase function for asymmetry `g` at scattering-angle cosine `nu`, per
/// steradian: (1 − g²) / (4π (1 + g² − 2gν)^{3/2}); ∫ P dΩ = 1.
#[must_use]
#[inline]
pub fn henyey_greenstein(g: f64, nu: f64) -> f64 {
    let d = (1.0 + g * g - 2.0 * g * nu).max(1e-12);
    (1.0 - g * g) / (4.0 * PI * d * d.sqrt())
}

/// Geopotential base heights (km) and temperature lapse rates (K/km) of the US Standard
/// Atmosphere 1976's seven layers up to 84.852 km' (NOAA/NASA/USAF, 1976, Table 4).
const US76_LAYERS: [(f64, f64); 7] = [
    (0.0, -6.5),
    (11.0, 0.0),
    (20.0, 1.0),
    (32.0, 2.8),
    (47.0, 0.0),
    (51.0, -2.8),
    (71.0, -2.0),
];
/// g₀ M₀ / R* of the US Standard Atmosphere 1976, K/km (9.80665 · 28.9644 / 8314.32 · 1000).
const US76_GMR: f64 = 34.163_195;
/// r₀ of the geopotential-height conversion, km (US Standard Atmosphere 1976).
const US76_R0_KM: f64 = 6356.766;

/// Top of the seventh layer, km' (geopotential).
const US76_TOP_KM: f64 = 84.852;

/// Temperature (K) and pressure (Pa) of the US Standard Atmosphere 1976 at geometric altitude
/// `z_m` (−1 to 106 km). Below 86 km (84.852 km geopotential) the standard's seven layers, the
/// first continued below sea level (the standard's own convention down to −5 km); above, the
/// temperature there (186.87 K) continued isothermally, which reproduces the standard's 100 km
/// density within 3 %. Altitudes below −1 km are treated as −1 km.
#[must_use]
pub fn us76(z_m: f64) -> (f64, f64) {
    let z = (z_m * 1e-3).max(-1.0);
    let h = US76_R0_KM * z / (US76_R0_KM + z); // geopotential km
    let (mut t, mut p) = (288.15, 101_325.0);
    for (i, &(base, lapse)) in US76_LAYERS.iter().enumerate() {
        let top = US76_LAYERS.get(i + 1).map_or(US76_TOP_KM, |l| l.0);
        let dh = h.min(top) - base;
        if dh <= 0.0 && i > 0 {
            break;
        }
        if lapse == 0.0 {
            p *= (-US76_GMR * dh / t).exp();
        } else {
            let t1 = t + lapse * dh;
            p *= (t / t1).powf(US76_GMR / lapse);
            t = t1;
        }
    }
    if h > US76_TOP_KM {
        p *= (-US76_GMR * (h - US76_TOP_KM) / t).exp();
    }
    (t, p)
}

/// Air molecule number density of the US Standard Atmosphere 1976 at `z_m`, m⁻³ (n = P / kT).
#[must_use]
pub fn air_number_density(z_m: f64) -> f64 {
    let (t, p) = us76(z_m);
    p / (BOLTZMANN * t)
}

/// Ozone cross-sections at 233 K, m², per 10 nm bin from 360 nm: Serdyuchenko et al. 2014 and
/// Gorshelev et al. 2014 (IUP Bremen, "o3spectra2011"), averaged over each bin
/// [360 + 10i, 370 + 10i) nm, as tabulated by Bruneton 2017 (precomputed_atmospheric_scattering,
/// atmosphere/demo/demo.cc, `kOzoneCrossSection`, whose bin i is [360 + 10i, 370 + 10i)).
/// The Huggins band's tail below 380 nm and the Chappuis band (peak near 600 nm).
pub const OZONE_CROSS_SECTION: Spectrum = [
    1.18e-27, 2.182e-28, 2.818e-28, 6.636e-28, 1.527e-27, 2.763e-27, 5.52e-27, 8.451e-27,
    1.582e-26, 2.316e-26, 3.669e-26, 4.924e-26, 7.752e-26, 9.016e-26, 1.48e-25, 1.602e-25,
    2.139e-25, 2.755e-25, 3.091e-25, 3.5e-25, 4.266e-25, 4.672e-25, 4.398e-25, 4.701e-25,
    5.019e-25, 4.305e-25, 3.74e-25, 3.215e-25, 2.662e-25, 2.238e-25, 1.852e-25, 1.473e-25,
    1.209e-25, 9.423e-26, 7.455e-26, 6.566e-26, 5.105e-26, 4.15e-26, 4.228e-26, 3.237e-26,
    2.451e-26, 2.801e-26, 2.534e-26, 1.624e-26, 1.465e-26, 2.078e-26, 1.383e-26,
];

/// The ozone layer's shape: 0 below 10 km, rising linearly to 1 at 25 km, falling linearly to 0
/// at 40 km (the layer of Bruneton 2017's demo, after a textbook mid-latitude profile; its
/// integral is 15 km, so a column of D Dobson units has a peak density of D · DU / 15 km).
#[must_use]
#[inline]
pub fn ozone_shape(z_m: f64) -> f64 {
    let z = z_m * 1e-3;
    if z <= 10.0 || z >= 40.0 {
        0.0
    } else if z <= 25.0 {
        (z - 10.0) / 15.0
    } else {
        (40.0 - z) / 15.0
    }
}

/// The integral of [`ozone_shape`] over altitude, m.
pub const OZONE_SHAPE_INTEGRAL_M: f64 = 15_000.0;

/// Per-wavelength coefficients of the three constituents: what multiplies each column density
/// (see [`crate::physical::transport::Columns`]) to give an optical depth, and the scattering
/// part of each.
#[derive(Debug, Clone, PartialEq)]
pub struct Coefficients {
    /// Rayleigh cross-section per molecule, m² (Bodhaine et al. 1999).
    pub rayleigh: Spectrum,
    /// Aerosol extinction per metre of sea-level-equivalent path, m⁻¹: τ_a(λ) / H_a.
    pub aerosol_extinction: Spectrum,
    /// Aerosol scattering per metre of sea-level-equivalent path, m⁻¹: ϖ τ_a(λ) / H_a.
    pub aerosol_scattering: Spectrum,
    /// Ozone cross-section per molecule, m².
    pub ozone: Spectrum,
    /// Rayleigh phase-function terms (a, b) per wavelength, from each bin's depolarisation.
    pub rayleigh_phase: [(f64, f64); N_WAVELENGTHS],
}

/// The Rayleigh cross-section of every bin: the bin average of σ(λ) (a 10-point midpoint rule
/// over the bin, which matters at the λ⁻⁴ blue end).
#[must_use]
pub fn rayleigh_cross_sections() -> Spectrum {
    std::array::from_fn(|i| {
        let lo = FIRST_EDGE_NM + BIN_NM * f64::from(u32::try_from(i).unwrap_or(0));
        (0..10)
            .map(|k| rayleigh_cross_section((lo + f64::from(k) + 0.5) * 1e-3, CO2_PPM))
            .sum::<f64>()
            / 10.0
    })
}

/// Rayleigh phase terms of every bin, at the bin centre's King factor.
#[must_use]
pub fn rayleigh_phases() -> [(f64, f64); N_WAVELENGTHS] {
    std::array::from_fn(|i| {
        rayleigh_phase_terms(depolarisation(king_factor(
            wavelength_nm(i) * 1e-3,
            CO2_PPM,
        )))
    })
}

/// The Rayleigh phase-function terms at 550 nm, used for the multiple-scattering kernels
/// (whose wavelength dependence, 0.4 % in the cos² term over 360-830 nm, is below their
/// quadrature error).
#[must_use]
pub fn rayleigh_phase_550() -> (f64, f64) {
    rayleigh_phase_terms(depolarisation(king_factor(0.55, CO2_PPM)))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Bodhaine et al. 1999, eq. 29: their fit to the full calculation for 360 ppm CO₂,
    /// σ(10⁻²⁸ cm²) = (1.0455996 − 341.29061 λ⁻² − 0.90230850 λ²) / (1 + 0.0027059889 λ⁻² −
    /// 85.968563 λ²), accurate to 0.01 % over 250-850 nm by their statement.
    #[test]
    fn rayleigh_cross_section_matches_bodhaine_fit() {
        for nm in [360.0, 400.0, 450.0, 500.0, 550.0, 600.0, 700.0, 830.0] {
            let l = nm * 1e-3_f64;
            let (s2, l2) = (1.0 / (l * l), l * l);
            let fit = (1.045_599_6 - 341.290_61 * s2 - 0.902_308_50 * l2)
                / (1.0 + 0.002_705_988_9 * s2 - 85.968_563 * l2)
                * 1e-28
                * 1e-4;
            let ours = rayleigh_cross_section(l, CO2_PPM);
            assert!(
                (ours / fit - 1.0).abs() < 2e-3,
                "{nm} nm: {ours:e} vs Bodhaine's fit {fit:e}"
            );
        }
    }

    /// Bodhaine et al. 1999, Table 3 / §5: the Rayleigh optical depth of the US Standard
    /// Atmosphere at sea level (1013.25 hPa) is 0.0973 at 550 nm (their 0.09726 for 360 ppm).
    #[test]
    fn rayleigh_optical_depth_at_550() {
        let n = 20_000;
        let dz = TOP_ALTITUDE_M / f64::from(n);
        let column: f64 = (0..n)
            .map(|k| air_number_density((f64::from(k) + 0.5) * dz) * dz)
            .sum();
        let tau = column * rayleigh_cross_section(0.55, CO2_PPM);
        assert!((tau - 0.0973).abs() < 0.001, "tau = {tau}");
    }

    /// The standard's published values (US Standard Atmosphere 1976, Table I, at geopotential
    /// layer bases): 11 km' 216.65 K, 22,632 Pa; 20 km' 5,474.9 Pa; 32 km' 228.65 K, 868.02 Pa;
    /// 47 km' 270.65 K, 110.91 Pa; 51 km' 66.939 Pa; 71 km' 214.65 K, 3.9564 Pa.
    #[test]
    fn us76_layer_bases() {
        for (hgp, t_ref, p_ref) in [
            (11.0, 216.65, 22_632.1),
            (20.0, 216.65, 5_474.89),
            (32.0, 228.65, 868.019),
            (47.0, 270.65, 110.906),
            (51.0, 270.65, 66.9389),
            (71.0, 214.65, 3.956_42),
        ] {
            let z = hgp * US76_R0_KM / (US76_R0_KM - hgp) * 1e3;
            let (t, p) = us76(z);
            assert!((t - t_ref).abs() < 0.01, "{hgp} km': T {t}");
            assert!((p / p_ref - 1.0).abs() < 1e-3, "{hgp} km': P {p}");
        }
        // Sea level: 2.5469e25 m⁻³ (the standard's number density, Table I).
        assert!((air_number_density(0.0) / 2.5470e25 - 1.0).abs() < 1e-3);
    }

    #[test]
    fn phase_functions_are_normalised() {
        let (a, b) = rayleigh_phase_terms(0.0279);
        let hg = |nu| henyey_greenstein(0.7, nu);
        let n = 20_000;
        let (mut pr, mut pa) = (0.0, 0.0);
        for k in 0..n {
            let nu = -1.0 + 2.0 * (f64::from(k) + 0.5) / f64::from(n);
            pr += (a + b * nu * nu) * 2.0 * PI * 2.0 / f64::from(n);
            pa += hg(nu) * 2.0 * PI * 2.0 / f64::from(n);
        }
        assert!((pr - 1.0).abs() < 1e-6, "{pr}");
        assert!((pa - 1.0).abs() < 1e-4, "{pa}");
    }

    #[test]
    fn ozone_shape_integral() {
        let n = 100_000;
        let dz = 50_000.0 / f64::from(n);
        let s: f64 = (0..n)
            .map(|k| ozone_shape((f64::from(k) + 0.5) * dz) * dz)
            .sum();
        assert!((s / OZONE_SHAPE_INTEGRAL_M - 1.0).abs() < 1e-6);
    }
}
