//! The clear-sky daylight of one UTC day at a site, as typed arrays:
//! [sky-core's `Daylight`](sky_core::daylight::Daylight) at the sun position the controller computes
//! ([`Settings::sun`](sky_core::controller::Settings)'s default algorithm), one call per day
//! (feature `daylight-day`); and the daylight's range of aerosol optical depth (features
//! `daylight` and `daylight-day`).

use sky_core::daylight;
#[cfg(feature = "daylight-day")]
use sky_core::{
    SkyError,
    controller::{self, Settings},
    daylight::Daylight,
    solar::{Site, UtcTime},
};
use wasm_bindgen::prelude::*;

#[cfg(feature = "daylight-day")]
use crate::js_error;

/// Seconds in a UTC day (leap seconds are not represented).
#[cfg(feature = "daylight-day")]
const DAY_SECONDS: f64 = 86_400.0;

/// The last whole second of a UTC day, 23:59:59.
#[cfg(feature = "daylight-day")]
const LAST_SECOND: f64 = DAY_SECONDS - 1.0;

/// The smallest step between samples, seconds: at most 86,400 samples a day.
#[cfg(feature = "daylight-day")]
const MIN_STEP_SECONDS: f64 = 1.0;

/// The clear-sky daylight at times of one UTC day at one site: per sample the sun's elevation,
/// the global, diffuse and direct horizontal illuminance, the global light's chromaticity, CCT
/// and melanopic EDI, each a `Float32Array` with one value per sample at
/// ([`times`](Self::times)).
///
/// ```js
/// // Vienna, 21 June 2026, every 5 minutes of the UTC day, the default atmosphere.
/// const day = DaylightDay.at(2026, 6, 21, 0, 86399, 300, 48.21, 16.37, 190, daylightDefaultAod());
/// const noon = day.times.findIndex((t) => t >= 11 * 3600);
/// console.log(day.globalLux[noon], day.cctK[noon], day.melanopicEdiLux[noon]);
/// day.free();
/// ```
#[cfg(feature = "daylight-day")]
#[wasm_bindgen]
#[derive(Debug, Clone, Default)]
pub struct DaylightDay {
    times: Vec<f64>,
    /// Per sample, in this order: sun elevation, global, diffuse and direct illuminance, x, y,
    /// CCT, melanopic EDI (the getters below).
    columns: [Vec<f32>; 8],
}

/// `value` in `[min, max]` (NaN is not), else sky-core's out-of-range error naming `parameter`.
#[cfg(feature = "daylight-day")]
#[allow(clippy::cast_possible_truncation)] // seconds of a day, for the message
fn check(parameter: &'static str, value: f64, min: f64, max: f64) -> Result<f64, SkyError> {
    if (min..=max).contains(&value) {
        Ok(value)
    } else {
        Err(SkyError::OutOfRange {
            parameter,
            value: value as f32,
            min: min as f32,
            max: max as f32,
        })
    }
}

#[cfg(feature = "daylight-day")]
#[wasm_bindgen]
impl DaylightDay {
    /// The daylight on `year-month-day` (UTC) from `start` to `end` seconds after 0:00 UTC
    /// (both in [0, 86399], `end` ≥ `start`; `end` is a sample when the steps reach it) every
    /// `step` seconds ([1, 86400]), at `latitude` (degrees, −90 to 90, north positive),
    /// `longitude` (degrees, −180 to 180, east positive) and `elevation` (metres, −500 to
    /// 5 000), under a clear atmosphere of aerosol optical depth `aod` at 550 nm
    /// ([`daylight_min_aod`] to [`daylight_max_aod`]) at the site's surface pressure, with the
    /// default ozone column: the controller's clear sky at that site (`Daylight::refracted`
    /// with `controller::clear_atmosphere`, the sun's beam from its refracted position, on
    /// the date's Earth-Sun distance). The sun is the controller's default (Grena 2012: the
    /// years 2000-2110).
    ///
    /// # Errors
    /// A parameter outside its range, named with the range in the message.
    #[allow(clippy::too_many_arguments)] // a date, a time range, a place and an atmosphere
    pub fn at(
        year: i32,
        month: u32,
        day: u32,
        start: f64,
        end: f64,
        step: f64,
        latitude: f64,
        longitude: f64,
        elevation: f64,
        aod: f32,
    ) -> Result<DaylightDay, JsError> {
        let start = check("start [s after 0:00 UTC]", start, 0.0, LAST_SECOND).map_err(js_error)?;
        let end = check("end [s after 0:00 UTC]", end, start, LAST_SECOND).map_err(js_error)?;
        let step = check("step [s]", step, MIN_STEP_SECONDS, DAY_SECONDS).map_err(js_error)?;
        let site = Site::new(latitude, longitude, elevation).map_err(js_error)?;
        let settings = Settings {
            aerosol_optical_depth: aod,
            ..Settings::default()
        };
        let atmosphere = controller::clear_atmosphere(&site, &settings);
        atmosphere.validate().map_err(js_error)?;
        let sun = settings.sun;
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let samples = ((end - start) / step) as usize + 1;
        let mut out = Self {
            times: Vec::with_capacity(samples),
            columns: core::array::from_fn(|_| Vec::with_capacity(samples)),
        };
        // The first sample checks the date and the sun algorithm's years.
        for k in 0..samples {
            #[allow(clippy::cast_precision_loss)]
            let t = start + k as f64 * step;
            #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
            let (hour, minute) = ((t / 3600.0) as u32, (t / 60.0) as u32 % 60);
            let second = t - f64::from(hour * 3600 + minute * 60);
            let time = UtcTime::new(year, month, day, hour, minute, second).map_err(js_error)?;
            let position = sun.position(&time, &site).map_err(js_error)?;
            let light = Daylight::refracted(&position, &atmosphere)
                .map_err(js_error)?
                .on_day(time.day_of_year());
            let (x, y) = light.chromaticity();
            #[allow(clippy::cast_possible_truncation)]
            let row = [
                position.elevation_deg() as f32,
                light.global().y,
                light.diffuse().y,
                light.direct().y,
                x,
                y,
                light.cct().map_or(f32::NAN, |c| c.kelvin),
                light.melanopic_edi(),
            ];
            out.times.push(t);
            for (column, v) in out.columns.iter_mut().zip(row) {
                column.push(v);
            }
        }
        Ok(out)
    }

    /// Column `i` of [`Self::columns`], one copy for every getter.
    #[inline(never)]
    fn column(&self, i: usize) -> Vec<f32> {
        self.columns[i].clone()
    }

    /// The samples' times, seconds after 0:00 UTC (a `Float64Array`).
    #[wasm_bindgen(getter)]
    #[must_use]
    pub fn times(&self) -> Vec<f64> {
        self.times.clone()
    }

    /// The sun's geometric elevation, degrees.
    #[wasm_bindgen(getter, js_name = elevationDeg)]
    #[must_use]
    pub fn elevation_deg(&self) -> Vec<f32> {
        self.column(0)
    }

    /// The global (sun and sky) horizontal illuminance, lux.
    #[wasm_bindgen(getter, js_name = globalLux)]
    #[must_use]
    pub fn global_lux(&self) -> Vec<f32> {
        self.column(1)
    }

    /// The diffuse (sky) horizontal illuminance, lux.
    #[wasm_bindgen(getter, js_name = diffuseLux)]
    #[must_use]
    pub fn diffuse_lux(&self) -> Vec<f32> {
        self.column(2)
    }

    /// The direct (sun) horizontal illuminance, lux.
    #[wasm_bindgen(getter, js_name = directLux)]
    #[must_use]
    pub fn direct_lux(&self) -> Vec<f32> {
        self.column(3)
    }

    /// The CIE 1931 chromaticity x of the global light.
    #[wasm_bindgen(getter)]
    #[must_use]
    pub fn x(&self) -> Vec<f32> {
        self.column(4)
    }

    /// The CIE 1931 chromaticity y of the global light.
    #[wasm_bindgen(getter)]
    #[must_use]
    pub fn y(&self) -> Vec<f32> {
        self.column(5)
    }

    /// The global light's correlated colour temperature, kelvin; NaN where it is undefined
    /// (|Duv| above 0.05, as in nautical twilight).
    #[wasm_bindgen(getter, js_name = cctK)]
    #[must_use]
    pub fn cct_k(&self) -> Vec<f32> {
        self.column(6)
    }

    /// The global light's melanopic EDI, lux (CIE S 026:2018, D65-equivalent).
    #[wasm_bindgen(getter, js_name = melanopicEdiLux)]
    #[must_use]
    pub fn melanopic_edi_lux(&self) -> Vec<f32> {
        self.column(7)
    }
}

/// The smallest aerosol optical depth at 550 nm of sky-core's daylight.
#[wasm_bindgen(js_name = daylightMinAod)]
#[must_use]
pub fn daylight_min_aod() -> f32 {
    daylight::MIN_AOD
}

/// The largest aerosol optical depth at 550 nm of sky-core's daylight.
#[wasm_bindgen(js_name = daylightMaxAod)]
#[must_use]
pub fn daylight_max_aod() -> f32 {
    daylight::MAX_AOD
}

/// The default (clear-sky record's) aerosol optical depth at 550 nm of sky-core's daylight.
#[wasm_bindgen(js_name = daylightDefaultAod)]
#[must_use]
pub fn daylight_default_aod() -> f32 {
    daylight::DEFAULT_AOD
}
