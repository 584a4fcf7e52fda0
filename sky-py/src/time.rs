//! UTC instants, sites and the sun's algorithm, as the Python side passes them: times as whole
//! microseconds since 1970-01-01 00:00 UTC (numpy's `datetime64[us]` as int64; NaT is its
//! smallest value), degrees and metres, and the algorithm by name.

use pyo3::PyErr;
use sky_core::solar::{Site, SunAlgorithm, UtcTime};

use crate::value_error;

/// numpy's NaT as int64.
pub(crate) const NAT: i64 = i64::MIN;

const MICROS_PER_DAY: i64 = 86_400_000_000;

/// Year, month (1-12) and day (1-31) of `days` since 1970-01-01 in the proleptic Gregorian
/// calendar (H. Hinnant, "chrono-Compatible Low-Level Date Algorithms", `civil_from_days`).
fn civil_from_days(days: i64) -> (i64, u32, u32) {
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z.rem_euclid(146_097); // day of the 400-year era, [0, 146096]
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365; // [0, 399]
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100); // from 1 March, [0, 365]
    let mp = (5 * doy + 2) / 153; // month from March, [0, 11]
    let day = doy - (153 * mp + 2) / 5 + 1;
    let month = if mp < 10 { mp + 3 } else { mp - 9 };
    let year = yoe + era * 400 + i64::from(month <= 2);
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)] // 1-12 and 1-31
    (year, month as u32, day as u32)
}

/// The calendar fields of `micros` since 1970 UTC: year, month, day, hour, minute, second.
#[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)] // each in its small range
#[allow(clippy::cast_precision_loss)] // below 6e7 microseconds: exact in f64
fn fields(micros: i64) -> (i64, u32, u32, u32, u32, f64) {
    let (year, month, day) = civil_from_days(micros.div_euclid(MICROS_PER_DAY));
    let of_day = micros.rem_euclid(MICROS_PER_DAY);
    let hour = (of_day / 3_600_000_000) as u32;
    let minute = (of_day / 60_000_000 % 60) as u32;
    let second = (of_day % 60_000_000) as f64 / 1e6;
    (year, month, day, hour, minute, second)
}

/// The time `micros` as ISO 8601 text, for messages.
pub(crate) fn iso(micros: i64) -> String {
    if micros == NAT {
        return "NaT".to_owned();
    }
    let (y, mo, d, h, mi, s) = fields(micros);
    format!("{y:04}-{mo:02}-{d:02}T{h:02}:{mi:02}:{s:09.6}Z")
}

/// The name of element `i` of the array `name` in messages, or `name` alone for a scalar.
pub(crate) fn element(name: &str, i: usize, scalar: bool) -> String {
    if scalar {
        name.to_owned()
    } else {
        format!("{name}[{i}]")
    }
}

/// The instant `micros` microseconds after 1970-01-01 00:00 UTC.
///
/// # Errors
/// A `ValueError` naming `times` (its element `i`) for NaT, or a year outside sky-core's
/// [`UtcTime::MIN_YEAR`]-[`UtcTime::MAX_YEAR`].
pub(crate) fn utc_time(micros: i64, i: usize, scalar: bool) -> Result<UtcTime, PyErr> {
    let at = || format!("{} = {}", element("times", i, scalar), iso(micros));
    if micros == NAT {
        return Err(value_error(
            &element("times", i, scalar),
            "NaT (not a time) has no sun",
        ));
    }
    let (year, month, day, hour, minute, second) = fields(micros);
    let year = i32::try_from(year).unwrap_or(i32::MAX);
    UtcTime::new(year, month, day, hour, minute, second).map_err(|e| value_error(&at(), e))
}

/// The site at `latitude`, `longitude` (degrees) and `elevation` (metres).
///
/// # Errors
/// sky-core's message naming the parameter out of its range.
pub(crate) fn site(latitude: f64, longitude: f64, elevation: f64) -> Result<Site, PyErr> {
    Site::new(latitude, longitude, elevation).map_err(|e| value_error("", e))
}

/// The sun's algorithm named `name`: "fast" (Grena 2012, 2000-2110) or "spa" (NREL SPA,
/// 1-2999).
///
/// # Errors
/// A `ValueError` naming `algorithm` for any other name.
pub(crate) fn algorithm(name: &str) -> Result<SunAlgorithm, PyErr> {
    match name {
        "fast" => Ok(SunAlgorithm::Fast),
        "spa" => Ok(SunAlgorithm::Spa),
        other => Err(value_error(
            "algorithm",
            format!(
                "{other:?} is not a sun position algorithm: \"fast\" (Grena 2012, the years \
                 2000-2110, within 0.003° of SPA) or \"spa\" (NREL SPA, the years 1-2999)"
            ),
        )),
    }
}

/// The sun's position at element `i` of `times`, naming it and the other algorithm in errors.
pub(crate) fn sun_at(
    algorithm: SunAlgorithm,
    micros: i64,
    site: &Site,
    i: usize,
    scalar: bool,
) -> Result<sky_core::solar::SunPosition, PyErr> {
    let time = utc_time(micros, i, scalar)?;
    algorithm.position(&time, site).map_err(|e| {
        let hint = if algorithm == SunAlgorithm::Fast {
            " (algorithm=\"spa\" takes the years 1-2999)"
        } else {
            ""
        };
        value_error(
            &format!("{} = {}", element("times", i, scalar), iso(micros)),
            format!("{e}{hint}"),
        )
    })
}
