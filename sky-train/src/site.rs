//! A site's clear atmosphere by month: the aerosol optical depth, its Ångström exponent, the
//! ozone column, the water vapour and the surface pressure of any latitude and longitude, from
//! published climatologies (`sky-train site`; `docs/daylight.md`, "The site's clear sky").
//!
//! - **Aerosol**: the monthly Linke turbidity TL(AM2) of the SoDa / Meteotest climatology
//!   (Remund, Wald, Lefèvre, Ranchin & Page 2003, "Worldwide Linke turbidity information",
//!   ISES Solar World Congress; as pvlib-python ships it), averaged to a 1° grid
//!   (`data/site/linke_turbidity_1deg.bin`, `data/site/README.md`) and interpolated bilinearly,
//!   converted to the aerosol optical depth by Ineichen 2008 ("Conversion function between the
//!   Linke turbidity and the atmospheric water vapor and aerosol content", Solar Energy 82,
//!   1095-1097): TL = (9.4 + 0.9 m) (δ_cda + δ_w + δ_a) at m = 2 (Kasten's pyrheliometric
//!   formula), δ_cda = −0.101 + 0.235 m^−0.16 the clean dry atmosphere's broadband optical
//!   depth, δ_w = 0.112 m^−0.55 w^0.34 the water vapour's, and δ_a the aerosol's broadband
//!   optical depth, which is its optical depth at 700 nm (Molineaux, Ineichen & O'Neill 1998);
//!   τ₅₅₀ = δ_a (700 / 550)^α.
//! - **Ångström exponent** α: 1.3 everywhere (no climatology of it is shipped; the physical
//!   atmosphere's default, Ångström 1929's continental value).
//! - **Ozone**: Van Heuklon 1979 ("Estimating atmospheric ozone for solar radiation models",
//!   Solar Energy 22, 63-68), the total column from latitude, longitude and day of the year, at
//!   the middle of the month.
//! - **Water vapour** (precipitable water, cm): the AFGL reference atmospheres' columns
//!   (Anderson et al. 1986, AFGL-TR-86-0110: tropical 4.12, mid-latitude summer 2.92 and winter
//!   0.85, subarctic summer 2.09 and winter 0.42 cm) interpolated in latitude (tropical to 15°,
//!   mid-latitude at 45°, subarctic from 60°) and in season (a cosine peaking in mid-July in
//!   the north, mid-January in the south), times e^(−z / 2 km) for the site's elevation z (the
//!   reference profiles' scale height). It enters the aerosol's conversion (a factor 2 in w
//!   moves τ₅₅₀ by about 0.03 w^0.34) and the luminous efficacy of a measured irradiance; the
//!   physical atmosphere does not absorb by it (360-830 nm: under 0.3 % of the illuminance,
//!   `docs/daylight.md`).
//! - **Pressure**: the US Standard Atmosphere 1976's at the site's elevation, which is given or
//!   else the 1° grid's mean elevation (`data/site/elevation_1deg.bin`: a coarse stand-in,
//!   hundreds of metres off in mountains).

use std::f64::consts::PI;

use crate::args::ParamError;
use crate::physical::Atmosphere;
use crate::physical::atmosphere::SITE_ELEVATION_RANGE_M;
use crate::physical::constituents::us76;

/// 20 × the monthly Linke turbidity, 1° cells, rows from 89.5° N, columns from 179.5° W,
/// months innermost.
static LINKE_TURBIDITY: &[u8; 180 * 360 * 12] =
    include_bytes!("../data/site/linke_turbidity_1deg.bin");
/// Mean elevation of each 1° cell, m, little-endian i16, rows and columns as above.
static ELEVATION: &[u8; 180 * 360 * 2] = include_bytes!("../data/site/elevation_1deg.bin");

/// The Ångström exponent of every site ([`Atmosphere`]'s default).
pub const ANGSTROM: f64 = 1.3;

/// The smallest aerosol optical depth the conversion gives (a turbidity below the clean, dry
/// atmosphere's plus its water vapour's would give a negative one).
pub const MIN_AOD_550: f64 = 0.01;

/// One month of a site's clear atmosphere.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SiteMonth {
    /// Latitude, degrees north.
    pub latitude: f64,
    /// Longitude, degrees east.
    pub longitude: f64,
    /// The month, 1 (January) to 12.
    pub month: u32,
    /// The site's elevation, m: as given, else the 1° grid's.
    pub elevation_m: f64,
    /// Whether the elevation came from the grid.
    pub elevation_from_grid: bool,
    /// Surface pressure, hPa (US Standard Atmosphere 1976 at the elevation).
    pub pressure_hpa: f64,
    /// The climatology's Linke turbidity TL(AM2).
    pub linke_turbidity: f64,
    /// Precipitable water, cm.
    pub water_vapour_cm: f64,
    /// Total ozone column, Dobson units.
    pub ozone_du: f64,
    /// Ångström exponent.
    pub angstrom: f64,
    /// Aerosol optical depth at 550 nm.
    pub aod_550: f64,
}

impl SiteMonth {
    /// The physical atmosphere of this month: the default atmosphere's constituents with this
    /// site's aerosol optical depth, Ångström exponent, ozone column and elevation.
    #[must_use]
    pub fn atmosphere(&self) -> Atmosphere {
        Atmosphere {
            aod_550: self.aod_550,
            angstrom: self.angstrom,
            ozone_du: self.ozone_du,
            site_elevation_m: self.elevation_m,
            ..Atmosphere::default()
        }
    }
}

/// The grid's value at (`lat`, `lon`) by bilinear interpolation between cell centres
/// (longitude wrapping, latitude clamped to the outermost centres); `cell(row, col)` reads one.
fn bilinear(lat: f64, lon: f64, cell: impl Fn(usize, usize) -> f64) -> f64 {
    let fi = (90.0 - lat - 0.5).clamp(0.0, 179.0);
    let fj = lon + 180.0 - 0.5;
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let i0 = (fi.floor() as usize).min(178);
    let wi = fi - i0 as f64;
    let j0f = fj.floor();
    let wj = fj - j0f;
    #[allow(clippy::cast_possible_truncation)]
    let j0 = (j0f as i64).rem_euclid(360);
    #[allow(clippy::cast_sign_loss, clippy::cast_possible_truncation)]
    let (a, b) = (j0 as usize, ((j0 + 1) % 360) as usize);
    cell(i0, a) * (1.0 - wi) * (1.0 - wj)
        + cell(i0 + 1, a) * wi * (1.0 - wj)
        + cell(i0, b) * (1.0 - wi) * wj
        + cell(i0 + 1, b) * wi * wj
}

/// The climatology's Linke turbidity TL(AM2) at (`lat`, `lon`) in `month` (1-12).
#[must_use]
pub fn linke_turbidity(lat: f64, lon: f64, month: u32) -> f64 {
    let m = (month.clamp(1, 12) - 1) as usize;
    bilinear(lat, lon, |i, j| {
        f64::from(LINKE_TURBIDITY[(i * 360 + j) * 12 + m]) / 20.0
    })
}

/// The 1° grid's mean elevation at (`lat`, `lon`), m.
#[must_use]
pub fn grid_elevation_m(lat: f64, lon: f64) -> f64 {
    bilinear(lat, lon, |i, j| {
        let k = (i * 360 + j) * 2;
        f64::from(i16::from_le_bytes([ELEVATION[k], ELEVATION[k + 1]]))
    })
}

/// Van Heuklon 1979's total ozone, Dobson units, at latitude `lat`, longitude `lon` (degrees,
/// east positive) on day `day` of the year: 235 + [A + C sin(D (E + F)) + G sin(H (λ + I))]
/// sin²(β φ), angles in degrees; north: A 150, β 1.28, C 40, F −30, G 20, H 3, I 20 east of
/// Greenwich and 0 west of it; south: A 100, β 1.5, C 30, F 152.625, G 20, H 2, I −75; D 0.9865.
#[must_use]
pub fn ozone_du(lat: f64, lon: f64, day: f64) -> f64 {
    let d = PI / 180.0;
    let (a, beta, c, f, g, h, i) = if lat >= 0.0 {
        (
            150.0,
            1.28,
            40.0,
            -30.0,
            20.0,
            3.0,
            if lon > 0.0 { 20.0 } else { 0.0 },
        )
    } else {
        (100.0, 1.5, 30.0, 152.625, 20.0, 2.0, -75.0)
    };
    let seasonal = a + c * (0.9865 * (day + f) * d).sin() + g * (h * (lon + i) * d).sin();
    235.0 + seasonal * (beta * lat * d).sin().powi(2)
}

/// Precipitable water, cm, at sea level for latitude `lat` on day `day` (module docs: the AFGL
/// reference atmospheres).
#[must_use]
pub fn sea_level_water_vapour_cm(lat: f64, day: f64) -> f64 {
    const TROPICAL: f64 = 4.12;
    const MID: (f64, f64) = (2.92, 0.85); // summer, winter
    const SUBARCTIC: (f64, f64) = (2.09, 0.42);
    let a = lat.abs();
    let (summer, winter) = if a <= 15.0 {
        (TROPICAL, TROPICAL)
    } else if a <= 45.0 {
        let w = (a - 15.0) / 30.0;
        (
            TROPICAL + w * (MID.0 - TROPICAL),
            TROPICAL + w * (MID.1 - TROPICAL),
        )
    } else if a <= 60.0 {
        let w = (a - 45.0) / 15.0;
        (
            MID.0 + w * (SUBARCTIC.0 - MID.0),
            MID.1 + w * (SUBARCTIC.1 - MID.1),
        )
    } else {
        SUBARCTIC
    };
    // Summer's peak in mid-July (day 196) in the north, mid-January (day 15) in the south.
    let peak = if lat >= 0.0 { 196.0 } else { 15.0 };
    let season = (2.0 * PI * (day - peak) / 365.25).cos();
    0.5 * (summer + winter) + 0.5 * (summer - winter) * season
}

/// The aerosol optical depth at 550 nm of Linke turbidity `tl` (AM2) with `w` cm of
/// precipitable water and Ångström exponent `alpha` (Ineichen 2008, module docs), at least
/// [`MIN_AOD_550`].
#[must_use]
pub fn aod_550_from_linke(tl: f64, w: f64, alpha: f64) -> f64 {
    let m: f64 = 2.0;
    let clean_dry = -0.101 + 0.235 * m.powf(-0.16);
    let water = 0.112 * m.powf(-0.55) * w.max(0.0).powf(0.34);
    let aod_700 = tl / (9.4 + 0.9 * m) - clean_dry - water;
    (aod_700 * (700.0_f64 / 550.0).powf(alpha)).max(MIN_AOD_550)
}

/// The day of the year of the 15th of `month` (a non-leap year).
#[must_use]
pub fn mid_month_day(month: u32) -> f64 {
    const FIRST: [u32; 12] = [1, 32, 60, 91, 121, 152, 182, 213, 244, 274, 305, 335];
    f64::from(FIRST[(month.clamp(1, 12) - 1) as usize] + 14)
}

/// The clear atmosphere of (`lat`, `lon`) in `month` (1-12), at `elevation_m` when given, else
/// at the 1° grid's elevation (module docs).
///
/// # Errors
/// A [`ParamError`] naming `--lat`, `--lon`, `--elevation` or the month outside its range.
pub fn site_month(
    lat: f64,
    lon: f64,
    elevation_m: Option<f64>,
    month: u32,
) -> Result<SiteMonth, ParamError> {
    if !(-90.0..=90.0).contains(&lat) {
        return Err(ParamError(format!(
            "--lat {lat} is outside the valid range [-90, 90]"
        )));
    }
    if !(-180.0..=180.0).contains(&lon) {
        return Err(ParamError(format!(
            "--lon {lon} is outside the valid range [-180, 180]"
        )));
    }
    if !(1..=12).contains(&month) {
        return Err(ParamError(format!(
            "month {month} is outside the valid range [1, 12]"
        )));
    }
    let (lo, hi) = SITE_ELEVATION_RANGE_M;
    let elevation = match elevation_m {
        Some(z) if !(lo..=hi).contains(&z) => {
            return Err(ParamError(format!(
                "--elevation {z} m is outside the valid range [{lo}, {hi}] m of the clear atmosphere"
            )));
        }
        Some(z) => z,
        None => grid_elevation_m(lat, lon).clamp(lo, hi),
    };
    let day = mid_month_day(month);
    let water = sea_level_water_vapour_cm(lat, day) * (-elevation / 2000.0).exp();
    let tl = linke_turbidity(lat, lon, month);
    Ok(SiteMonth {
        latitude: lat,
        longitude: lon,
        month,
        elevation_m: elevation,
        elevation_from_grid: elevation_m.is_none(),
        pressure_hpa: us76(elevation).1 / 100.0,
        linke_turbidity: tl,
        water_vapour_cm: water,
        ozone_du: ozone_du(lat, lon, day),
        angstrom: ANGSTROM,
        aod_550: aod_550_from_linke(tl, water, ANGSTROM),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Van Heuklon's formula at the check value of W. Broenkow's implementation (Moss Landing
    /// Marine Laboratories, 1997): 36° N, 122° W, day 185 → 321.2 DU.
    #[test]
    fn van_heuklon_check_value() {
        let o = ozone_du(36.0, -122.0, 185.0);
        assert!((o - 321.2).abs() < 0.2, "{o}");
    }

    /// pvlib 0.16.1's `lookup_linke_turbidity` (the 5' source, no interpolation): Tucson
    /// (32.23° N, 110.96° W) in October 2.5, Payerne (46.815° N, 6.944° E) in June 4.5; the 1°
    /// table within its stated downsampling error.
    #[test]
    fn linke_turbidity_near_the_source() {
        assert!((linke_turbidity(32.23, -110.96, 10) - 2.5).abs() < 0.3);
        assert!((linke_turbidity(46.815, 6.944, 6) - 4.5).abs() < 0.5);
    }

    /// Inverting pvlib 0.16.1's `atmosphere.kasten96_lt` (Ineichen 2008): at air mass 2 with
    /// 1.5 cm of water and a broadband aerosol optical depth of 0.1, TL = 3.327929.
    #[test]
    fn aerosol_from_linke_inverts_kasten96() {
        let tau = aod_550_from_linke(3.327_929, 1.5, 0.0);
        assert!((tau - 0.1).abs() < 1e-3, "{tau}");
    }

    #[test]
    fn ranges_are_named() {
        assert!(site_month(91.0, 0.0, None, 1).is_err_and(|e| e.0.contains("--lat")));
        assert!(site_month(0.0, 0.0, Some(7000.0), 1).is_err_and(|e| e.0.contains("--elevation")));
        assert!(site_month(0.0, 0.0, None, 13).is_err());
        let s = site_month(37.70, -105.92, Some(2317.0), 1).expect("valid");
        assert!((s.pressure_hpa - 766.0).abs() < 5.0, "{}", s.pressure_hpa);
    }
}
