//! A fast sun position: Grena's algorithm 5 (R. Grena, *Five new algorithms for the computation
//! of sun position from 2010 to 2110*, Solar Energy 86(5), 1323-1337, 2012; §3.5, Table 7 for
//! the coefficients), evaluated without f64 and without a transcendental function of a large
//! argument. Grena states a maximum error of 0.0027° (zenith and azimuth) over 2010-2110
//! against SPA; this crate accepts [`MIN_YEAR`]-[`MAX_YEAR`] (2000-2110) and holds the result
//! within 0.01° of pvlib's NREL SPA over 2000-2100 at latitudes ±80° and within 0.003° of this
//! crate's SPA over 2010-2110 (`tests/tests/sun_fast.rs`, figures in docs/controller.md).
//!
//! How it is computed:
//!
//! * **Time split exactly.** Grena's time t (days of UT from 2060-01-01 0h) is kept as a whole
//!   number of days D (an integer) and the fraction of the day f (f32); TT adds ΔT / 86,400 to
//!   the fraction (ΔT in f32: the Espenak & Meeus-based estimate `SunPosition::new` uses).
//! * **Large linear terms reduced exactly.** Every angle linear in time, φ + ω t (the mean
//!   longitude, the annual harmonic, the sidereal angle of 6.3 rad/day, the nutation and the
//!   seven perturbations of Table 7), is an angle in **turns** in 64-bit fixed point
//!   (2⁶⁴ per turn): φ and ω are converted once (at compile time), ω D is an integer product
//!   taken modulo one turn by wrapping arithmetic, exact; only ω f, under one turn and a few
//!   hundredths for most terms, is f32. The result keeps 32 bits of a turn (1.5e-9 rad).
//! * **The rest in f32**, sin and cos of an angle in turns reduced to an octant by its top
//!   bits, then Taylor polynomials on [−π/4, π/4] (a truncation error under 3e-9); the
//!   equatorial and horizontal directions are rotations of unit vectors (no asin, no atan2 for
//!   the right ascension); the zenith and azimuth are two `atan2f` and one `sqrtf` of libm,
//!   which are f32 throughout.
//!
//! An order of magnitude fewer instructions than the f64 form on a single-precision FPU and on
//! the FPU-less cores (docs/controller.md, "Instructions per step").

#![allow(clippy::unreadable_literal, clippy::many_single_char_names)]

use core::f32::consts::{FRAC_PI_2, PI, TAU};

use super::{Site, SunPosition, UtcTime};
use crate::error::SkyError;

/// The first year accepted: Grena fitted 2010-2110; 2000-2009 is held within 0.01° of pvlib's
/// SPA by `tests/tests/sun_fast.rs`.
pub const MIN_YEAR: i32 = 2000;
/// The last year accepted (Grena's range).
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

/// 2⁶⁴, one turn in [`Linear`]'s fixed point.
const TURN: f64 = 18_446_744_073_709_551_616.0;

/// The fraction of a turn of `radians`, in `[0, 1)`, times 2⁶⁴ (compile time only: f64 keeps
/// 53 bits of it, 1e-16 of a turn).
#[allow(
    clippy::cast_possible_truncation,
    clippy::cast_sign_loss,
    clippy::cast_precision_loss
)]
const fn fixed_turns(radians: f64) -> u64 {
    let turns = radians / core::f64::consts::TAU;
    let fraction = turns - (turns as i64) as f64;
    let fraction = if fraction < 0.0 {
        fraction + 1.0
    } else {
        fraction
    };
    (fraction * TURN) as u64
}

/// An angle linear in time, φ + ω t, in turns: φ and ω modulo one turn in 64-bit fixed point,
/// and ω in f32 turns per day for the fraction of a day.
#[derive(Clone, Copy)]
struct Linear {
    phase: u64,
    rate: u64,
    rate_turns: f32,
}

impl Linear {
    /// φ + ω t for φ in radians and ω in radians per day.
    #[allow(clippy::cast_possible_truncation)]
    const fn new(phase: f64, rate: f64) -> Self {
        Self {
            phase: fixed_turns(phase),
            rate: fixed_turns(rate),
            rate_turns: (rate / core::f64::consts::TAU) as f32,
        }
    }

    /// The angle at `days` whole days and `fraction` of a day (in turns, 2³² per turn): the
    /// whole days' part exact modulo one turn, the fraction's part in f32.
    #[allow(clippy::cast_sign_loss, clippy::cast_possible_truncation)]
    fn at(self, days: i64, fraction: f32) -> u32 {
        let whole = self.phase.wrapping_add(self.rate.wrapping_mul(days as u64));
        ((whole >> 32) as u32).wrapping_add(turns_to_fixed(self.rate_turns * fraction))
    }
}

/// An angle in f32 turns (any magnitude below 2³¹ turns) as 2³² per turn, modulo one turn.
#[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
fn turns_to_fixed(turns: f32) -> u32 {
    (turns * 4_294_967_296.0) as i64 as u32
}

/// An angle in f32 radians as 2³² per turn, modulo one turn.
fn radians_to_fixed(radians: f32) -> u32 {
    turns_to_fixed(radians * (1.0 / TAU))
}

/// sin and cos of `x` radians for |x| ≤ π/4: Taylor polynomials to x⁹ and x¹⁰ (truncation
/// below 2e-9 and 3e-10; the f32 evaluation adds about 1e-7).
fn sincos_octant(x: f32) -> (f32, f32) {
    let x2 = x * x;
    let sin = x
        * (1.0
            + x2 * (-1.0 / 6.0
                + x2 * (1.0 / 120.0 + x2 * (-1.0 / 5_040.0 + x2 * (1.0 / 362_880.0)))));
    let cos = 1.0
        + x2 * (-0.5
            + x2 * (1.0 / 24.0
                + x2 * (-1.0 / 720.0 + x2 * (1.0 / 40_320.0 + x2 * (-1.0 / 3_628_800.0)))));
    (sin, cos)
}

/// sin and cos of an angle in turns (2³² per turn): the nearest quarter turn from the top bits,
/// the rest (at most an eighth of a turn) by [`sincos_octant`].
#[allow(clippy::cast_possible_wrap, clippy::cast_precision_loss)]
fn sincos(angle: u32) -> (f32, f32) {
    let quadrant = angle.wrapping_add(1 << 29) >> 30;
    let rest = angle.wrapping_sub(quadrant << 30) as i32;
    let (s, c) = sincos_octant(rest as f32 * (TAU / 4_294_967_296.0));
    match quadrant {
        0 => (s, c),
        1 => (c, -s),
        2 => (-s, -c),
        _ => (-c, s),
    }
}

/// TT − UT in seconds at the middle of `month` of `year` (2000-2110), in f32: the estimate of
/// the `solar-positioning` crate that [`SunPosition::new`] uses (Espenak & Meeus' polynomial
/// to 2005, then that crate's pieces joined in value and slope), evaluated in f32 (a second
/// of ΔT moves the sun by 1.2e-5°).
#[allow(clippy::cast_precision_loss)] // years and months, exact in f32
fn delta_t(year: i32, month: u32) -> f32 {
    let at = |base: i32| (year - base) as f32 + (month as f32 - 0.5) / 12.0;
    if year < 2005 {
        let t = at(2000);
        63.86
            + t * (0.3345
                + t * (-0.060374 + t * (0.0017275 + t * (0.000651814 + t * 0.00002373599))))
    } else if year < 2015 {
        64.69 + 0.2930 * at(2005)
    } else if year < 2026 || (year == 2026 && month <= 6) {
        let t = at(2015);
        67.62 + t * (0.2930 + t * (0.087_531_66 + t * (-0.020_049_796 + t * 0.000_975_849_63)))
    } else {
        let t = at(2026) - 0.5;
        69.14 + t * (0.288_052_9 + t * 0.005_738_04)
    }
}

/// The annual harmonic ωa te of the heliocentric longitude.
const ANNUAL: Linear = Linear::new(0.0, 0.0172019715);
/// The heliocentric longitude's linear part, 1.7527901 + 1.7202792159e-2 te.
const LONGITUDE: Linear = Linear::new(1.7527901, 1.7202792159e-2);
/// The nutation's argument, 9.282e-4 te − 0.8.
const NUTATION: Linear = Linear::new(-0.8, 9.282e-4);
/// The sidereal angle's linear part, 1.7528311 + 6.300388099 t (UT).
const SIDEREAL: Linear = Linear::new(1.7528311, 6.300388099);
/// Table 7's seven perturbations of the longitude: amplitude d_i (rad) and the argument
/// ω_i te + φ_i.
const PERTURBATIONS: [(f32, Linear); 7] = [
    (1.27e-5, Linear::new(-2.337, 1.49e-3)),
    (1.21e-5, Linear::new(3.065, 4.31e-3)),
    (2.33e-5, Linear::new(-1.533, 1.076e-2)),
    (3.49e-5, Linear::new(-2.358, 1.575e-2)),
    (2.67e-5, Linear::new(0.074, 2.152e-2)),
    (1.28e-5, Linear::new(1.547, 3.152e-2)),
    (3.14e-5, Linear::new(-0.488, 2.1277e-1)),
];

/// An angle in f64 degrees (a site's latitude or longitude) as 2³² per turn, through f32.
#[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
fn degrees_to_fixed(degrees: f64) -> u32 {
    ((degrees as f32) * (4_294_967_296.0 / 360.0)) as i64 as u32
}

/// The sun's position at `time` seen from `site` by Grena's algorithm 5: the geometric
/// topocentric zenith (Grena's parallax term, the site's elevation neglected), the compass
/// azimuth, and the zenith refracted by Grena's formula for 1013.25 hPa and 15 °C (as SPA: from
/// a geometric elevation of −0.83° up, none below). TT − UT (ΔT) is the estimate
/// [`SunPosition::new`] uses.
/// Error bounds: within 0.01° of pvlib's NREL SPA (zenith, azimuth × sin zenith) over
/// 2000-2100 at latitudes ±80°; see the module docs.
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
#[allow(clippy::cast_precision_loss, clippy::cast_possible_truncation)] // small whole numbers
pub fn sun_position(time: &UtcTime, site: &Site) -> Result<SunPosition, SkyError> {
    if !(MIN_YEAR..=MAX_YEAR).contains(&time.year) {
        return Err(SkyError::OutOfRange {
            parameter: "year (fast sun position, Grena 2012)",
            value: time.year as f32,
            min: MIN_YEAR as f32,
            max: MAX_YEAR as f32,
        });
    }
    // Time scale (§2): t = days + f, days of UT from 2060-01-01 0h; te = days + fe in TT.
    let days = days_from_civil(time.year, time.month, time.day) - days_from_civil(2060, 1, 1);
    let seconds = (time.hour * 3600 + time.minute * 60) as f32 + time.second as f32;
    let f = seconds / 86_400.0;
    let fe = f + delta_t(time.year, time.month) / 86_400.0;
    // For the slow terms only (6.19e-9 and 2.92e-5 rad/day): |te| < 22,000 days.
    let te = days as f32 + fe;

    // Heliocentric longitude L (§3.5): the annual harmonics, from sin and cos of ωa·te by the
    // angle-sum identities, the slow modulation β and the seven perturbations of Table 7.
    let (s1, c1) = sincos(ANNUAL.at(days, fe));
    let (s2, c2) = (2.0 * s1 * c1, (c1 + s1) * (c1 - s1));
    let (s3, c3) = (s2 * c1 + c2 * s1, c2 * c1 - s2 * s1);
    let mut periodic = 3.33024e-2 * s1 - 2.0582e-3 * c1 + 3.512e-4 * s2 - 4.07e-5 * c2
        + 5.2e-6 * s3
        - 9e-7 * c3
        - 8.23e-5 * s1 * sincos_octant(2.92e-5 * te).0;
    for (amplitude, argument) in PERTURBATIONS {
        periodic += amplitude * sincos(argument.at(days, fe)).0;
    }
    // Nutation in longitude and the obliquity; the geocentric longitude λ = L + π + Δλ.
    let (snu, cnu) = sincos(NUTATION.at(days, fe));
    let dlambda = 8.34e-5 * snu;
    let lambda = LONGITUDE
        .at(days, fe)
        .wrapping_add(1 << 31)
        .wrapping_add(radians_to_fixed(periodic + dlambda));
    let epsilon = 4.089567e-1 - 6.19e-9 * te + 4.46e-5 * cnu;
    let (sl, cl) = sincos(lambda);
    let (se, ce) = sincos_octant(epsilon);
    // The sun's direction in the equatorial frame, (cos δ cos α, cos δ sin α, sin δ): the
    // ecliptic unit vector at λ turned by the obliquity.
    let (ex, ey, ez) = (cl, sl * ce, sl * se);
    // The local sidereal angle θ (Grena's h = θ − α), then the direction in the frame of the
    // meridian: cos δ cos h, cos δ sin h.
    let theta = SIDEREAL
        .at(days, f)
        .wrapping_add(degrees_to_fixed(site.longitude))
        .wrapping_add(radians_to_fixed(0.92 * dlambda));
    let (st, ct) = sincos(theta);
    let x = ct * ex + st * ey;
    let y = st * ex - ct * ey;
    // Horizontal frame: up, north and the westward component (y).
    let (sp, cp) = sincos(degrees_to_fixed(site.latitude));
    let up = sp * ez + cp * x;
    let north = cp * ez - sp * x;
    let horizontal = libm::sqrtf(north * north + y * y);
    // Topocentric zenith (Grena's parallax, 4.26e-5 cos e), azimuth from south westward
    // (Grena's γ = atan2(sin h, cos h sin φ − tan δ cos φ), times cos δ > 0), refraction.
    let zenith = (libm::atan2f(horizontal, up) + 4.26e-5 * horizontal).min(PI);
    let gamma = libm::atan2f(y, -north);
    let elevation = FRAC_PI_2 - zenith;
    // From the elevation where SPA starts refracting too (its −0.26667° sun radius and
    // −0.5667° refraction at the horizon), so the apparent sun is the same by both algorithms.
    let refraction = if elevation > -0.014_545 {
        // 1 atm, 15 °C: 0.08422 P / ((273 + T) tan(e + 0.003138 / (e + 0.08919)))
        let (s, c) = sincos(radians_to_fixed(
            elevation + 0.003138 / (elevation + 0.08919),
        ));
        0.08422 * c / (288.0 * s)
    } else {
        0.0
    };
    SunPosition::from_radians_f32(zenith, refraction, gamma + PI)
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
    fn sin_and_cos_of_turns_agree_with_f64() {
        // Every octant and its edges, against f64 sin and cos of the same angle.
        let mut worst = 0.0f64;
        for k in 0..=4096u32 {
            for offset in [0u32, 1, u32::MAX] {
                let angle = k.wrapping_mul(1 << 20).wrapping_add(offset);
                let (s, c) = sincos(angle);
                let x = f64::from(angle) / 4_294_967_296.0 * core::f64::consts::TAU;
                worst = worst
                    .max((f64::from(s) - x.sin()).abs())
                    .max((f64::from(c) - x.cos()).abs());
            }
        }
        assert!(worst < 3e-7, "{worst}");
    }

    #[test]
    fn linear_terms_reduce_exactly() {
        // The sidereal angle 1.7528311 + 6.300388099 t at t = −21,915 days (2000-01-01) and
        // 0.25 of a day, against the same modulo 2π in f64 (exact to about 1e-11 rad there).
        for (days, fraction) in [(-21_915i64, 0.25f32), (18_627, 0.999), (0, 0.0), (-1, 0.5)] {
            let t = days as f64 + f64::from(fraction);
            let want = (1.7528311 + 6.300388099 * t).rem_euclid(core::f64::consts::TAU);
            let got =
                f64::from(SIDEREAL.at(days, fraction)) / 4_294_967_296.0 * core::f64::consts::TAU;
            let diff = (got - want + 3.0 * core::f64::consts::PI)
                .rem_euclid(core::f64::consts::TAU)
                - core::f64::consts::PI;
            assert!(diff.abs() < 1e-6, "{days} {fraction}: {got} against {want}");
        }
    }

    #[test]
    fn delta_t_follows_the_spa_estimate() {
        for year in MIN_YEAR..=MAX_YEAR {
            for month in 1..=12 {
                let spa =
                    solar_positioning::delta_t::estimate_from_date(year, month).expect("in range");
                let fast = f64::from(delta_t(year, month));
                assert!(
                    (fast - spa).abs() < 0.01,
                    "{year}-{month}: {fast} against {spa}"
                );
            }
        }
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
