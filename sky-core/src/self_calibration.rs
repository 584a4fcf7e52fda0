//! Self-calibration: the site's clear-sky level learned from the sensor's own clear periods.
//!
//! A clear-sky model meets a real sensor at a level off by a few per cent to tens of per cent,
//! and differently with the sun high and low: the site's aerosol, water vapour and pressure (a
//! turbid default atmosphere under a clean high-altitude sky), the sensor's calibration, cosine
//! response and cleanliness. [`SelfCalibration`] learns the ratio of the sensor's readings to
//! the clear sky's on the sensor's clear periods, one robust figure per clear day in each of
//! [`BANDS`] bands of sun elevation, and hands back a factor to scale the clear sky by at the
//! sun's elevation. It takes the clear sky's value as an input (any clear-sky model), allocates
//! nothing and keeps its learned state in [`STATE_BYTES`] bytes
//! ([`SelfCalibration::to_bytes`], [`SelfCalibration::from_bytes`]).
//!
//! **How** (each reading, [`SelfCalibration::update`]):
//!
//! 1. the reading and the clear sky scaled by the current factor go through Reno & Hansen's
//!    clear-period detector ([`crate::clear_period`]);
//! 2. each reading found clear with the sun at least [`MIN_SUN_ELEVATION_DEG`] high adds the
//!    logarithm of its ratio to the (unscaled) clear sky to the day's histogram of its band of
//!    sun elevation ([`BAND_EDGES_DEG`]; [`HISTOGRAM_BINS`] bins over ln 0.4 to ln 2.5, 2.9 %
//!    wide, the median interpolated within its bin; the band is that of the sun at the newest
//!    reading of the clear window);
//! 3. when the mean solar day ends (local mean midnight, from the site's longitude), a day with
//!    at least [`MIN_CLEAR_MINUTES`] clear minutes is a clear day; each band with at least
//!    [`MIN_BAND_MINUTES`] of them keeps that day's median ratio, the last [`DAYS_KEPT`] per
//!    band, and the band's level is their median (one day gives its own, two their geometric
//!    mean): a single odd day (snow on the sensor, a haze the detector took for clear) moves
//!    it by no more than the next-nearest day;
//! 4. the factor at a sun elevation is the bands' levels interpolated linearly in the
//!    logarithm of the air mass (1 / sin of the elevation) between the bands' centres, the
//!    nearest learned band's beyond them; 1 before the first clear day.
//!
//! Before a band's first clear day the detector's clear sky is rescaled, in that band, by the
//! running median of the band's clear readings so far (as pvlib's `detect_clearsky` refits its
//! factor α); bands without clear readings take the nearest band's. This finds a site up to
//! about 15 % from the model; farther (NREL Golden in winter, 20-25 % above the default clear
//! sky at midday) the mean and maximum criteria (75 and 65 W/m²) hold only with the sun low,
//! where the ratio is higher still, and the estimator does not learn (`docs/weather.md`).
//!
//! **Bounds and status** ([`Status`]). Every band's factor is limited to [`Bounds`] (by default
//! [`Bounds::DEFAULT`], 0.75 to 1.6 of the clear sky given). The *level* is the mean of the
//! learned bands' logarithms: beyond the bounds the status is [`Status::SensorSuspect`] (a
//! sensor reading clear days at 60 % of the clear sky is shaded, covered or miscalibrated, not
//! at a hazy site). After [`DAYS_KEPT`] clear days the level is *commissioned* (kept in the
//! state); a later level more than [`Bounds::drift`] away from it (8 % by default) gives
//! [`Status::Drifted`]: soiling, a new obstruction or a recalibration; the factor follows it
//! within the bounds, and the status says so until the level returns or the state is
//! commissioned anew ([`SelfCalibration::recommission`]).
//!
//! **Bright days.** A sensor reading far above the clear sky may never be found clear at all
//! (the detector's mean and maximum criteria are absolute, 75 W/m²), so it would learn nothing
//! and say nothing. Each window the detector does not find clear, with the sun in the bands, is
//! therefore judged once more against the clear sky scaled by the window's own least-squares
//! factor ([`crate::clear_period::ClearSkyDetector::fitted_clear_window`]). A day with
//! [`MIN_CLEAR_MINUTES`] of readings clear only at a factor above the upper bound is a *bright*
//! day: [`Status::SensorSuspect`] from then on, whatever the days after it (a sensor far too
//! high may still pass for clear under a smooth overcast it reads as a dim clear sky), until
//! [`SelfCalibration::recommission`]; the flag is kept in the state. No sky is smooth for an
//! hour and brighter than the brightest clear sky the bounds allow (a sensor with a wrong
//! sensitivity constant is); a smooth overcast is darker, so the lower side has no such test.
//!
//! **What it cannot tell.** One sensor cannot tell a dirty or miscalibrated sensor from a site
//! whose clear sky is that much dimmer or brighter than the model: within the bounds it learns
//! either as the site's level (the clear-sky index then reads 1 on clear days, which is what a
//! controller classifying cloud needs, while the absolute level stays the sensor's). Narrower
//! bounds would not help: even against the site's climatology (`sky-train site`), a clean
//! sensor's learned factor at the month's end spans 0.84 to 1.28 over a year of DTU Lyngby's
//! months (`docs/weather.md`), as far apart as a +25 % calibration error. A shaded part of the
//! day (a clipped morning) is not a clear period for the detector and does not enter the level.

use crate::clear_period::{ClearSkyDetector, Criteria, Verdict};
use crate::error::SkyError;
use crate::math;
use crate::solar::UtcTime;

/// Readings with the sun lower than this, degrees, do not enter the level (the cosine response
/// of pyranometers and the clear-sky models' own errors grow near the horizon, and so do
/// obstructions).
pub const MIN_SUN_ELEVATION_DEG: f32 = 10.0;

/// Bands of sun elevation, degrees: 10-20, 20-35, 35-55, 55-90.
pub const BAND_EDGES_DEG: [f32; BANDS + 1] = [MIN_SUN_ELEVATION_DEG, 20.0, 35.0, 55.0, 90.0];

/// The number of bands of sun elevation.
pub const BANDS: usize = 4;

/// Clear minutes (with the sun above [`MIN_SUN_ELEVATION_DEG`]) that make a day a clear day.
pub const MIN_CLEAR_MINUTES: u32 = 60;

/// Clear minutes in a band on a clear day that make the day count for the band.
pub const MIN_BAND_MINUTES: u32 = 15;

/// Clear days whose medians each band keeps; the band's level is their median.
pub const DAYS_KEPT: usize = 3;

/// Bins of each band's histogram of ln(reading / clear sky) over the day.
pub const HISTOGRAM_BINS: usize = 64;

/// The histogram's range of ratios (reading over clear sky): ratios outside count in the end
/// bins.
pub const HISTOGRAM_RANGE: (f32, f32) = (0.4, 2.5);

/// Bytes of the learned state ([`SelfCalibration::to_bytes`]).
pub const STATE_BYTES: usize = 36;

/// The state's format version (byte 1).
pub const STATE_VERSION: u8 = 1;

/// The state's first byte.
const STATE_MAGIC: u8 = 0x5C;

/// The learned levels' unit in the state: ln(ratio) × 8192 as i16 (±4 in ln, 1.2e-4
/// resolution).
const LN_SCALE: f32 = 8192.0;

/// The range a learned factor may take, and the drift that is flagged.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Bounds {
    /// The smallest factor (reading over clear sky on clear days).
    pub min: f32,
    /// The largest factor.
    pub max: f32,
    /// The relative change of the level from the commissioned one that is flagged
    /// ([`Status::Drifted`]).
    pub drift: f32,
}

impl Bounds {
    /// 0.75 to 1.6, drift 8 %: wide enough for the default clear sky (one turbid aerosol depth,
    /// 0.38, at sea level) at the clean and high sites measured, where it is up to 1.5 too dim
    /// with the sun low (`docs/weather.md`), narrow enough to flag a sensor reading 40 % low.
    pub const DEFAULT: Self = Self {
        min: 0.75,
        max: 1.6,
        drift: 0.08,
    };

    fn check(self) -> Result<Self, SkyError> {
        crate::error::check_range("calibration bound min", self.min, 0.4, 1.0)?;
        crate::error::check_range("calibration bound max", self.max, 1.0, 2.5)?;
        crate::error::check_range("calibration drift", self.drift, 0.0, 1.0)?;
        Ok(self)
    }
}

/// What the learned level says about the sensor.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Status {
    /// Fewer than [`DAYS_KEPT`] clear days so far (none: the factor is 1).
    Learning,
    /// The level rests on [`DAYS_KEPT`] clear days, within the bounds and the drift.
    Calibrated,
    /// The level has moved more than [`Bounds::drift`] from the commissioned one (soiling, an
    /// obstruction, a recalibration); the factor follows it within the bounds.
    Drifted,
    /// The level is beyond the bounds (the factor is held at the bound), or a day since the
    /// last recommissioning had an hour clear only above the bounds (a *bright* day, module
    /// docs): the sensor is shaded, covered, miscalibrated or not a global horizontal sensor.
    SensorSuspect,
}

impl Status {
    /// A short name: `learning`, `calibrated`, `drifted`, `sensor-suspect`.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Learning => "learning",
            Self::Calibrated => "calibrated",
            Self::Drifted => "drifted",
            Self::SensorSuspect => "sensor-suspect",
        }
    }
}

/// One reading for the calibration.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Observation {
    /// Seconds since 1970-01-01 00:00 UTC ([`unix_seconds`]).
    pub seconds: i64,
    /// The sun's elevation, degrees.
    pub sun_elevation_deg: f32,
    /// The measured global horizontal irradiance, W/m².
    pub measured: f32,
    /// The clear sky's global horizontal irradiance at the same time, W/m² (unscaled: the
    /// model's).
    pub clear: f32,
}

/// What one reading gave.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Calibrated {
    /// The factor to scale the clear sky by at this reading's sun elevation, after this
    /// reading (within the bounds; 1 before the first clear day).
    pub factor: f32,
    /// The clear-period detector's verdict on the window ending at this reading.
    pub verdict: Verdict,
    /// The status after this reading.
    pub status: Status,
}

/// One band of sun elevation: its learned days and the day in progress.
#[derive(Debug, Clone, PartialEq)]
struct Band {
    /// ln of the last clear days' medians, oldest first; `days` of them valid.
    history: [f32; DAYS_KEPT],
    days: usize,
    histogram: [u16; HISTOGRAM_BINS],
    count: u32,
    /// ln of the running median of the band's clear readings before its first clear day:
    /// the detector's level until then.
    provisional: Option<f32>,
}

impl Band {
    const EMPTY: Self = Self {
        history: [0.0; DAYS_KEPT],
        days: 0,
        histogram: [0; HISTOGRAM_BINS],
        count: 0,
        provisional: None,
    };

    /// ln of the band's level, `None` before its first clear day.
    fn level(&self) -> Option<f32> {
        let h = &self.history;
        match self.days {
            0 => None,
            1 => Some(h[0]),
            2 => Some(0.5 * (h[0] + h[1])),
            _ => Some(h[0].max(h[1]).min(h[2]).max(h[0].min(h[1]))),
        }
    }

    fn add(&mut self, ln_ratio: f32) {
        let (lo, hi) = ln_range();
        #[allow(clippy::cast_precision_loss)]
        let t = (ln_ratio - lo) / (hi - lo) * HISTOGRAM_BINS as f32;
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let bin = if t > 0.0 {
            (t as usize).min(HISTOGRAM_BINS - 1)
        } else {
            0
        };
        self.histogram[bin] = self.histogram[bin].saturating_add(1);
        self.count = self.count.saturating_add(1);
    }

    /// ln of the median of the day's histogram (linear within its bin); 0 when empty.
    #[allow(clippy::cast_precision_loss)]
    fn median(&self) -> f32 {
        let (lo, hi) = ln_range();
        let width = (hi - lo) / HISTOGRAM_BINS as f32;
        let half = self.count as f32 * 0.5;
        let mut below = 0.0f32;
        for (i, &n) in self.histogram.iter().enumerate() {
            let n = f32::from(n);
            if n > 0.0 && below + n >= half {
                return lo + width * (i as f32 + (half - below) / n);
            }
            below += n;
        }
        0.0
    }

    fn keep(&mut self, ln_level: f32) {
        if self.days == DAYS_KEPT {
            self.history.copy_within(1.., 0);
            self.history[DAYS_KEPT - 1] = ln_level;
        } else {
            self.history[self.days] = ln_level;
            self.days += 1;
        }
    }

    fn clear_day(&mut self) {
        self.histogram = [0; HISTOGRAM_BINS];
        self.count = 0;
    }
}

fn ln_range() -> (f32, f32) {
    (math::ln(HISTOGRAM_RANGE.0), math::ln(HISTOGRAM_RANGE.1))
}

/// ln of the relative air mass 1 / sin(elevation) (the elevation at least 1°), the axis the
/// bands' levels are interpolated on.
fn ln_air_mass(elevation_deg: f32) -> f32 {
    let e = elevation_deg.clamp(1.0, 90.0).to_radians();
    -math::ln(math::sin(e))
}

/// The band of a sun elevation, `None` below [`MIN_SUN_ELEVATION_DEG`] (or NaN).
fn band_of(elevation_deg: f32) -> Option<usize> {
    (elevation_deg >= BAND_EDGES_DEG[0]).then(|| {
        (1..BANDS)
            .take_while(|&i| elevation_deg >= BAND_EDGES_DEG[i])
            .count()
    })
}

/// The estimator (module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct SelfCalibration {
    bounds: Bounds,
    longitude_deg: f32,
    detector: ClearSkyDetector,
    bands: [Band; BANDS],
    /// ln of the commissioned level.
    commissioned: Option<f32>,
    /// Clear days counted since the state began (saturating).
    clear_days: u16,
    /// The current mean solar day.
    day: Option<i64>,
    /// The day's clear readings in all bands.
    day_all: Band,
    /// The clear readings of all bands before the first clear day.
    all: Band,
    /// Readings today found clear only against the clear sky scaled above the bounds
    /// ([`ClearSkyDetector::fitted_clear_window`]).
    bright_readings: u32,
    /// A bright day has been seen since the state began or was last recommissioned (kept in
    /// the state).
    bright: bool,
}

/// Seconds of `time` since 1970-01-01 00:00 UTC (proleptic Gregorian; the seconds rounded down).
#[must_use]
pub fn unix_seconds(time: &UtcTime) -> i64 {
    // Days from the civil date (H. Hinnant's days_from_civil).
    let (m, d) = (i64::from(time.month()), i64::from(time.day()));
    let y = i64::from(time.year()) - i64::from(m <= 2);
    let era = y.div_euclid(400);
    let yoe = y - era * 400;
    let doy = (153 * (m + if m > 2 { -3 } else { 9 }) + 2) / 5 + d - 1;
    let doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
    let days = era * 146_097 + doe - 719_468;
    #[allow(clippy::cast_possible_truncation)] // 0 to 60
    let second = time.second() as i64;
    days * 86_400 + i64::from(time.hour()) * 3600 + i64::from(time.minute()) * 60 + second
}

impl SelfCalibration {
    /// A new estimator (nothing learned: factor 1, [`Status::Learning`]) for readings every
    /// `interval_seconds` at a site at `longitude_deg` (east positive; it places the day's end
    /// at local mean midnight), detecting clear periods by `criteria` and bounded by `bounds`.
    ///
    /// ```
    /// use sky_core::clear_period::Criteria;
    /// use sky_core::self_calibration::{Bounds, Observation, SelfCalibration, Status};
    ///
    /// let mut cal = SelfCalibration::new(Criteria::RENO_HANSEN_2016, 60, 0.0, Bounds::DEFAULT)?;
    /// // Five clear days (a smooth clear-sky curve), the sensor reading 7 % below the model.
    /// for minute in 0..5 * 1440 {
    ///     let hours = (minute % 1440) as f32 / 60.0;
    ///     let elevation = 65.0 * (core::f32::consts::PI * (hours - 5.5) / 13.0).sin();
    ///     let clear = 1000.0 * elevation.max(0.0).to_radians().sin().powf(1.2);
    ///     let o = Observation { seconds: 60 * minute, sun_elevation_deg: elevation, measured: 0.93 * clear, clear };
    ///     cal.update(&o);
    /// }
    /// assert!((cal.factor(40.0) - 0.93).abs() < 0.01 && cal.status() == Status::Calibrated);
    /// let saved = cal.to_bytes();                  // 36 bytes for the firmware's flash
    /// let restored = SelfCalibration::from_bytes(&saved, Criteria::RENO_HANSEN_2016, 60, 0.0, Bounds::DEFAULT)?;
    /// assert!((restored.factor(40.0) - cal.factor(40.0)).abs() < 2e-4); // ln × 8192 as i16
    /// # Ok::<(), sky_core::SkyError>(())
    /// ```
    ///
    /// # Errors
    /// The detector's ([`ClearSkyDetector::new`]); [`SkyError::OutOfRange`] for bounds outside
    /// min 0.4-1, max 1-2.5, drift 0-1, or a longitude outside ±180°.
    pub fn new(
        criteria: Criteria,
        interval_seconds: u32,
        longitude_deg: f32,
        bounds: Bounds,
    ) -> Result<Self, SkyError> {
        crate::error::check_range("longitude [deg]", longitude_deg, -180.0, 180.0)?;
        Ok(Self {
            bounds: bounds.check()?,
            longitude_deg,
            detector: ClearSkyDetector::new(criteria, interval_seconds)?,
            bands: [Band::EMPTY; BANDS],
            commissioned: None,
            clear_days: 0,
            day: None,
            day_all: Band::EMPTY,
            all: Band::EMPTY,
            bright_readings: 0,
            bright: false,
        })
    }

    /// The bounds.
    #[must_use]
    pub fn bounds(&self) -> Bounds {
        self.bounds
    }

    /// The clear-period detector.
    #[must_use]
    pub fn detector(&self) -> &ClearSkyDetector {
        &self.detector
    }

    /// Clear days counted since the state began (saturating at 65,535).
    #[must_use]
    pub fn clear_days(&self) -> u16 {
        self.clear_days
    }

    /// ln of the level: the mean of the learned bands' ln levels; `None` before the first
    /// clear day.
    fn level(&self) -> Option<f32> {
        let (mut sum, mut n) = (0.0f32, 0.0f32);
        for l in self.bands.iter().filter_map(Band::level) {
            sum += l;
            n += 1.0;
        }
        (n > 0.0).then(|| sum / n)
    }

    /// The learned level (reading over clear sky on clear days, the bands' geometric mean),
    /// unbounded; `None` before the first clear day.
    #[must_use]
    pub fn level_unbounded(&self) -> Option<f32> {
        self.level().map(math::exp_libm)
    }

    /// The factor to scale the clear sky by with the sun at `elevation_deg` (module docs),
    /// within the bounds; 1 before the first clear day.
    #[must_use]
    pub fn factor(&self, elevation_deg: f32) -> f32 {
        self.interpolated(elevation_deg, Band::level)
    }

    /// The bands' `level`s interpolated in ln air mass at `elevation_deg`, within the bounds;
    /// 1 where no band has one.
    fn interpolated(&self, elevation_deg: f32, level: fn(&Band) -> Option<f32>) -> f32 {
        let x = ln_air_mass(elevation_deg);
        // The nearest bands' centres at a larger and at a smaller air mass.
        let mut below: Option<(f32, f32)> = None;
        let mut above: Option<(f32, f32)> = None;
        for (i, b) in self.bands.iter().enumerate() {
            let Some(l) = level(b) else { continue };
            let c = ln_air_mass(0.5 * (BAND_EDGES_DEG[i] + BAND_EDGES_DEG[i + 1]));
            if c >= x {
                below = Some((c, l));
            } else if above.is_none() {
                above = Some((c, l));
            }
        }
        let ln_k = match (below, above) {
            (None, None) => return 1.0,
            (Some((_, l)), None) | (None, Some((_, l))) => l,
            (Some((c0, l0)), Some((c1, l1))) => l0 + (l1 - l0) * (x - c0) / (c1 - c0),
        };
        math::exp_libm(ln_k).clamp(self.bounds.min, self.bounds.max)
    }

    /// The status (module docs).
    #[must_use]
    pub fn status(&self) -> Status {
        if self.bright {
            return Status::SensorSuspect;
        }
        let Some(level) = self.level() else {
            return Status::Learning;
        };
        let k = math::exp_libm(level);
        let days = self.bands.iter().map(|b| b.days).max().unwrap_or(0);
        if !(self.bounds.min..=self.bounds.max).contains(&k) {
            Status::SensorSuspect
        } else if self
            .commissioned
            .is_some_and(|c| libm::fabsf(math::exp_libm(level - c) - 1.0) > self.bounds.drift)
        {
            Status::Drifted
        } else if days < DAYS_KEPT {
            Status::Learning
        } else {
            Status::Calibrated
        }
    }

    /// Takes the current level as the commissioned one (after a cleaning or a recalibration
    /// has been checked; nothing before the first clear day), and forgets a bright day.
    pub fn recommission(&mut self) {
        self.commissioned = self.level();
        self.bright = false;
    }

    /// Adds one reading (module docs) and returns the factor, the detector's verdict and the
    /// status. Readings must come in time order at the detector's interval; a gap starts a new
    /// window, and time going back a new day (the day in progress is dropped). Non-finite or
    /// non-positive values never enter the level.
    pub fn update(&mut self, o: &Observation) -> Calibrated {
        let day = o
            .seconds
            .saturating_add(self.longitude_seconds())
            .div_euclid(86_400);
        match self.day {
            Some(d) if d == day => {}
            Some(d) if d < day => {
                self.close_day();
                self.day = Some(day);
            }
            _ => {
                self.clear_day_data();
                self.day = Some(day);
            }
        }
        let working = self.working_factor(o.sun_elevation_deg);
        let verdict = self.detector.push(o.seconds, o.measured, working * o.clear);
        if let Some(band) = band_of(o.sun_elevation_deg) {
            for age in 0..verdict.newly_clear {
                if let Some((m, c)) = self.detector.reading(age)
                    && m > 0.0
                    && c > 0.0
                {
                    // The detector's clear sky was scaled by `working`.
                    let r = math::ln(m / c * working);
                    if r.is_finite() {
                        self.bands[band].add(r);
                        self.day_all.add(r);
                        if self.level().is_none() {
                            self.all.add(r);
                        }
                    }
                }
            }
            // Clear only above the bounds: a smooth day brighter than any clear sky the bounds
            // allow (an overcast can be smooth, never that bright).
            if !verdict.window_clear
                && let Some(f) = self.detector.fitted_clear_window()
                && f.alpha * working > self.bounds.max
            {
                #[allow(clippy::cast_possible_truncation)] // at most 64
                let newly = f.newly_clear as u32;
                self.bright_readings = self.bright_readings.saturating_add(newly);
            }
            let b = &mut self.bands[band];
            if b.days == 0 && b.count >= 3 {
                b.provisional = Some(b.median());
            }
            if self.all.count >= 3 {
                self.all.provisional = Some(self.all.median());
            }
        }
        Calibrated {
            factor: self.factor(o.sun_elevation_deg),
            verdict,
            status: self.status(),
        }
    }

    /// The factor the detector's clear sky is scaled by: the learned one where the sun's band
    /// has a clear day; else the running median of the band's clear readings so far; else
    /// that of all bands' (pvlib's refitted α, band by band); 1 before any clear reading.
    fn working_factor(&self, elevation_deg: f32) -> f32 {
        let own = band_of(elevation_deg).map(|b| &self.bands[b]);
        match own {
            Some(b) if b.days > 0 => self.factor(elevation_deg),
            Some(Band {
                provisional: Some(l),
                ..
            }) => math::exp_libm(*l),
            _ => self
                .all
                .provisional
                .map_or_else(|| self.factor(elevation_deg), math::exp_libm),
        }
    }

    /// The longitude as seconds of mean solar time ahead of UTC.
    #[allow(clippy::cast_possible_truncation)] // within ±43,200
    fn longitude_seconds(&self) -> i64 {
        i64::from((self.longitude_deg * 240.0) as i32)
    }

    fn clear_day_data(&mut self) {
        for b in &mut self.bands {
            b.clear_day();
        }
        self.bright_readings = 0;
        self.day_all.clear_day();
        self.detector.reset();
    }

    /// Ends the day: a clear day's medians join their bands' histories.
    fn close_day(&mut self) {
        let minutes =
            |count: u32| u64::from(count) * u64::from(self.detector.interval_seconds()) / 60;
        if minutes(self.bright_readings) >= u64::from(MIN_CLEAR_MINUTES) {
            self.bright = true;
        }
        if minutes(self.day_all.count) >= u64::from(MIN_CLEAR_MINUTES) {
            for b in &mut self.bands {
                if minutes(b.count) >= u64::from(MIN_BAND_MINUTES) {
                    let m = b.median();
                    b.keep(m);
                }
            }
            self.clear_days = self.clear_days.saturating_add(1);
            if self.commissioned.is_none() && usize::from(self.clear_days) >= DAYS_KEPT {
                self.commissioned = self.level();
            }
        }
        self.clear_day_data();
    }

    /// The learned state in [`STATE_BYTES`] bytes, little-endian: magic 0x5C, version
    /// [`STATE_VERSION`], the bands' numbers of clear-day medians kept (2 bits each, the
    /// lowest band in the lowest bits), a flag byte (bit 0: commissioned; bit 1: a bright day
    /// seen; an estimator of before bit 1 refuses a state with it), the clear days
    /// counted (u16), the commissioned level, the four bands' three medians each (each ln ×
    /// 8192 as i16), and a CRC-16/CCITT-FALSE of the first 34 bytes. The day in progress is not
    /// kept.
    #[must_use]
    pub fn to_bytes(&self) -> [u8; STATE_BYTES] {
        let mut b = [0u8; STATE_BYTES];
        b[0] = STATE_MAGIC;
        b[1] = STATE_VERSION;
        for (i, band) in self.bands.iter().enumerate() {
            #[allow(clippy::cast_possible_truncation)] // at most 3
            {
                b[2] |= (band.days as u8) << (2 * i);
            }
        }
        b[3] = u8::from(self.commissioned.is_some()) | u8::from(self.bright) << 1;
        b[4..6].copy_from_slice(&self.clear_days.to_le_bytes());
        let q = |l: f32| -> [u8; 2] {
            #[allow(clippy::cast_possible_truncation)] // clamped to i16
            let v = libm::roundf(l * LN_SCALE).clamp(-32_767.0, 32_767.0) as i16;
            v.to_le_bytes()
        };
        b[6..8].copy_from_slice(&q(self.commissioned.unwrap_or(0.0)));
        for (i, band) in self.bands.iter().enumerate() {
            for j in 0..DAYS_KEPT {
                let v = if j < band.days { band.history[j] } else { 0.0 };
                let at = 8 + 6 * i + 2 * j;
                b[at..at + 2].copy_from_slice(&q(v));
            }
        }
        let crc = crc16(&b[..STATE_BYTES - 2]);
        b[STATE_BYTES - 2..].copy_from_slice(&crc.to_le_bytes());
        b
    }

    /// An estimator with the learned state `bytes` ([`SelfCalibration::to_bytes`]) and the
    /// detector and bounds of [`SelfCalibration::new`]. The state is checked before it is
    /// trusted: its length, magic byte, version, checksum, flags and levels (each within
    /// ln 0.4 to ln 2.5); a state that fails any check is refused, not used.
    ///
    /// # Errors
    /// [`SkyError::OutOfRange`] naming what is wrong with the state (`calibration state
    /// length [bytes]`, `… magic byte`, `… version`, `… checksum`, `… flags`, `… level`), or
    /// [`SelfCalibration::new`]'s.
    pub fn from_bytes(
        bytes: &[u8],
        criteria: Criteria,
        interval_seconds: u32,
        longitude_deg: f32,
        bounds: Bounds,
    ) -> Result<Self, SkyError> {
        let refuse = |parameter, value: f32, min: f32, max: f32| SkyError::OutOfRange {
            parameter,
            value,
            min,
            max,
        };
        #[allow(clippy::cast_precision_loss)]
        if bytes.len() != STATE_BYTES {
            return Err(refuse(
                "calibration state length [bytes]",
                bytes.len() as f32,
                STATE_BYTES as f32,
                STATE_BYTES as f32,
            ));
        }
        let exactly = |parameter, value: u8, want: u8| {
            if value == want {
                Ok(())
            } else {
                Err(refuse(
                    parameter,
                    f32::from(value),
                    f32::from(want),
                    f32::from(want),
                ))
            }
        };
        exactly("calibration state magic byte", bytes[0], STATE_MAGIC)?;
        exactly("calibration state version", bytes[1], STATE_VERSION)?;
        let crc = crc16(&bytes[..STATE_BYTES - 2]);
        let stored = u16::from_le_bytes([bytes[STATE_BYTES - 2], bytes[STATE_BYTES - 1]]);
        if crc != stored {
            return Err(refuse(
                "calibration state checksum",
                f32::from(stored),
                f32::from(crc),
                f32::from(crc),
            ));
        }
        if bytes[3] > 3 {
            return Err(refuse(
                "calibration state flags",
                f32::from(bytes[3]),
                0.0,
                3.0,
            ));
        }
        let (lo, hi) = ln_range();
        let level = |at: usize| -> Result<f32, SkyError> {
            let l = f32::from(i16::from_le_bytes([bytes[at], bytes[at + 1]])) / LN_SCALE;
            if (lo - 1e-3..=hi + 1e-3).contains(&l) {
                Ok(l)
            } else {
                Err(refuse(
                    "calibration state level",
                    math::exp_libm(l),
                    HISTOGRAM_RANGE.0,
                    HISTOGRAM_RANGE.1,
                ))
            }
        };
        let mut s = Self::new(criteria, interval_seconds, longitude_deg, bounds)?;
        for (i, band) in s.bands.iter_mut().enumerate() {
            band.days = usize::from((bytes[2] >> (2 * i)) & 3).min(DAYS_KEPT);
            for j in 0..band.days {
                band.history[j] = level(8 + 6 * i + 2 * j)?;
            }
        }
        s.clear_days = u16::from_le_bytes([bytes[4], bytes[5]]);
        s.commissioned = if bytes[3] & 1 == 1 {
            Some(level(6)?)
        } else {
            None
        };
        s.bright = bytes[3] & 2 == 2;
        Ok(s)
    }
}

/// CRC-16/CCITT-FALSE (polynomial 0x1021, initial 0xFFFF), bitwise: no table.
fn crc16(bytes: &[u8]) -> u16 {
    let mut crc: u16 = 0xFFFF;
    for &b in bytes {
        crc ^= u16::from(b) << 8;
        for _ in 0..8 {
            crc = if crc & 0x8000 != 0 {
                (crc << 1) ^ 0x1021
            } else {
                crc << 1
            };
        }
    }
    crc
}

#[cfg(test)]
mod tests {
    use super::*;

    /// CRC-16/CCITT-FALSE's check value for "123456789" is 0x29B1 (the catalogue's).
    #[test]
    fn crc_matches_the_catalogue_check_value() {
        assert_eq!(crc16(b"123456789"), 0x29B1);
    }

    /// Rewrites a state's checksum after a test has changed it (a well-formed state).
    fn reseal(b: &mut [u8; STATE_BYTES]) {
        let crc = crc16(&b[..STATE_BYTES - 2]).to_le_bytes();
        b[STATE_BYTES - 2..].copy_from_slice(&crc);
    }

    /// The site's longitude in these tests, degrees east.
    const LONGITUDE: f32 = 7.0;

    /// Days of a clear-sky curve at [`LONGITUDE`], one per `(gain, horizon_deg)`: the sensor
    /// reading `gain` times the clear sky with the sun above `horizon_deg` and 0 below (an
    /// obstructed horizon); the calibration after them.
    fn days(bounds: Bounds, days: &[(f32, f32)]) -> SelfCalibration {
        let mut cal =
            SelfCalibration::new(Criteria::RENO_HANSEN_2016, 60, LONGITUDE, bounds).expect("new");
        for (day, &(gain, horizon_deg)) in (0_i64..).zip(days) {
            for minute in day * 1440..(day + 1) * 1440 {
                #[allow(clippy::cast_precision_loss)]
                let hours = (minute % 1440) as f32 / 60.0;
                let elevation = 65.0 * math::sin(core::f32::consts::PI * (hours - 5.5) / 13.0);
                let clear = 1000.0 * math::powf(math::sin(elevation.max(0.0).to_radians()), 1.2);
                let measured = if elevation > horizon_deg {
                    gain * clear
                } else {
                    0.0
                };
                let _ = cal.update(&Observation {
                    seconds: 60 * minute,
                    sun_elevation_deg: elevation,
                    measured,
                    clear,
                });
            }
        }
        cal
    }

    /// Five days at one gain and horizon ([`days`]).
    fn clear_days(bounds: Bounds, gain: f32, horizon_deg: f32) -> SelfCalibration {
        days(bounds, &[(gain, horizon_deg); 5])
    }

    #[test]
    fn a_day_clear_only_above_the_bounds_is_flagged_and_kept() {
        // 80 % high (a wrong sensitivity constant), the horizon obstructed below 20°: beyond the
        // detector's mean criterion (75 W/m²) wherever the sensor sees the sun, so nothing is
        // learned; but clear at its own factor 1.8, above the bounds: bright days.
        let cal = clear_days(Bounds::DEFAULT, 1.8, 20.0);
        assert_eq!((cal.level_unbounded(), cal.bright), (None, true));
        assert_eq!(cal.status(), Status::SensorSuspect);
        assert!((cal.factor(40.0) - 1.0).abs() < 1e-6);
        // One such day is enough: its bright minutes are counted like clear ones (each reading
        // once), about 8 hours with the sun above 20°.
        let one = days(Bounds::DEFAULT, &[(1.8, 20.0), (0.0, 90.0)]);
        assert!(one.bright);
        // 30 % high is within the bounds: not bright, nothing learned, not flagged.
        let within = clear_days(Bounds::DEFAULT, 1.3, 20.0);
        assert_eq!((within.bright, within.status()), (false, Status::Learning));
        // Bounds of 0.8 to 1.2 make the same days bright.
        let narrow = Bounds {
            min: 0.8,
            max: 1.2,
            drift: 0.08,
        };
        assert_eq!(
            clear_days(narrow, 1.3, 20.0).status(),
            Status::SensorSuspect
        );
        // With the low sun in view the sensor is still beyond the detector's reach above about
        // 8° (the mean criterion at 80 % high): nothing learned, flagged by its bright days.
        let seen = clear_days(Bounds::DEFAULT, 1.8, 0.0);
        assert_eq!((seen.level_unbounded(), seen.bright), (None, true));
        // A sensor within the bounds and the detector's reach is never flagged.
        assert_eq!(clear_days(narrow, 1.1, 20.0).status(), Status::Calibrated);
        // The flag holds whatever the days after it: here three clear days within the bounds
        // (a level learned, otherwise `calibrated`).
        let after = days(
            Bounds::DEFAULT,
            &[(1.8, 20.0), (1.0, 0.0), (1.0, 0.0), (1.0, 0.0), (1.0, 0.0)],
        );
        assert!(
            after
                .level_unbounded()
                .is_some_and(|l| (l - 1.0).abs() < 0.02)
        );
        assert_eq!(after.status(), Status::SensorSuspect);
        // The flag survives a restart, and a recommissioning forgets it.
        let load = |b: &[u8]| {
            SelfCalibration::from_bytes(
                b,
                Criteria::RENO_HANSEN_2016,
                60,
                LONGITUDE,
                Bounds::DEFAULT,
            )
        };
        let mut back = load(&cal.to_bytes()).expect("its own state");
        assert_eq!(back.status(), Status::SensorSuspect);
        back.recommission();
        assert_eq!(back.status(), Status::Learning);
        let mut back = load(&after.to_bytes()).expect("its own state");
        assert_eq!(back.status(), Status::SensorSuspect);
        back.recommission();
        assert_eq!(back.status(), Status::Calibrated);
        // A flag byte with an unknown bit is refused.
        let mut b = cal.to_bytes();
        b[3] |= 4;
        reseal(&mut b);
        assert!(matches!(
            load(&b),
            Err(SkyError::OutOfRange {
                parameter: "calibration state flags",
                ..
            })
        ));
    }

    /// A learned state survives the round trip through its bytes; a changed byte, length,
    /// version or level is refused, not trusted.
    #[test]
    fn state_round_trips_and_corruption_is_refused() {
        let new =
            || SelfCalibration::new(Criteria::RENO_HANSEN_2016, 60, LONGITUDE, Bounds::DEFAULT);
        let cal = clear_days(Bounds::DEFAULT, 0.93, 0.0);
        assert!(
            (cal.factor(40.0) - 0.93).abs() < 0.01,
            "{}",
            cal.factor(40.0)
        );
        assert_eq!(cal.status(), Status::Calibrated);
        let bytes = cal.to_bytes();
        let load = |b: &[u8]| {
            SelfCalibration::from_bytes(
                b,
                Criteria::RENO_HANSEN_2016,
                60,
                LONGITUDE,
                Bounds::DEFAULT,
            )
        };
        let back = load(&bytes).expect("its own state");
        for e in [10.0, 15.0, 30.0, 45.0, 70.0] {
            assert!((back.factor(e) - cal.factor(e)).abs() < 2e-4);
        }
        assert_eq!(back.status(), cal.status());
        assert_eq!(back.clear_days(), cal.clear_days());
        for i in 0..STATE_BYTES {
            for bit in 0..8 {
                let mut b = bytes;
                b[i] ^= 1 << bit;
                assert!(load(&b).is_err(), "byte {i} bit {bit}");
            }
        }
        assert!(load(&bytes[..STATE_BYTES - 1]).is_err());
        // A well-formed state of another version, or with a level out of range, is refused.
        let mut b = bytes;
        b[1] = 2;
        reseal(&mut b);
        assert!(matches!(
            load(&b),
            Err(SkyError::OutOfRange {
                parameter: "calibration state version",
                ..
            })
        ));
        let mut b = bytes;
        b[8..10].copy_from_slice(&i16::MAX.to_le_bytes());
        reseal(&mut b);
        assert!(matches!(
            load(&b),
            Err(SkyError::OutOfRange {
                parameter: "calibration state level",
                ..
            })
        ));
        // A fresh estimator's state loads as nothing learned.
        let fresh = load(&new().expect("new").to_bytes()).expect("fresh");
        assert_eq!(
            (fresh.factor(30.0), fresh.status()),
            (1.0, Status::Learning)
        );
    }

    /// Unix seconds of known instants (the Unix epoch; 2000-01-01; a leap day).
    #[test]
    fn unix_seconds_of_known_instants() {
        let t = |y, mo, d, h, mi| unix_seconds(&UtcTime::new(y, mo, d, h, mi, 0.0).expect("valid"));
        assert_eq!(t(1970, 1, 1, 0, 0), 0);
        assert_eq!(t(2000, 1, 1, 0, 0), 946_684_800);
        assert_eq!(t(2016, 2, 29, 12, 30), 1_456_749_000);
        assert_eq!(t(1969, 12, 31, 23, 59), -60);
    }
}
