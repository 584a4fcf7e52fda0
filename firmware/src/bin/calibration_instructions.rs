//! Executed instructions per calibrated controller step, counted by the emulator.
//!
//! Run under qemu with `-icount shift=N,align=off,sleep=off` (as `scripts/cross.sh
//! instructions` does; the counter, `src/counter.rs`, is `controller-instructions`'s). Over
//! every step of the weather controller's series (`src/weather.rs`: four days of readings every
//! 10 minutes, three clear, the restart before the fourth), this counts
//! `sky_core::controller::step_calibrated` as a whole and the self-calibration's parts of it
//! called one by one as it calls them: the factor at the sun's elevation
//! (`SelfCalibration::factor`), the clear sky's irradiance the reading is compared with
//! (`controller::clear_sky_irradiance`) and the estimator's update (`SelfCalibration::update`,
//! the clear-period detector's window among it), on a copy of the estimator from before the
//! step; the parts' results must equal the whole step's bit for bit (the factor, what the
//! update returns, and the estimator after it). As a peer in the same run, the same reading
//! through `controller::step_with_history` (the step without the calibration). At the restart
//! it counts the state's saving (`to_bytes`) and restoring (`from_bytes`). It prints the
//! minimum, median and maximum over the series, in instructions.

#![no_std]
#![no_main]

use qemu_check::{entry, hprintln};
use sky_core::SkyError;
use sky_core::controller::{
    History, Measurement, clear_sky_irradiance, example_luminaire, step_calibrated,
    step_with_history,
};
use sky_core::self_calibration::{Observation, unix_seconds};
use sky_core::solar::{Site, UtcTime};

// `SITE`, `STEP_MINUTES`, ..., and the series' `SERIES_DATES`, `SERIES_RESTART_DAY` and
// `READINGS`, from build.rs.
include!(concat!(env!("OUT_DIR"), "/controller_config.rs"));
include!(concat!(env!("OUT_DIR"), "/calibrated_series.rs"));

#[path = "../counter.rs"]
mod counter;
#[path = "../weather.rs"]
mod weather;

use counter::{instructions, measure};
use weather::{new_calibration, series_settings};

const _: (u8, f32, f32, (i32, u32, u32)) = (PWM_BITS, AOD, FULL_SCALE_LUX, DATE); // not used here

/// Steps in the series.
const STEPS: usize = READINGS.len();
/// The parts counted: the whole step, the peer, the factor, the clear sky, the update, and
/// the estimator's three together.
const PARTS: usize = 6;

/// Instructions per part of the step, over the series.
struct Counts {
    name: &'static str,
    steps: [u32; STEPS],
}

/// Which steps had the sun above the horizon.
type SunUp = [bool; STEPS];

/// Instructions of the state's saving and restoring at the restart.
#[derive(Default)]
struct Restart {
    to_bytes: u32,
    from_bytes: u32,
}

/// Runs the series and fills `counts` and the restart's; `Ok(false)` if a part's result differs
/// from the whole step's.
#[allow(clippy::cast_possible_truncation)] // degrees, steps of a day
fn run(
    counts: &mut [Counts; PARTS],
    sun_up: &mut SunUp,
    restart: &mut Restart,
    per_instruction: f64,
    empty: u64,
) -> Result<bool, SkyError> {
    let site = Site::new(SITE.0, SITE.1, SITE.2)?;
    let lamp = example_luminaire()?;
    let settings = series_settings();
    let count = |t| instructions(t, per_instruction, empty);
    let mut calibration = new_calibration(None)?;
    let mut history = History::new();
    let steps_per_day = STEPS / SERIES_DATES.len();
    let mut same = true;
    for (index, &m) in READINGS.iter().enumerate() {
        let (day, step_of_day) = (index / steps_per_day, index % steps_per_day);
        if step_of_day == 0 && day == SERIES_RESTART_DAY {
            history = History::new();
            let (t_save, saved) = measure(|| calibration.to_bytes());
            let (t_restore, restored) = measure(|| new_calibration(Some(&saved)));
            calibration = restored?;
            same &= calibration.to_bytes() == saved;
            *restart = Restart {
                to_bytes: count(t_save),
                from_bytes: count(t_restore),
            };
        }
        let (year, month, date) = SERIES_DATES[day];
        let minutes = step_of_day as u32 * STEP_MINUTES;
        let time = UtcTime::new(year, month, date, minutes / 60, minutes % 60, 0.0)?;
        let (before, history_before) = (calibration.clone(), history);
        let (t_step, whole) = measure(|| {
            step_calibrated(
                &time,
                &site,
                &settings,
                &lamp,
                m,
                &mut calibration,
                &mut history,
            )
        });
        let (whole, calibrated) = whole?;
        let (t_peer, peer) = measure(|| {
            step_with_history(
                &time,
                &site,
                &settings,
                &lamp,
                Some(m),
                &mut history_before.clone(),
            )
        });
        peer?;
        // The parts, as step_calibrated calls them, on the estimator from before the step.
        let elevation = whole.sun.elevation_deg() as f32;
        sun_up[index] = elevation > 0.0;
        let (t_factor, factor) = measure(|| before.factor(elevation));
        let (measured, clear_lux) = whole.weather.map_or((0.0, 0.0), |w| {
            (w.global_irradiance, whole.daylight.global().y)
        });
        let (t_clear, clear) = measure(|| {
            clear_sky_irradiance(clear_lux, whole.sun.sun().zenith(), time.day_of_year())
        });
        let observation = Observation {
            seconds: unix_seconds(&time),
            sun_elevation_deg: elevation,
            measured,
            clear,
        };
        let mut updated = before;
        let (t_update, c) = measure(|| updated.update(&observation));
        same &= whole
            .weather
            .is_some_and(|w| w.clear_sky_factor.to_bits() == factor.to_bits())
            && c == calibrated
            && updated == calibration;
        let (factor, clear, update) = (count(t_factor), count(t_clear), count(t_update));
        for (counts, n) in counts.iter_mut().zip([
            count(t_step),
            count(t_peer),
            factor,
            clear,
            update,
            factor + clear + update,
        ]) {
            counts.steps[index] = n;
        }
    }
    Ok(same)
}

/// The least, median and largest of `counts` (sorted in place); zeros if empty.
fn stats(counts: &mut [u32]) -> (u32, u32, u32) {
    counts.sort_unstable();
    let n = counts.len();
    if n == 0 {
        return (0, 0, 0);
    }
    let median = if n % 2 == 0 {
        (counts[n / 2 - 1] + counts[n / 2]) / 2
    } else {
        counts[n / 2]
    };
    (counts[0], median, counts[n - 1])
}

#[entry]
fn main() -> ! {
    let (per_instruction, empty) = counter::start("calibration-instructions");
    let part = |name| Counts {
        name,
        steps: [0; STEPS],
    };
    let mut counts = [
        part("controller::step_calibrated"),
        part("  peer: step_with_history (no calibration)"),
        part("  SelfCalibration::factor"),
        part("  clear_sky_irradiance (the comparison)"),
        part("  SelfCalibration::update"),
        part("  the calibration's parts together"),
    ];
    let mut restart = Restart::default();
    let mut sun_up = [false; STEPS];
    let same = match run(
        &mut counts,
        &mut sun_up,
        &mut restart,
        per_instruction,
        empty,
    ) {
        Ok(same) => same,
        Err(error) => {
            hprintln!(
                "calibration-instructions: FAIL: {}",
                qemu_check::Message(error)
            );
            qemu_check::finish(false)
        }
    };
    let daylight = sun_up.iter().filter(|&&up| up).count();
    hprintln!(
        "calibration-instructions: {} steps of {} min ({} days, a restart before day {}; {} with \
         the sun up); executed instructions (qemu -icount, {:.3} counter ticks per instruction)",
        STEPS,
        STEP_MINUTES,
        SERIES_DATES.len(),
        SERIES_RESTART_DAY + 1,
        daylight,
        per_instruction
    );
    hprintln!(
        "{:<44} {:>32} {:>32}",
        "part: min / median / max",
        "every step",
        "the sun up"
    );
    let mut medians = [0u32; 2];
    for (i, c) in counts.iter_mut().enumerate() {
        let mut up = [0u32; STEPS];
        let mut n = 0;
        for (&count, _) in c.steps.iter().zip(&sun_up).filter(|(_, up)| **up) {
            up[n] = count;
            n += 1;
        }
        let (all_min, all_median, all_max) = stats(&mut c.steps);
        let (up_min, up_median, up_max) = stats(&mut up[..n]);
        if let Some(m) = medians.get_mut(i) {
            *m = up_median;
        }
        hprintln!(
            "{:<44} {:>10} {:>10} {:>10} {:>10} {:>10} {:>10}",
            c.name,
            all_min,
            all_median,
            all_max,
            up_min,
            up_median,
            up_max
        );
    }
    hprintln!(
        "calibrated step over the step without calibration, the sun up (medians): {:.3}",
        f64::from(medians[0]) / f64::from(medians[1])
    );
    hprintln!(
        "restart: SelfCalibration::to_bytes {} instructions, from_bytes {}",
        restart.to_bytes,
        restart.from_bytes
    );
    if !same {
        hprintln!("calibration-instructions: FAIL: the parts differ from the whole step");
    }
    qemu_check::finish(same)
}
