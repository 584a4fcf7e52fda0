//! The clear-period detector against pvlib's, and the self-calibration on measured multi-day
//! files (`tests/data/selfcal/`, README there; fixtures by `tests/reference/gen_selfcal_fixtures.py`).
//!
//! `cargo test -p sky-tests --test self_calibration -- --nocapture` prints the figures of
//! docs/weather.md ("Self-calibration").

mod common;

use sky_core::clear_period::{ClearSkyDetector, Criteria};
use sky_core::controller::{History, Measurement, Settings, example_luminaire, step_calibrated};
use sky_core::self_calibration::{Bounds, SelfCalibration, Status, unix_seconds};
use sky_core::solar::Site;

/// One row of a fixture.
struct Row {
    utc: String,
    ghi: f32,
    ineichen: f32,
    reno_hansen: bool,
    clear: bool,
}

/// A station's fixture: its site, reading interval and rows, and the controller's settings
/// with the site's clear sky of the month, as `sky-train schedule` takes it by default.
struct Station {
    name: &'static str,
    site: Site,
    interval: u32,
    rows: Vec<Row>,
    settings: Settings,
}

/// The controller's settings at (`lat`, `lon`, `elevation`) in `month`: the site climatology's
/// aerosol optical depth (clamped to the daylight tables' range), ozone column and
/// precipitable water (`sky_train::site`), the rest the defaults.
#[allow(clippy::cast_possible_truncation)]
fn site_settings(lat: f64, lon: f64, elevation: f64, month: u32) -> Settings {
    let m = sky_train::site::site_month(lat, lon, Some(elevation), month).expect("a site");
    let (lo, hi) = sky_core::daylight::OZONE_RANGE_DU;
    Settings {
        aerosol_optical_depth: (m.aod_550 as f32)
            .clamp(sky_core::daylight::MIN_AOD, sky_core::daylight::MAX_AOD),
        ozone_du: (m.ozone_du as f32).clamp(lo, hi),
        precipitable_water: m.water_vapour_cm as f32,
        ..Settings::default()
    }
}

fn station(name: &'static str, lat: f64, lon: f64, elevation: f64, interval: u32) -> Station {
    let path = format!("{}/data/selfcal/{name}.csv", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).expect("the fixture");
    let rows = text
        .lines()
        .filter(|l| !l.starts_with('#') && !l.starts_with("utc"))
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            let n = |i: usize| f[i].parse::<f32>().expect("a number");
            Row {
                utc: f[0].to_owned(),
                ghi: n(1),
                ineichen: n(2),
                reno_hansen: f[3] == "1",
                clear: f[4] == "1",
            }
        })
        .collect::<Vec<Row>>();
    let month = rows[0].utc[5..7].parse().expect("a month");
    Station {
        name,
        site: Site::new(lat, lon, elevation).expect("site"),
        interval,
        rows,
        settings: site_settings(lat, lon, elevation, month),
    }
}

fn stations() -> [Station; 2] {
    [
        station("bsrn-payerne-201606", 46.815, 6.944, 491.0, 60),
        station("nrel-rmis-golden-201902", 39.7407, -105.1686, 1829.0, 300),
    ]
}

fn criteria(interval: u32) -> Criteria {
    if interval == 60 {
        Criteria::RENO_HANSEN_2016
    } else {
        #[allow(clippy::cast_precision_loss)]
        Criteria::jordan_hansen_2023(interval as f32 / 60.0).expect("1-30 min")
    }
}

/// The detector's sample verdicts against pvlib's `detect_clearsky` (`max_iterations=1`) on
/// the same measured GHI and the same clear sky (pvlib's Ineichen), 1-minute BSRN Payerne (15
/// days) and 5-minute NREL Golden (6 days, Jordan & Hansen's thresholds).
#[test]
fn detector_agrees_with_pvlib_on_measured_series() {
    for s in stations() {
        let mut d = ClearSkyDetector::new(criteria(s.interval), s.interval).expect("detector");
        let mut ours = vec![false; s.rows.len()];
        for (i, r) in s.rows.iter().enumerate() {
            let t = unix_seconds(&common::utc(&r.utc));
            let v = d.push(t, r.ghi, r.ineichen);
            for age in 0..v.newly_clear {
                ours[i - age] = true;
            }
        }
        let theirs: Vec<bool> = s.rows.iter().map(|r| r.reno_hansen).collect();
        let both = ours.iter().zip(&theirs).filter(|(a, b)| **a && **b).count();
        let only_ours = ours
            .iter()
            .zip(&theirs)
            .filter(|(a, b)| **a && !**b)
            .count();
        let only_theirs = ours
            .iter()
            .zip(&theirs)
            .filter(|(a, b)| !**a && **b)
            .count();
        let n = s.rows.len();
        #[allow(clippy::cast_precision_loss)]
        let agreement = 1.0 - (only_ours + only_theirs) as f64 / n as f64;
        println!(
            "detector | {} | {n} readings | pvlib clear {} | both {both} | only ours {only_ours} | only pvlib's {only_theirs} | agreement {:.4} %",
            s.name,
            both + only_theirs,
            100.0 * agreement
        );
        let differing: Vec<&str> = s
            .rows
            .iter()
            .zip(ours.iter().zip(&theirs))
            .filter(|(_, (a, b))| a != b)
            .map(|(r, _)| r.utc.as_str())
            .collect();
        println!("detector | {} | differing readings: {differing:?}", s.name);
        assert!(both > 250, "{}: too few clear readings to compare", s.name);
        // At most 0.1 % of the readings, or one window's readings.
        assert!(
            only_ours + only_theirs <= (n / 1000).max(d.window()),
            "{}: {only_ours} + {only_theirs} of {n} readings differ",
            s.name
        );
    }
}

/// Percentiles by the nearest rank of a sorted copy.
fn percentile(v: &[f32], p: f64) -> f32 {
    let mut s = v.to_vec();
    s.sort_by(f32::total_cmp);
    #[allow(
        clippy::cast_possible_truncation,
        clippy::cast_sign_loss,
        clippy::cast_precision_loss
    )]
    let i = ((p * (s.len() - 1) as f64).round() as usize).min(s.len() - 1);
    s[i]
}

/// What a run of the calibration over a station gave.
struct Run {
    /// Per day: (date, factor at 40° elevation after the day, status after the day,
    /// clear-sky indices on the day's clear minutes with the sun above 5°).
    days: Vec<(String, f32, Status, Vec<f32>)>,
    calibration: SelfCalibration,
}

/// Runs `step_calibrated` over the station's readings, each reading `sensor(row, elevation,
/// azimuth, day index)` (the sensor's fault), with `bounds`; a reading the step refuses (a
/// sensor far too high) is skipped.
fn run(s: &Station, bounds: Bounds, sensor: &dyn Fn(&Row, f64, f64, usize) -> f32) -> Run {
    let lamp = example_luminaire().expect("lamp");
    let settings = s.settings;
    #[allow(clippy::cast_possible_truncation)]
    let mut cal = SelfCalibration::new(
        criteria(s.interval),
        s.interval,
        s.site.longitude() as f32,
        bounds,
    )
    .expect("calibration");
    let mut days: Vec<(String, f32, Status, Vec<f32>)> = Vec::new();
    let mut history = History::new();
    for r in &s.rows {
        let time = common::utc(&r.utc);
        let date = r.utc[..10].to_owned();
        if days.last().is_none_or(|d| d.0 != date) {
            days.push((date, 1.0, Status::Learning, Vec::new()));
        }
        let day = days.len() - 1;
        let sun = settings.sun.position(&time, &s.site).expect("sun");
        let reading = sensor(r, sun.elevation_deg(), sun.azimuth_deg(), day);
        let st = match step_calibrated(
            &time,
            &s.site,
            &settings,
            &lamp,
            Measurement::GlobalIrradiance(reading),
            &mut cal,
            &mut history,
        ) {
            Ok((st, _)) => st,
            // A reading above the physical limit (1.5 times the extraterrestrial horizontal
            // irradiance) is refused, as a firmware would skip it: only a high sensor's.
            Err(e) => {
                assert!(reading > 1.5 * r.ghi, "{}: {e}", r.utc);
                continue;
            }
        };
        let w = st.weather.expect("measured");
        let d = days.last_mut().expect("a day");
        if r.clear && sun.elevation_deg() > 5.0 {
            d.3.push(w.clear_sky_index.expect("by day"));
        }
        d.1 = cal.factor(40.0);
        d.2 = cal.status();
    }
    Run {
        days,
        calibration: cal,
    }
}

/// The clear-sky index's median and 5-95 % range over days `from..`.
fn figures(run: &Run, from: usize) -> (usize, f32, f32, f32) {
    let all: Vec<f32> = run.days[from..]
        .iter()
        .flat_map(|d| d.3.iter().copied())
        .collect();
    if all.is_empty() {
        return (0, f32::NAN, f32::NAN, f32::NAN);
    }
    (
        all.len(),
        percentile(&all, 0.5),
        percentile(&all, 0.05),
        percentile(&all, 0.95),
    )
}

/// The first day after which the calibration is no longer learning.
fn converged(run: &Run) -> Option<usize> {
    run.days.iter().position(|d| d.2 != Status::Learning)
}

/// The self-calibration over the measured files as delivered: days to converge, then the
/// clear-sky index on the later days' clear minutes (pvlib's verdict against its Ineichen
/// clear sky, sun above 5°), against the default clear sky without calibration.
#[test]
fn self_calibration_on_measured_days() {
    let as_delivered = |r: &Row, _: f64, _: f64, _: usize| r.ghi;
    for s in stations() {
        let off = run(
            &s,
            Bounds {
                min: 1.0,
                max: 1.0,
                drift: 1.0,
            },
            &as_delivered,
        );
        let on = run(&s, Bounds::DEFAULT, &as_delivered);
        assert!(
            on.days.iter().all(|d| d.2 != Status::SensorSuspect),
            "{}",
            s.name
        );
        for d in &on.days {
            let (n, med) = (d.3.len(), percentile_or_nan(&d.3, 0.5));
            println!(
                "day | {} | {} | clear minutes {n} | index median {med:.3} | factor at 40° {:.3} | {}",
                s.name,
                d.0,
                d.1,
                d.2.name()
            );
        }
        let first = learned(&on).map_or(on.days.len(), |d| d + 1);
        let from = converged(&on).map_or(on.days.len(), |d| d + 1);
        for (what, start) in [
            ("after the first clear day", first),
            ("after calibrated", from),
        ] {
            let (n, med, p5, p95) = figures(&on, start);
            let (_, med0, p50, p950) = figures(&off, start);
            println!(
                "station | {} | {what}: from day {start} | {} later days | clear minutes {n} | calibrated: median {med:.3}, 5-95 % {p5:.3}-{p95:.3} | uncalibrated: median {med0:.3}, 5-95 % {p50:.3}-{p950:.3}",
                s.name,
                on.days.len() - start
            );
        }
        if s.interval != 60 {
            // NREL Golden in winter, 5-minute readings, two clear days of six: with the site's
            // clear sky its clear days are found, and a level is learned after the first one
            // (not `calibrated`: that takes three); the later clear minutes (one day) meet the
            // issue's median, not its 95th percentile (docs/weather.md).
            assert!(on.calibration.level_unbounded().is_some(), "{}", s.name);
            let (n, med, _, _) = figures(&on, first);
            assert!(
                n > 50 && (0.97..=1.03).contains(&med),
                "{}: {n}, {med}",
                s.name
            );
            continue;
        }
        // Issue 24's bounds on the later days' clear minutes, learned on the earlier days.
        let (n, med, p5, p95) = figures(&on, from);
        assert!(from <= 8, "{}: calibrated after day {from}", s.name);
        assert!(n > 1000, "{}: {n} clear minutes", s.name);
        assert!(
            (0.97..=1.03).contains(&med) && p5 >= 0.92 && p95 <= 1.08,
            "{}: median {med}, 5-95 % {p5}-{p95} after calibration",
            s.name
        );
        assert_eq!(on.calibration.status(), Status::Calibrated);
    }
}

/// The first day after which a level has been learned.
fn learned(run: &Run) -> Option<usize> {
    run.days.iter().position(|d| (d.1 - 1.0).abs() > 0.0)
}

fn percentile_or_nan(v: &[f32], p: f64) -> f32 {
    if v.is_empty() {
        f32::NAN
    } else {
        percentile(v, p)
    }
}

/// Degraded sensors on the Payerne month: a shaded morning (the sun east of south and below
/// 25° reads a quarter, the diffuse of an obstruction), a sensor soiled 10 % from the second
/// half on, one miscalibrated +25 % (under the default bounds and under 0.8-1.2), one +70 %
/// and one −40 % from the start: bounded, flagged where a level beyond the bounds is learned or
/// a day is clear only above them, not chased.
#[test]
fn degraded_sensors_stay_bounded_and_are_flagged() {
    let [payerne, _] = stations();
    let bounds = Bounds::DEFAULT;
    let clean = run(&payerne, bounds, &|r, _, _, _| r.ghi);
    let base = clean.calibration.level_unbounded().expect("learned");
    let shaded = run(&payerne, bounds, &|r, el, az, _| {
        if az < 180.0 && el < 25.0 {
            0.25 * r.ghi
        } else {
            r.ghi
        }
    });
    // The days of the second half start at index 6 (21 June).
    let dirty = run(&payerne, bounds, &|r, _, _, day| {
        if day >= 6 { 0.9 * r.ghi } else { r.ghi }
    });
    let high = run(&payerne, bounds, &|r, _, _, _| 1.25 * r.ghi);
    let narrow = Bounds {
        min: 0.8,
        max: 1.2,
        drift: 0.08,
    };
    let high_narrow = run(&payerne, narrow, &|r, _, _, _| 1.25 * r.ghi);
    let very_high = run(&payerne, bounds, &|r, _, _, _| 1.7 * r.ghi);
    let low = run(&payerne, bounds, &|r, _, _, _| 0.6 * r.ghi);
    for (name, r) in [
        ("clean", &clean),
        ("shaded morning", &shaded),
        ("soiled -10 % from 21 June", &dirty),
        ("+25 %", &high),
        ("+25 %, bounds 0.8-1.2", &high_narrow),
        ("+70 %", &very_high),
        ("-40 %", &low),
    ] {
        let c = &r.calibration;
        let level = c.level_unbounded().unwrap_or(f32::NAN); // NaN: nothing learned
        let (_, med, p5, p95) = figures(r, converged(r).map_or(r.days.len(), |d| d + 1));
        let first_flag = r
            .days
            .iter()
            .find(|d| d.2 == Status::SensorSuspect)
            .map_or("never", |d| d.0.as_str());
        println!(
            "sensor | {name} | level {level:.3} ({:+.1} % of the clean sensor's) | {} clear days | factor at 40° {:.3} | {} (sensor-suspect first after {first_flag}) | later clear-sky index median {med:.3}, 5-95 % {p5:.3}-{p95:.3}",
            100.0 * (level / base - 1.0),
            c.clear_days(),
            c.factor(40.0),
            c.status().name()
        );
    }
    let level = |r: &Run| r.calibration.level_unbounded().expect("learned");
    // The shaded morning is not a clear period: the level stays the clean sensor's.
    assert!((level(&shaded) / base - 1.0).abs() < 0.02);
    assert_eq!(shaded.calibration.status(), Status::Calibrated);
    // Soiling after commissioning: followed, and flagged as drift.
    assert!((level(&dirty) / base - 0.9).abs() < 0.02);
    assert_eq!(dirty.calibration.status(), Status::Drifted);
    // +25 %, +70 % or −40 % from the start: never called calibrated, never chased. +25 %: its
    // clear days are 20-35 % above the site's clear sky, beyond the detector's mean and maximum
    // criteria (75 W/m²), so nothing is learned and, within the bounds 0.75-1.6, nothing is
    // flagged (`learning`); under bounds of 0.8-1.2 the windows clear at their own factor, above
    // 1.2, make bright days, flagged `sensor-suspect` from the first one on. +70 %: bright days
    // above 1.6, flagged (and a smooth overcast, read 1.7 times too high, passes for a clear
    // day at 0.75 of the clear sky: a level at the bound, flagged too). −40 %: found clear with
    // the sun low, a level learned beyond the bounds, the factor held within them and flagged
    // `sensor-suspect`.
    for r in [&high, &high_narrow] {
        assert_eq!(r.calibration.level_unbounded(), None);
        assert_eq!(r.calibration.factor(40.0), 1.0);
    }
    for r in [&high, &high_narrow, &very_high] {
        assert!(r.days.iter().all(|d| d.2 != Status::Calibrated));
    }
    assert_eq!(high.calibration.status(), Status::Learning);
    for r in [&high_narrow, &very_high] {
        let flagged_after = r
            .days
            .iter()
            .position(|d| d.2 == Status::SensorSuspect)
            .expect("flagged");
        assert!(flagged_after <= 3, "flagged after day {flagged_after}");
        assert!(
            r.days[flagged_after..]
                .iter()
                .all(|d| d.2 == Status::SensorSuspect),
            "the flag holds"
        );
    }
    // The clean, shaded and soiled sensors are never flagged.
    for r in [&clean, &shaded, &dirty] {
        assert!(r.days.iter().all(|d| d.2 != Status::SensorSuspect));
    }
    let c = &low.calibration;
    let learned = c.level_unbounded().expect("the -40 % sensor's level");
    assert!(learned < bounds.min, "level {learned}");
    assert_eq!(c.status(), Status::SensorSuspect);
    for h in [10.0, 40.0, 80.0] {
        let k = c.factor(h);
        assert!((bounds.min..=bounds.max).contains(&k), "factor {k} at {h}°");
    }
}
