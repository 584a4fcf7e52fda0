//! The site's clear sky against measured clear days (issue 24 item 1): `sky-train schedule
//! --measurements` runs the stations' files as delivered, each with nothing but the station's
//! latitude, longitude and elevation (the clear atmosphere is the site's month from the
//! climatology, `sky-train site`, on the day's Earth-Sun distance; nothing is fitted to a day;
//! the self-calibration on, as by default), and the clear-sky index of its output is taken on
//! the clear minutes an independent selector picked (pvlib's `detect_clearsky`, Reno & Hansen
//! 2016, the sun above 5°: `tests/fixtures/clear_minutes.csv`, written by
//! `tests/reference/gen_station_fixtures.py`). The bounds: median within [0.97, 1.03],
//! the 5th and 95th percentiles within [0.92, 1.08], on at least three stations of different
//! altitude and climate.
//!
//! The stations (`tests/data/stations/README.md`): SURFRAD Alamosa and MIDC UAT Tucson were
//! looked at while the climatology and its conversion were chosen; BSRN Payerne and MIDC BMS
//! Golden were held out then (and looked at since). What each figure rests on:
//!
//! * Tucson (786 m, desert, October) and Golden (1,829 m, Front Range, January): single days,
//!   so the climatology alone (the test checks that no calibration factor was applied);
//! * Payerne (491 m, Swiss plateau, June, 16 clear days): the self-calibration learned on the
//!   earlier days (its first clear days use the climatology alone); the climatology alone gives
//!   a 95th percentile of 1.119 there (printed, not asserted): the month's climatological
//!   aerosol is three times what the measured beam shows on its clear days (docs/daylight.md);
//! * Alamosa (2,317 m, San Luis Valley, 1 January 2016): **not met** and not asserted (median
//!   1.059, 95th percentile 1.192): a single day, so nothing earlier to learn from, and the
//!   day's aerosol is far below the climatology's (and below the tables' floor, 0.05);
//!   docs/daylight.md has the measurement. The ground was not snow-covered (the station's own
//!   upward pyranometer: albedo 0.185).

use std::collections::HashSet;

use sky_train::cli::{self, Cli};

/// One station's days.
struct Station {
    name: &'static str,
    file: &'static str,
    format: &'static str,
    lat: &'static str,
    lon: &'static str,
    elevation: &'static str,
    held_out: bool,
    /// Whether the bounds are claimed (and asserted) for this station.
    claimed: bool,
    /// Whether the figure rests on the self-calibration learned on earlier days (else on the
    /// climatology alone: no factor may have been applied).
    calibrated: bool,
}

const STATIONS: [Station; 4] = [
    Station {
        name: "alamosa",
        file: "surfrad-slv16001-day.dat",
        format: "surfrad",
        lat: "37.70",
        lon: "-105.92",
        elevation: "2317",
        held_out: false,
        claimed: false,
        calibrated: false,
    },
    Station {
        name: "tucson",
        file: "midc-uat-raw-20181018-day.txt",
        format: "midc",
        lat: "32.22969",
        lon: "-110.95534",
        elevation: "786",
        held_out: false,
        claimed: true,
        calibrated: false,
    },
    Station {
        name: "payerne",
        file: "bsrn-pay-201606-clear.csv",
        format: "csv",
        lat: "46.815",
        lon: "6.944",
        elevation: "491",
        held_out: true,
        claimed: true,
        calibrated: true,
    },
    Station {
        name: "golden",
        file: "midc-bms-ghi-20220120.csv",
        format: "csv",
        lat: "39.742",
        lon: "-105.18",
        elevation: "1829",
        held_out: true,
        claimed: true,
        calibrated: false,
    },
];

fn root() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).to_path_buf()
}

/// `schedule --measurements` of the station's file, as text (`extra`: further flags).
fn schedule(s: &Station, extra: &[&str]) -> String {
    let file = root().join("data/stations").join(s.file);
    let file = file.to_str().expect("utf-8 path");
    let args = [
        "sky-train",
        "schedule",
        "--lat",
        s.lat,
        "--lon",
        s.lon,
        "--elevation",
        s.elevation,
        "--measurements",
        file,
        "--measurements-format",
        s.format,
    ];
    let args = args.iter().chain(extra);
    let cli = <Cli as clap::Parser>::try_parse_from(args).expect("arguments");
    let mut out = Vec::new();
    cli::execute(cli.command, &mut std::io::empty(), &mut out).expect("schedule runs");
    String::from_utf8(out).expect("utf-8")
}

/// The clear minutes of `station` (RFC 3339 UTC, as the schedule writes them).
fn clear_minutes(station: &str) -> HashSet<String> {
    let text = std::fs::read_to_string(root().join("fixtures/clear_minutes.csv")).expect("fixture");
    text.lines()
        .skip(1)
        .filter_map(|l| l.split_once(','))
        .filter(|(s, _)| *s == station)
        .map(|(_, t)| t.to_owned())
        .collect()
}

/// The `q` quantile of sorted `v` by linear interpolation between order statistics (numpy's
/// default).
fn quantile(v: &[f64], q: f64) -> f64 {
    let x = q * (v.len() - 1) as f64;
    let i = x.floor() as usize;
    let j = (i + 1).min(v.len() - 1);
    v[i] + (x - i as f64) * (v[j] - v[i])
}

/// The clear-sky index on the station's clear minutes of `schedule`'s `text`, sorted, with the
/// calibration factors applied to them.
fn indices(text: &str, clear: &HashSet<String>) -> (Vec<f64>, Vec<f64>) {
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().expect("header").split(',').collect();
    let col = |name: &str| header.iter().position(|h| *h == name).expect(name);
    let (utc, index, factor) = (col("utc"), col("clear_sky_index"), col("clear_sky_factor"));
    let (mut k, mut f): (Vec<f64>, Vec<f64>) = lines
        .filter_map(|l| {
            let v: Vec<&str> = l.split(',').collect();
            clear.contains(v[utc]).then(|| {
                (
                    v[index].parse::<f64>().expect("an index by day"),
                    v[factor].parse::<f64>().expect("a factor"),
                )
            })
        })
        .unzip();
    k.sort_by(f64::total_cmp);
    f.sort_by(f64::total_cmp);
    (k, f)
}

/// (median, 5th, 95th percentile) of sorted `k`.
fn figures(k: &[f64]) -> (f64, f64, f64) {
    (quantile(k, 0.5), quantile(k, 0.05), quantile(k, 0.95))
}

#[test]
fn clear_sky_index_on_measured_clear_days() {
    let mut failures = Vec::new();
    let mut met: Vec<f64> = Vec::new();
    for s in &STATIONS {
        let clear = clear_minutes(s.name);
        let (k, factors) = indices(&schedule(s, &[]), &clear);
        assert!(
            k.len() * 10 >= clear.len() * 9,
            "{}: {} of {} clear minutes in the output",
            s.name,
            k.len(),
            clear.len()
        );
        let (median, p5, p95) = figures(&k);
        let (alone, alone5, alone95) =
            figures(&indices(&schedule(s, &["--no-self-calibration"]), &clear).0);
        let ok = (0.97..=1.03).contains(&median) && p5 >= 0.92 && p95 <= 1.08;
        println!(
            "{:8} {:9} {:5} clear minutes: clear-sky index median {median:.3}, 5-95 % {p5:.3} to {p95:.3} ({}; bounds {}) | climatology alone: median {alone:.3}, 5-95 % {alone5:.3} to {alone95:.3}",
            s.name,
            if s.held_out { "held out" } else { "design" },
            k.len(),
            if s.calibrated {
                "self-calibrated on earlier days"
            } else {
                "climatology alone"
            },
            if ok { "met" } else { "not met" },
        );
        if s.calibrated {
            assert!(
                factors.iter().any(|&f| f != 1.0),
                "{}: nothing learned",
                s.name
            );
        } else {
            assert!(factors.iter().all(|&f| f == 1.0), "{}: calibrated", s.name);
        }
        if s.claimed {
            if ok {
                met.push(s.elevation.parse().expect("metres"));
            } else {
                failures.push(s.name);
            }
        }
    }
    assert!(
        failures.is_empty(),
        "outside median [0.97, 1.03] or 5-95 % [0.92, 1.08]: {failures:?}"
    );
    met.sort_by(f64::total_cmp);
    met.dedup();
    assert!(
        met.len() >= 3,
        "stations of different altitude within the bounds: {met:?}"
    );
}
