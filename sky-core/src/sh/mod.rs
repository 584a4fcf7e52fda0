//! Spherical-harmonics sky lighting from polynomial tables (seed 001: Habel, Mustata, Wimmer,
//! "Efficient Spherical Harmonics Lighting with the Preetham Skylight Model", Eurographics 2008).
//!
//! A sky's SH coefficients `c_lm` (real SH, [`basis`]) are stored as 2-D polynomials in sun
//! zenith θ and turbidity τ ([`polynomial`], eq. 1, in a Chebyshev basis), fitted offline by `sky-train fit-sh` to
//! the projection of the sky with the sun at azimuth 0. [`ShSky::new`] evaluates them for one sun
//! and atmosphere, filters the zonal terms against ringing ([`filter`], eq. 5) and turns them to
//! the sun's azimuth ([`rotation`], eq. 4); then [`ShSky::radiance`] and [`ShSky::irradiance`]
//! are cheap per direction.
//!
//! ```
//! use sky_core::{geom, sh::ShSky, Sun};
//! let sky = ShSky::new(Sun::new(1.0, 0.5)?, 3.0, 5)?; // 5 bands
//! let up = geom::direction(0.0, 0.0);
//! let e = sky.irradiance(up);                   // linear sRGB, lux scale
//! assert!(e.y > 1000.0);
//! let l = sky.radiance(geom::direction(0.8, 0.5)); // towards the sun's side
//! assert!(l.min_element() > 0.0);
//! # Ok::<(), sky_core::SkyError>(())
//! ```
//!
//! # Accuracy (Preetham tables: sun zenith 0-90°, turbidity 2.5-6)
//!
//! The reconstruction error of eqs. 2-3 (seed 001 §3.2), relative to the sky's smallest
//! luminance, largest over the linear sRGB channels, on skies off the fit grid: E_mean at most
//! 0.0015 % for 1 to 5 bands and 0.35 % for 7 (E_max 0.0051 % and 1.05 %); held by
//! `tests/tests/sh.rs` at the paper's bounds (0.005 % up to 5 bands, 1.5 % at 7). The
//! irradiance agrees with a brute-force cosine-weighted integral of the sky to 1 % from 5 bands
//! on (see [`ShSky::irradiance`]). The tables take 28 080 bytes for 7 bands
//! ([`PolynomialTable::bytes_for_bands`] for fewer; 62 076 as f32): a row of small
//! coefficients is stored as whole steps of 2⁻¹³ (bands 0-4) or 2⁻⁸ (bands 5-6) in `i16` or
//! `i8` ([`polynomial::CoefficientRows`]), which adds at most 0.0003 % to the E_mean of 1 to
//! 5 bands and 0.004 % to that of 7 (the rounding alone, measured by `sky-train fit-sh
//! --report`, `docs/sh_errors.md`).
//!
//! # Conventions
//!
//! Real SH as defined in [`basis`] (orthonormal, no Condon-Shortley phase, `Y_11 ∝ +x`,
//! `Y_1-1 ∝ +y`), in the crate's frame (+z up, azimuth from +x towards +y). Coefficients are
//! linear sRGB on the model's radiance scale (cd/m² for Preetham).

pub mod basis;
pub mod filter;
pub mod polynomial;
mod preetham_table;
pub mod rotation;

use glam::Vec3;

use crate::error::{SkyError, check_range};
use crate::geom::Sun;
use basis::{BAND_OF, CLAMPED_COSINE, MAX_BANDS, MAX_COEFFICIENTS};
pub use polynomial::PolynomialTable;
pub use preetham_table::PREETHAM;

/// The SH lighting of one sky: RGB coefficients for up to seven bands, evaluated from a
/// model's polynomial tables, filtered and rotated.
///
/// **Units**: [`radiance`](Self::radiance) is linear sRGB on the model's scale (cd/m² for the
/// Preetham sky; its luminance is [`color::luminance`](crate::color::luminance));
/// [`irradiance`](Self::irradiance) on the same scale times steradians (lux for Preetham).
/// **Non-negative, black below the horizon**: [`radiance`](Self::radiance) is the truncated
/// series clamped at zero (its ringing dips below zero, above the horizon too at 5 bands and
/// more without the filter), and zero below the horizon, as the Preetham sky it represents;
/// [`series`](Self::series) is the series itself, for studying the ringing.
#[derive(Debug, Clone, PartialEq)]
pub struct ShSky {
    bands: usize,
    /// `c_lm` per index (RGB), zero beyond `bands`.
    coefficients: [Vec3; MAX_COEFFICIENTS],
    /// `Â_l c_lm`, for the irradiance.
    irradiance: [Vec3; MAX_COEFFICIENTS],
}

impl ShSky {
    /// The SH lighting of the Preetham sky for `sun` and `turbidity` with `bands` bands
    /// (1 to 7), with the ringing filter of eq. 5 applied: reconstruction from [`PREETHAM`]
    /// (eq. 1, basis values shared across coefficients), filter (eq. 5), rotation to the sun's
    /// azimuth (eq. 4).
    ///
    /// # Errors
    /// [`SkyError::SunBelowHorizon`] for a sun zenith above π/2; [`SkyError::OutOfRange`] for a
    /// turbidity outside the fitted range ([`PREETHAM`]`.turbidity`) or `bands` outside 1..=7.
    ///
    /// ```
    /// use sky_core::{sh::ShSky, Sun};
    /// assert!(ShSky::new(Sun::new(0.3, 0.0)?, 4.0, 7).is_ok());
    /// assert!(ShSky::new(Sun::new(0.3, 0.0)?, 4.0, 8).is_err());
    /// assert!(ShSky::new(Sun::new(1.7, 0.0)?, 4.0, 3).is_err()); // sun below the horizon
    /// # Ok::<(), sky_core::SkyError>(())
    /// ```
    pub fn new(sun: Sun, turbidity: f32, bands: usize) -> Result<Self, SkyError> {
        Self::from_table(&PREETHAM, sun, turbidity, bands, true)
    }

    /// [`new`](Self::new) without the ringing filter: the plain reconstruction of the fitted
    /// coefficients, rotated. Its zonal coefficients are the polynomials' values, as the error
    /// measure of eqs. 2-3 compares them.
    ///
    /// # Errors
    /// As [`new`](Self::new).
    pub fn new_unfiltered(sun: Sun, turbidity: f32, bands: usize) -> Result<Self, SkyError> {
        Self::from_table(&PREETHAM, sun, turbidity, bands, false)
    }

    /// The SH lighting from any model's `table` (see [`new`](Self::new)); `filter` selects
    /// whether eq. 5 is applied.
    ///
    /// # Errors
    /// As [`new`](Self::new), with the ranges of `table`.
    #[inline]
    pub fn from_table<const NT: usize, const NU: usize, const MT: usize, const MU: usize>(
        table: &PolynomialTable<NT, NU, MT, MU>,
        sun: Sun,
        turbidity: f32,
        bands: usize,
        filter: bool,
    ) -> Result<Self, SkyError> {
        let [t_lo, t_hi] = table.turbidity;
        let turbidity = check_range("turbidity", turbidity, t_lo, t_hi)?;
        let theta = sun.zenith();
        if theta > table.sun_zenith[1] {
            return Err(SkyError::SunBelowHorizon { zenith: theta });
        }
        check_bands(bands)?;
        let mut coefficients = [Vec3::ZERO; MAX_COEFFICIENTS];
        table.evaluate(theta, turbidity, bands, &mut coefficients);
        // The irradiance uses the unfiltered zonal terms: the clamped-cosine convolution has
        // no ringing to suppress, and eq. 5 would bias it by several per cent.
        let zonal: [Vec3; MAX_BANDS] = core::array::from_fn(|l| coefficients[basis::index(l, 0)]);
        if filter {
            filter::apply(&mut coefficients, bands);
        }
        rotation::rotate_about_zenith(&mut coefficients, bands, sun.azimuth());
        let mut sky = Self::with_coefficients(coefficients, bands);
        for (l, z) in zonal.iter().enumerate() {
            sky.irradiance[basis::index(l, 0)] = *z * CLAMPED_COSINE[l];
        }
        Ok(sky)
    }

    /// The SH lighting given by `coefficients` (RGB at [`basis::index`]`(l, m)`, e.g. projected
    /// by the caller), of which the first `bands` bands are used as they are: no filter, no
    /// rotation.
    ///
    /// # Errors
    /// [`SkyError::OutOfRange`] for `bands` outside 1..=7.
    pub fn from_coefficients(
        coefficients: [Vec3; MAX_COEFFICIENTS],
        bands: usize,
    ) -> Result<Self, SkyError> {
        check_bands(bands)?;
        let mut c = coefficients;
        c[bands * bands..].fill(Vec3::ZERO);
        Ok(Self::with_coefficients(c, bands))
    }

    fn with_coefficients(coefficients: [Vec3; MAX_COEFFICIENTS], bands: usize) -> Self {
        let irradiance = core::array::from_fn(|i| coefficients[i] * CLAMPED_COSINE[BAND_OF[i]]);
        Self {
            bands,
            coefficients,
            irradiance,
        }
    }

    /// The number of bands used.
    #[must_use]
    pub fn bands(&self) -> usize {
        self.bands
    }

    /// The SH coefficients `c_lm` (RGB) at [`basis::index`]`(l, m)`: filtered (unless built by
    /// [`new_unfiltered`](Self::new_unfiltered)) and rotated to the sun's azimuth; 0 beyond
    /// the bands used.
    #[must_use]
    pub fn coefficients(&self) -> &[Vec3; MAX_COEFFICIENTS] {
        &self.coefficients
    }

    /// The SH sky's radiance towards `dir`: [`series`](Self::series) with every channel
    /// clamped at zero above the horizon, black below it (the crate's rule,
    /// [`geom::below_horizon`](crate::geom::below_horizon), on `dir` normalised); linear sRGB on the
    /// model's scale, finite and non-negative for every `dir` (need not be unit length; a zero
    /// or non-finite vector gives a finite, meaningless value).
    #[inline]
    #[must_use]
    pub fn radiance(&self, dir: Vec3) -> Vec3 {
        if dir.z >= -crate::geom::HORIZON_TOLERANCE * dir.length() {
            self.series(dir).max(Vec3::ZERO)
        } else {
            Vec3::ZERO
        }
    }

    /// The truncated series itself, `Σ c_lm Y_lm(dir)` (eq. 1), over the whole sphere: what
    /// the ringing filter acts on, negative where the series rings. Finite for every `dir`.
    #[inline]
    #[must_use]
    pub fn series(&self, dir: Vec3) -> Vec3 {
        Self::expand(&self.coefficients, dir, self.bands)
    }

    /// The irradiance on a surface with unit normal `normal` lit by the SH sky, `E(n) =
    /// ∫ max(n·ω, 0) L(ω) dω = Σ Â_l c_lm Y_lm(n)` (the clamped-cosine convolution,
    /// [`basis::CLAMPED_COSINE`]): linear sRGB on the model's scale times steradians (its
    /// luminance is the illuminance in lux for the Preetham sky).
    ///
    /// The irradiance always uses the unfiltered coefficients (the ringing filter of eq. 5
    /// would bias it by up to 4 % of the largest irradiance; the convolution needs no filter).
    ///
    /// **Accuracy** against a brute-force cosine-weighted f64 integral of the Preetham sky
    /// (zero below the horizon), for normals over the whole sphere, relative to the largest
    /// irradiance over the normals: within 1 % from 5 bands on (0.9 % at 5, 0.4 % at 7; 2.9 %
    /// at 3 bands), held by `tests/tests/sh.rs`.
    ///
    /// Clamped at zero (a truncated series can dip below zero where a surface faces away
    /// from the sky); finite for every `normal`.
    #[inline]
    #[must_use]
    pub fn irradiance(&self, normal: Vec3) -> Vec3 {
        Self::expand(&self.irradiance, normal, self.bands).max(Vec3::ZERO)
    }

    #[inline]
    fn expand(c: &[Vec3; MAX_COEFFICIENTS], dir: Vec3, bands: usize) -> Vec3 {
        let y = basis::evaluate(dir, bands);
        let n = bands * bands;
        c[..n]
            .iter()
            .zip(&y[..n])
            .fold(Vec3::ZERO, |s, (c, y)| s + *c * *y)
    }
}

/// Checks that `bands` lies in 1..=[`MAX_BANDS`].
fn check_bands(bands: usize) -> Result<(), SkyError> {
    if (1..=MAX_BANDS).contains(&bands) {
        Ok(())
    } else {
        #[allow(clippy::cast_precision_loss)] // small integers; huge ones need no precision
        Err(SkyError::OutOfRange {
            parameter: "SH bands",
            value: bands as f32,
            min: 1.0,
            max: MAX_BANDS as f32,
        })
    }
}
