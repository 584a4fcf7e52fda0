//! The sun outside the atmosphere: its spectrum at 1 AU, its distance on a date, its disc.

use super::constituents::Spectrum;
use super::spectra::SOLAR_ETR;

/// The sun's angular radius, rad (0.2666°, the mean apparent semi-diameter at 1 AU: 959.6″).
pub const SUN_ANGULAR_RADIUS: f64 = 959.63 / 3600.0 * std::f64::consts::PI / 180.0;

/// Extraterrestrial solar spectral irradiance at 1 AU, W m⁻² nm⁻¹ per bin (ASTM G-173-03,
/// [`SOLAR_ETR`]).
#[must_use]
pub fn extraterrestrial() -> Spectrum {
    SOLAR_ETR
}

/// The eccentricity correction (r₀ / r)² of the extraterrestrial irradiance on day `day_of_year`
/// (1 = 1 January): Spencer 1971 ("Fourier series representation of the position of the sun",
/// Search 2(5), 172), E₀ = 1.000110 + 0.034221 cos Γ + 0.001280 sin Γ + 0.000719 cos 2Γ +
/// 0.000077 sin 2Γ with Γ = 2π (d − 1) / 365; within 0.01 % of the ephemeris.
#[must_use]
pub fn eccentricity_correction(day_of_year: u32) -> f64 {
    let g = 2.0 * std::f64::consts::PI * (f64::from(day_of_year.clamp(1, 366)) - 1.0) / 365.0;
    1.000_110
        + 0.034_221 * g.cos()
        + 0.001_280 * g.sin()
        + 0.000_719 * (2.0 * g).cos()
        + 0.000_077 * (2.0 * g).sin()
}

/// The day of the year (1-366) of a Gregorian date.
#[must_use]
pub fn day_of_year(year: i32, month: u32, day: u32) -> u32 {
    (1..month.clamp(1, 12))
        .map(|m| sky_core::solar::days_in_month(year, m))
        .sum::<u32>()
        + day
}

/// The fraction of the sun's disc above a horizon that lies `alpha` radians below the disc's
/// centre (negative: the centre is below it): the area of a circular segment,
/// (acos(−s) + s √(1 − s²)) / π with s = α / angular radius.
#[must_use]
#[inline]
pub fn disc_fraction_above(alpha: f64) -> f64 {
    let s = (alpha / SUN_ANGULAR_RADIUS).clamp(-1.0, 1.0);
    ((-s).acos() + s * (1.0 - s * s).sqrt()) / std::f64::consts::PI
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solar_spectrum_integral() {
        // The trapezoidal integral of ASTM G-173's ETR rows from 360 to 830 nm (pvlib 0.16.1's
        // ASTMG173.csv, computed with numpy): 734.776 W m⁻² (of 1347.9 over 280-4000 nm).
        let s: f64 = extraterrestrial().iter().sum::<f64>() * 10.0;
        assert!((s / 734.776 - 1.0).abs() < 1e-4, "{s}");
    }

    #[test]
    fn perihelion_and_aphelion() {
        // Perihelion early January (r = 0.9833 AU: (1/r)² = 1.0343), aphelion early July
        // (1.0167 AU: 0.9674).
        assert!((eccentricity_correction(3) - 1.0343).abs() < 0.001);
        assert!((eccentricity_correction(185) - 0.9674).abs() < 0.001);
        assert_eq!(day_of_year(2026, 3, 1), 60);
        assert_eq!(day_of_year(2024, 12, 31), 366);
    }

    #[test]
    fn disc_fraction() {
        assert!((disc_fraction_above(0.0) - 0.5).abs() < 1e-12);
        assert_eq!(disc_fraction_above(1.0), 1.0);
        assert_eq!(disc_fraction_above(-1.0), 0.0);
    }
}
