//! Clear periods in a series of global horizontal irradiance: the five criteria of Reno &
//! Hansen, *Identification of periods of clear sky irradiance in time series of GHI
//! measurements* (Renewable Energy 90, 2016, 520–531), as pvlib's `clearsky.detect_clearsky`
//! applies them, in a fixed-capacity sliding window (no allocation).
//!
//! Over a window of `n` successive readings (10 minutes of 1-minute data by default), the
//! measured series `m` and the clear sky's series `c` (both W/m², the interval `Δt` in minutes)
//! are compared (Reno & Hansen's eqs. 6–14; pvlib's parameter names):
//!
//! 1. mean: |mean m − mean c| < `mean_diff` (eq. 6);
//! 2. maximum: |max m − max c| < `max_diff` (eq. 7);
//! 3. line length: `lower_line_length` < L(m) − L(c) < `upper_line_length`, with
//!    L(x) = Σ √((x_{i+1} − x_i)² + Δt²) (eq. 8);
//! 4. variability: σ(s) / mean m < `var_diff`, s_i = (m_{i+1} − m_i) / Δt the slopes, σ the
//!    sample standard deviation (n − 1 in the denominator) of the n − 1 slopes, the mean over
//!    all n readings (eqs. 9–11, pvlib's reading of eq. 11);
//! 5. largest change of the difference: max |(m_{i+1} − c_{i+1}) − (m_i − c_i)| < `slope_dev`
//!    (eqs. 12–14);
//!
//! and the clear sky's mean is not 0. A window meeting all of them is clear, and so is every
//! reading in it: a reading is clear when any window holding it is clear (pvlib's verdict). The
//! window here ends at the newest reading, so a reading is known clear at the latest
//! `n − 1` readings after it ([`Verdict::newly_clear`]).
//!
//! **Differences from pvlib**: pvlib rescales the clear sky by a factor α fitted to the clear
//! readings and repeats (up to 20 times); here the clear sky is compared as given (pvlib with
//! `max_iterations=1`): the factor is the business of [`crate::self_calibration`], which feeds
//! the detector its learned clear-sky level. [`ClearSkyDetector::fitted_clear_window`] judges a
//! window once more against the clear sky times α fitted to that window alone (the
//! self-calibration's test for a sensor reading far too high). pvlib refuses a series with
//! unequal intervals; here a reading that does not follow the one before by the interval
//! (within a quarter of it), or a reading that is not finite, starts a new window. Sums are in
//! f32.
//!
//! **Intervals**: [`Criteria::RENO_HANSEN_2016`] are the paper's thresholds for 1-minute data
//! (a 10-minute window). [`Criteria::jordan_hansen_2023`] interpolates the thresholds of Jordan
//! & Hansen, *Clear-sky detection for PV degradation analysis using multiple regression*
//! (Renewable Energy 209, 2023, Table 1; pvlib's `infer_limits=True`) for intervals of 1 to
//! 30 minutes (windows of 50 to 120 minutes). A window holds at least 3 and at most
//! [`WINDOW_CAPACITY`] readings.
//!
//! **Agreement with pvlib**: `tests/tests/self_calibration.rs` runs both on the same measured
//! series (BSRN Payerne, a month of 1-minute GHI, and NREL's Golden 5-minute GHI) against the
//! same clear sky; the figures are in `docs/weather.md` ("Self-calibration").

use crate::error::SkyError;
use crate::math;

/// The most readings a window holds (50 minutes of 1-minute data under
/// [`Criteria::jordan_hansen_2023`] is the longest window its table asks for).
pub const WINDOW_CAPACITY: usize = 64;

/// The thresholds of the five criteria (module docs), in W/m², minutes and their ratios.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Criteria {
    /// The window's length, minutes.
    pub window_minutes: f32,
    /// Largest difference of the means, W/m² (eq. 6).
    pub mean_diff: f32,
    /// Largest difference of the maxima, W/m² (eq. 7).
    pub max_diff: f32,
    /// Lower limit of the line length's difference (eq. 8).
    pub lower_line_length: f32,
    /// Upper limit of the line length's difference (eq. 8).
    pub upper_line_length: f32,
    /// Largest standard deviation of the slopes over the mean, 1/minute (eqs. 9–11).
    pub var_diff: f32,
    /// Largest change of the difference between successive readings, W/m² (eqs. 12–14).
    pub slope_dev: f32,
}

impl Criteria {
    /// Reno & Hansen 2016's thresholds for 1-minute data (pvlib's defaults): a 10-minute
    /// window, means and maxima within 75 W/m², line length −5 to 10, variability 0.005,
    /// change 8 W/m².
    pub const RENO_HANSEN_2016: Self = Self {
        window_minutes: 10.0,
        mean_diff: 75.0,
        max_diff: 75.0,
        lower_line_length: -5.0,
        upper_line_length: 10.0,
        var_diff: 0.005,
        slope_dev: 8.0,
    };

    /// Jordan & Hansen 2023's thresholds (Table 1, for 1, 5, 15 and 30-minute data) linearly
    /// interpolated at `interval_minutes`, as pvlib's `infer_limits=True` does: window 50, 60, 90,
    /// 120 minutes; mean 75; max 60, 65, 75, 90; line length −45 to 80; variability 0.005, 0.01,
    /// 0.032, 0.07; change 50, 60, 75, 96.
    ///
    /// # Errors
    /// [`SkyError::OutOfRange`] for an interval outside 1 to 30 minutes (or NaN).
    pub fn jordan_hansen_2023(interval_minutes: f32) -> Result<Self, SkyError> {
        let t = crate::error::check_range("sample interval [min]", interval_minutes, 1.0, 30.0)?;
        const AT: [f32; 4] = [1.0, 5.0, 15.0, 30.0];
        let interp = |v: [f32; 4]| {
            let i = if t < AT[1] {
                0
            } else if t < AT[2] {
                1
            } else {
                2
            };
            v[i] + (v[i + 1] - v[i]) * (t - AT[i]) / (AT[i + 1] - AT[i])
        };
        Ok(Self {
            window_minutes: interp([50.0, 60.0, 90.0, 120.0]),
            mean_diff: 75.0,
            max_diff: interp([60.0, 65.0, 75.0, 90.0]),
            lower_line_length: -45.0,
            upper_line_length: 80.0,
            var_diff: interp([0.005, 0.01, 0.032, 0.07]),
            slope_dev: interp([50.0, 60.0, 75.0, 96.0]),
        })
    }
}

/// What one reading told the detector.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Verdict {
    /// The window ending at this reading met every criterion.
    pub window_clear: bool,
    /// How many of the newest readings (this one and the ones before it) have just become
    /// known clear: those of a clear window not already in an earlier clear window (0 to the
    /// window's length).
    pub newly_clear: usize,
}

/// A window clear against the clear sky times its own least-squares factor
/// ([`ClearSkyDetector::fitted_clear_window`]).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct FittedWindow {
    /// The window's factor α = Σ m c / Σ c² (measured over clear sky, least squares).
    pub alpha: f32,
    /// How many of the newest readings have just become known clear at their window's own
    /// factor: those not already in an earlier such window or a clear one (0 to the window's
    /// length), as [`Verdict::newly_clear`] counts them.
    pub newly_clear: usize,
}

/// The sliding-window detector (module docs): readings in, a verdict per reading out.
#[derive(Debug, Clone, PartialEq)]
pub struct ClearSkyDetector {
    criteria: Criteria,
    interval_seconds: u32,
    window: usize,
    measured: [f32; WINDOW_CAPACITY],
    clear: [f32; WINDOW_CAPACITY],
    /// Index of the next slot to write.
    head: usize,
    /// Readings in the current run of evenly spaced readings.
    run: usize,
    /// The time of the last reading, seconds.
    last: Option<i64>,
    /// How many of the newest readings of the run are not yet known clear.
    unmarked: usize,
    /// The same for windows clear at their own factor ([`Self::fitted_clear_window`]).
    fitted_unmarked: usize,
}

impl ClearSkyDetector {
    /// A detector for readings every `interval_seconds` seconds, by `criteria`; the window
    /// holds `criteria.window_minutes / interval` readings, rounded down (as pvlib does).
    ///
    /// ```
    /// use sky_core::clear_period::{ClearSkyDetector, Criteria};
    ///
    /// let mut d = ClearSkyDetector::new(Criteria::RENO_HANSEN_2016, 60)?;
    /// let mut clear_minutes = 0;
    /// for minute in 0..30 {
    ///     let clear_sky = 600.0 + 2.0 * minute as f32;       // W/m², a rising sun
    ///     let reading = 0.98 * clear_sky;                    // a clear sensor, 2 % low
    ///     clear_minutes += d.push(60 * minute, reading, clear_sky).newly_clear;
    /// }
    /// assert_eq!(clear_minutes, 30);
    /// # Ok::<(), sky_core::SkyError>(())
    /// ```
    ///
    /// # Errors
    /// [`SkyError::OutOfRange`] for an interval of 0 or above a day, or a window of fewer than
    /// 3 or more than [`WINDOW_CAPACITY`] readings; [`SkyError::NotFinite`] for a criterion that
    /// is not finite.
    pub fn new(criteria: Criteria, interval_seconds: u32) -> Result<Self, SkyError> {
        #[allow(clippy::cast_precision_loss)] // at most 86,400
        let interval = crate::error::check_range(
            "sample interval [s]",
            interval_seconds as f32,
            1.0,
            86_400.0,
        )?;
        let c = criteria;
        for (parameter, v) in [
            ("window length [min]", c.window_minutes),
            ("mean_diff [W/m2]", c.mean_diff),
            ("max_diff [W/m2]", c.max_diff),
            ("lower_line_length", c.lower_line_length),
            ("upper_line_length", c.upper_line_length),
            ("var_diff [1/min]", c.var_diff),
            ("slope_dev [W/m2]", c.slope_dev),
        ] {
            if !v.is_finite() {
                return Err(SkyError::NotFinite { parameter });
            }
        }
        let samples = math::floor(c.window_minutes * 60.0 / interval);
        #[allow(clippy::cast_precision_loss)]
        crate::error::check_range("readings per window", samples, 3.0, WINDOW_CAPACITY as f32)?;
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)] // 3 to 64
        let window = samples as usize;
        Ok(Self {
            criteria,
            interval_seconds,
            window,
            measured: [0.0; WINDOW_CAPACITY],
            clear: [0.0; WINDOW_CAPACITY],
            head: 0,
            run: 0,
            last: None,
            unmarked: 0,
            fitted_unmarked: 0,
        })
    }

    /// The criteria.
    #[must_use]
    pub fn criteria(&self) -> Criteria {
        self.criteria
    }

    /// Readings per window.
    #[must_use]
    pub fn window(&self) -> usize {
        self.window
    }

    /// The interval between readings, seconds.
    #[must_use]
    pub fn interval_seconds(&self) -> u32 {
        self.interval_seconds
    }

    /// Forgets the readings (the next one starts a new window).
    pub fn reset(&mut self) {
        self.run = 0;
        self.unmarked = 0;
        self.fitted_unmarked = 0;
        self.last = None;
    }

    /// The reading `age` readings back (0 the newest) of the current run: (measured, clear
    /// sky), W/m²; `None` beyond the run or the window's capacity.
    #[must_use]
    pub fn reading(&self, age: usize) -> Option<(f32, f32)> {
        if age >= self.run.min(WINDOW_CAPACITY) {
            return None;
        }
        let i = (self.head + WINDOW_CAPACITY - 1 - age) % WINDOW_CAPACITY;
        Some((self.measured[i], self.clear[i]))
    }

    /// Adds the reading `measured` with the clear sky's `clear` (both global horizontal
    /// irradiance, W/m²) at `seconds` (any epoch, increasing) and judges the window ending
    /// there. A reading not one interval (within a quarter of it) after the one before, or a
    /// measured or clear value that is not finite, starts a new window (a non-finite one is
    /// not kept).
    pub fn push(&mut self, seconds: i64, measured: f32, clear: f32) -> Verdict {
        if !(measured.is_finite() && clear.is_finite()) {
            self.reset();
            return Verdict::default();
        }
        let step = i64::from(self.interval_seconds);
        let evenly = self
            .last
            .is_some_and(|t| (seconds.saturating_sub(t) - step).abs() * 4 <= step);
        if !evenly {
            self.run = 0;
            self.unmarked = 0;
            self.fitted_unmarked = 0;
        }
        self.last = Some(seconds);
        self.measured[self.head] = measured;
        self.clear[self.head] = clear;
        self.head = (self.head + 1) % WINDOW_CAPACITY;
        self.run = self.run.saturating_add(1);
        self.unmarked = (self.unmarked + 1).min(self.window);
        self.fitted_unmarked = (self.fitted_unmarked + 1).min(self.window);
        if self.run < self.window || !self.criteria_met(1.0) {
            return Verdict::default();
        }
        let newly_clear = self.unmarked;
        self.unmarked = 0;
        self.fitted_unmarked = 0;
        Verdict {
            window_clear: true,
            newly_clear,
        }
    }

    /// Whether the newest window is clear against the clear sky scaled by its own
    /// least-squares factor α = Σ m c / Σ c² (Reno & Hansen's α, as pvlib refits it, but fitted
    /// to this window alone): the factor and the readings it newly covers when every criterion
    /// holds against α c (they are then counted, as [`Self::push`] counts a clear window's);
    /// `None` when a criterion fails, when α is not finite and positive, or before the run
    /// fills a window. A smooth overcast also passes at a small α, so only an α above what a
    /// clear sky can give tells something (a sensor reading high: [`crate::self_calibration`]).
    pub fn fitted_clear_window(&mut self) -> Option<FittedWindow> {
        if self.run < self.window {
            return None;
        }
        let (mut mc, mut cc) = (0.0f32, 0.0f32);
        for k in 0..self.window {
            let (m, c) = self.at(k);
            mc += m * c;
            cc += c * c;
        }
        let alpha = mc / cc;
        if !(alpha.is_finite() && alpha > 0.0 && self.criteria_met(alpha)) {
            return None;
        }
        let newly_clear = self.fitted_unmarked;
        self.fitted_unmarked = 0;
        Some(FittedWindow { alpha, newly_clear })
    }

    /// The `k`-th of the newest `window` readings, oldest first: (measured, clear sky).
    fn at(&self, k: usize) -> (f32, f32) {
        let i = (self.head + WINDOW_CAPACITY - self.window + k) % WINDOW_CAPACITY;
        (self.measured[i], self.clear[i])
    }

    /// The five criteria over the newest `window` readings (module docs), the clear sky
    /// scaled by `alpha`.
    #[allow(clippy::cast_precision_loss)] // at most 64 readings
    fn criteria_met(&self, alpha: f32) -> bool {
        let c = &self.criteria;
        let n = self.window;
        let dt = self.interval_seconds as f32 / 60.0;
        let at = |k: usize| {
            let (m, cs) = self.at(k);
            (m, alpha * cs)
        };
        let (mut sum_m, mut sum_c) = (0.0f32, 0.0f32);
        let (mut max_m, mut max_c) = (f32::NEG_INFINITY, f32::NEG_INFINITY);
        let (mut len_m, mut len_c) = (0.0f32, 0.0f32);
        let (mut sum_slope, mut max_change) = (0.0f32, 0.0f32);
        for k in 0..n {
            let (m, cs) = at(k);
            sum_m += m;
            sum_c += cs;
            max_m = max_m.max(m);
            max_c = max_c.max(cs);
            if k > 0 {
                let (m0, c0) = at(k - 1);
                let (dm, dc) = (m - m0, cs - c0);
                len_m += math::sqrt(dm * dm + dt * dt);
                len_c += math::sqrt(dc * dc + dt * dt);
                sum_slope += dm / dt;
                max_change = max_change.max(libm::fabsf(dm - dc));
            }
        }
        let mean_m = sum_m / n as f32;
        let mean_c = sum_c / n as f32;
        if mean_c == 0.0 {
            return false;
        }
        let mean_slope = sum_slope / (n - 1) as f32;
        let mut var = 0.0f32;
        for k in 1..n {
            let s = (at(k).0 - at(k - 1).0) / dt - mean_slope;
            var += s * s;
        }
        let nstd = math::sqrt(var / (n - 2) as f32) / mean_m;
        let line = len_m - len_c;
        libm::fabsf(mean_m - mean_c) < c.mean_diff
            && libm::fabsf(max_m - max_c) < c.max_diff
            && line > c.lower_line_length
            && line < c.upper_line_length
            && nstd < c.var_diff
            && max_change < c.slope_dev
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A rising clear sky, W/m², at minute `i`.
    fn clear(i: i64) -> f32 {
        #[allow(clippy::cast_precision_loss)]
        let t = i as f32;
        500.0 + 3.0 * t
    }

    #[test]
    fn a_window_is_clear_at_its_own_factor() {
        let mut d = ClearSkyDetector::new(Criteria::RENO_HANSEN_2016, 60).expect("detector");
        for i in 0..30 {
            let v = d.push(60 * i, 1.4 * clear(i), clear(i));
            // 40 % above the clear sky: 200 W/m² and more from it, never clear at the factor 1.
            assert!(!v.window_clear);
            let fitted = d.fitted_clear_window();
            if i < 9 {
                // The window (10 readings) is not full yet.
                assert_eq!(fitted, None);
            } else {
                let f = fitted.expect("clear at its own factor");
                assert!((f.alpha - 1.4).abs() < 1e-5, "{}", f.alpha);
                // The first window covers its 10 readings, each later one the newest.
                assert_eq!(f.newly_clear, if i == 9 { 10 } else { 1 });
            }
        }
        // A cloud's dip in the window: not clear at any factor.
        let mut d = ClearSkyDetector::new(Criteria::RENO_HANSEN_2016, 60).expect("detector");
        for i in 0..10 {
            let dip = if i == 5 { 0.5 } else { 1.0 };
            let _ = d.push(60 * i, 1.4 * dip * clear(i), clear(i));
        }
        assert_eq!(d.fitted_clear_window(), None);
        // A clear sky of 0 has no factor.
        let mut d = ClearSkyDetector::new(Criteria::RENO_HANSEN_2016, 60).expect("detector");
        for i in 0..10 {
            let _ = d.push(60 * i, 10.0, 0.0);
        }
        assert_eq!(d.fitted_clear_window(), None);
    }
}
