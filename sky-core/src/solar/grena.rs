//! A fast sun position: Grena's algorithm 5 (R. Grena, *Five new algorithms for the computation
//! of sun position from 2010 to 2110*, Solar Energy 86(5), 1323-1337, 2012; §3.5, Table 7 for
//! the coefficients). Grena states a maximum error of 0.0027° (zenith and azimuth) over
//! 2010-2110 against SPA; outside those years the fitted series do not hold, so they are
//! refused. Measured here against this crate's SPA over 2010-2110 at 14 sites:
//! `tests/tests/sun_fast.rs`.
//!
//! About twenty transcendental functions in f64, where SPA evaluates its periodic-term tables:
//! an order of magnitude fewer instructions on a single-precision FPU (docs/controller.md).
//! The time stays in f64: its argument 0.0172 rad/day × 18,262 days would lose 0.003° in f32.

#![allow(clippy::unreadable_literal, clippy::many_single_char_names)]

use core::f64::consts::{FRAC_PI_2, PI, TAU};

use solar_positioning::delta_t;

use super::{Site, SunPosition, UtcTime};
use crate::error::SkyError;

/// The first year of the algorithm's range.
pub const MIN_YEAR: i32 = 2010;
/// The last year of the algorithm's range.
pub const MAX_YEAR: i32 = 2110;

/// Days from 1970-01-01 to `year-month-day` in the proleptic Gregorian calendar.
fn days_from_civil(year: i32, month: u32, day: u32) -> i64 {
    let y = i64::from(year) - i64::from(month <= 2);
    let era = y.div_euclid(400);
    let yoe = y - era * 400;
    let m = i64::from(month);
    let doy = (153 * (m + if m > 2 { -3 } else { 9 }) + 2) / 5 + i64::from(day) - 1;
    let doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
    era * 146_097 + doe - 719_468
}

/// The sun's position at `time` seen from `site` by Grena's algorithm 5: the geometric
/// topocentric zenith (Grena's parallax term, the site's elevation neglected), the compass
/// azimuth, and the zenith refracted by Grena's formula for 1013.25 hPa and 15 °C (no refraction
/// with the sun below the horizon). TT − UT (ΔT) is the Espenak & Meeus estimate that
/// [`SunPosition::new`] uses.
///
/// ```
/// use sky_core::solar::{grena, Site, SunPosition, UtcTime};
///
/// let vienna = Site::new(48.21, 16.37, 190.0)?;
/// let noon = UtcTime::new(2026, 6, 21, 11, 0, 0.0)?;
/// let fast = grena::sun_position(&noon, &vienna)?;
/// let spa = SunPosition::new(&noon, &vienna)?;
/// assert!((fast.zenith_deg() - spa.zenith_deg()).abs() < 0.01);
/// assert!((fast.azimuth_deg() - spa.azimuth_deg()).abs() < 0.01);
/// assert!(grena::sun_position(&UtcTime::new(2200, 1, 1, 0, 0, 0.0)?, &vienna).is_err());
/// # Ok::<(), sky_core::SkyError>(())
/// ```
///
/// # Errors
/// [`SkyError::OutOfRange`] for a year outside [`MIN_YEAR`]-[`MAX_YEAR`].
#[allow(clippy::cast_precision_loss)] // day counts and years, exact in f64 and f32
pub fn sun_position(time: &UtcTime, site: &Site) -> Result<SunPosition, SkyError> {
    if !(MIN_YEAR..=MAX_YEAR).contains(&time.year) {
        return Err(SkyError::OutOfRange {
            parameter: "year (fast sun position, Grena 2012)",
            value: time.year as f32,
            min: MIN_YEAR as f32,
            max: MAX_YEAR as f32,
        });
    }
    // Time scale (§2): t, days of UT from 2060-01-01 0h; te, the same in TT.
    let days = days_from_civil(time.year, time.month, time.day) - days_from_civil(2060, 1, 1);
    let seconds = f64::from(time.hour * 3600 + time.minute * 60) + time.second;
    let t = days as f64 + seconds / 86_400.0;
    let dt =
        delta_t::estimate_from_date(time.year, time.month).map_err(|_| SkyError::NotFinite {
            parameter: "ΔT (fast sun position)",
        })?;
    let te = t + dt / 86_400.0;

    // Heliocentric longitude L (§3.5): the annual harmonics, from sin and cos of ωa·te by the
    // angle-sum identities, the slow modulation β and the seven perturbations of Table 7.
    let (s1, c1) = libm::sincos(0.0172019715 * te);
    let (s2, c2) = (2.0 * s1 * c1, (c1 + s1) * (c1 - s1));
    let (s3, c3) = (s2 * c1 + c2 * s1, c2 * c1 - s2 * s1);
    let mut l = 1.7527901 + 1.7202792159e-2 * te + 3.33024e-2 * s1 - 2.0582e-3 * c1 + 3.512e-4 * s2
        - 4.07e-5 * c2
        + 5.2e-6 * s3
        - 9e-7 * c3
        - 8.23e-5 * s1 * libm::sin(2.92e-5 * te);
    // (amplitude d_i, frequency ω_i rad/day, phase φ_i)
    for (d, w, phi) in [
        (1.27e-5, 1.49e-3, -2.337),
        (1.21e-5, 4.31e-3, 3.065),
        (2.33e-5, 1.076e-2, -1.533),
        (3.49e-5, 1.575e-2, -2.358),
        (2.67e-5, 2.152e-2, 0.074),
        (1.28e-5, 3.152e-2, 1.547),
        (3.14e-5, 2.1277e-1, -0.488),
    ] {
        l += d * libm::sin(w * te + phi);
    }
    // Nutation in longitude and the obliquity, geocentric longitude λ.
    let (snu, cnu) = libm::sincos(9.282e-4 * te - 0.8);
    let dlambda = 8.34e-5 * snu;
    let lambda = l + PI + dlambda;
    let epsilon = 4.089567e-1 - 6.19e-9 * te + 4.46e-5 * cnu;
    // Right ascension, declination, hour angle.
    let (sl, cl) = libm::sincos(lambda);
    let (se, ce) = libm::sincos(epsilon);
    let alpha = libm::atan2(sl * ce, cl);
    let delta = libm::asin(sl * se);
    let h = 1.7528311 + 6.300388099 * t + site.longitude.to_radians() - alpha + 0.92 * dlambda;
    let h = libm::fmod(h, TAU);
    // Topocentric elevation (parallax) and azimuth (from south, westward), then refraction.
    let (sp, cp) = libm::sincos(site.latitude.to_radians());
    let (sd, cd) = libm::sincos(delta);
    let (sh, ch) = libm::sincos(h);
    let se0 = (sp * sd + cp * cd * ch).clamp(-1.0, 1.0);
    let elevation = libm::asin(se0) - 4.26e-5 * libm::sqrt(1.0 - se0 * se0);
    let gamma = libm::atan2(sh, ch * sp - sd * cp / cd);
    let refraction = if elevation > 0.0 {
        // 1 atm, 15 °C
        0.08422 / ((273.0 + 15.0) * libm::tan(elevation + 0.003138 / (elevation + 0.08919)))
    } else {
        0.0
    };
    let zenith = (FRAC_PI_2 - elevation).to_degrees();
    let azimuth = (gamma + PI).to_degrees();
    let azimuth = if azimuth >= 360.0 { 0.0 } else { azimuth };
    SunPosition::from_degrees(zenith, zenith - refraction.to_degrees(), azimuth)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn days_match_the_calendar() {
        assert_eq!(days_from_civil(1970, 1, 1), 0);
        assert_eq!(days_from_civil(2000, 3, 1), 11_017);
        // Grena's t at 2060-01-01 0h is 0; 2010-01-01 is 18,262 days earlier (13 leap days).
        assert_eq!(
            days_from_civil(2010, 1, 1) - days_from_civil(2060, 1, 1),
            -18_262
        );
    }

    #[test]
    fn every_year_in_range_has_a_position_and_others_are_refused() {
        // The poles, the date line and the range's ends.
        for (lat, lon) in [(90.0, 180.0), (-90.0, -180.0), (0.0, 0.0), (-89.9, 179.9)] {
            let site = Site::new(lat, lon, 0.0).expect("valid");
            for year in [MIN_YEAR, 2060, MAX_YEAR] {
                for (month, day, hour) in [(1, 1, 0), (12, 31, 23)] {
                    let t = UtcTime::new(year, month, day, hour, 59, 59.999).expect("valid");
                    let p = sun_position(&t, &site).expect("in range");
                    assert!((0.0..=180.0).contains(&p.zenith_deg()), "{p:?}");
                    assert!((0.0..360.0).contains(&p.azimuth_deg()), "{p:?}");
                    assert!(p.apparent_zenith_deg() <= p.zenith_deg(), "{p:?}");
                }
            }
        }
        let site = Site::new(0.0, 0.0, 0.0).expect("valid");
        for year in [MIN_YEAR - 1, MAX_YEAR + 1] {
            let t = UtcTime::new(year, 1, 1, 0, 0, 0.0).expect("valid");
            assert!(sun_position(&t, &site).is_err());
        }
    }
}
