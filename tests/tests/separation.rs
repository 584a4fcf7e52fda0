//! The separation of a global reading against measurement (issue 24 item 5): Erbs 1982 and
//! Engerer2 (Engerer 2015, and Bright & Engerer 2019's world-wide 1-minute re-fit) split the
//! measured GHI of public radiometric stations' days, as delivered, and the split's diffuse is
//! compared with the measured DHI on daylight minutes with GHI above 50 W/m². The split is the
//! controller's own (`controller::step` with a GHI-only measurement), so the clear sky Engerer2
//! uses is the one the controller uses (sky-core's `Daylight` at the default aerosol optical
//! depth, its illuminance through Perez's efficacy: `controller::clear_sky_irradiance`).
//!
//! A unit test checks `decomposition::engerer2` against an f64 evaluation of the published
//! formula written out here, with the solar time from the sun's hour angle of an independent
//! (NOAA / Spencer) expression.

use sky_core::controller::{
    Decomposition, Measurement, Settings, clear_sky_irradiance, example_luminaire, step,
};
use sky_core::decomposition::{
    ENGERER2_2015, ENGERER2_2019_1MIN, Engerer2Coefficients, Separation, apparent_solar_time,
    engerer2,
};
use sky_core::solar::{Site, SunAlgorithm, UtcTime, extraterrestrial_irradiance};

/// One measured minute: UTC (year, month, day, hour, minute), GHI and DHI in W/m².
struct Minute {
    time: (i32, u32, u32, u32, u32),
    ghi: f64,
    dhi: f64,
}

/// A station's day.
struct Station {
    name: &'static str,
    site: Site,
    minutes: Vec<Minute>,
}

fn data(name: &str) -> String {
    let path = format!("{}/data/stations/{name}", env!("CARGO_MANIFEST_DIR"));
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// NOAA SURFRAD daily file: year, day of year, month, day, hour, minute, decimal time, zenith,
/// dw_solar (GHI) and its flag, uw_solar, direct_n, diffuse and its flag, … (flag 0 = good).
fn surfrad(name: &'static str, file: &str) -> Station {
    let text = data(file);
    let mut lines = text.lines();
    let _name = lines.next();
    let head: Vec<f64> = lines
        .next()
        .expect("site line")
        .split_whitespace()
        .take(3)
        .map(|v| v.trim_end_matches('m').parse().expect("number"))
        .collect();
    // SURFRAD gives the longitude as degrees west.
    let site = Site::new(head[0], -head[1], head[2]).expect("site");
    let minutes = lines
        .filter_map(|l| {
            let f: Vec<f64> = l
                .split_whitespace()
                .map(|v| v.parse().expect("number"))
                .collect();
            (f[9] == 0.0 && f[15] == 0.0).then(|| Minute {
                time: (
                    f[0] as i32,
                    f[2] as u32,
                    f[3] as u32,
                    f[4] as u32,
                    f[5] as u32,
                ),
                ghi: f[8],
                dhi: f[14],
            })
        })
        .collect();
    Station {
        name,
        site,
        minutes,
    }
}

/// NREL MIDC raw file of UAT (Tucson): Year, DOY, MST (HHMM), DNI, DHI, GHI (tracker), …;
/// missing values −7999.
fn midc(name: &'static str, file: &str, site: Site) -> Station {
    let text = data(file);
    let minutes = text
        .lines()
        .skip(1)
        .filter_map(|l| {
            let f: Vec<f64> = l.split(',').map(|v| v.parse().expect("number")).collect();
            let (year, doy, hhmm) = (f[1] as i32, f[2] as u32, f[3] as u32);
            // MST is UTC−7; the day's rows stay within the UTC day for 06:00–16:59 MST.
            let (hour, minute) = (hhmm / 100 + 7, hhmm % 100);
            if hour >= 24 || f[5] < -100.0 || f[6] < -100.0 {
                return None;
            }
            let (month, day) = month_day(year, doy);
            Some(Minute {
                time: (year, month, day, hour, minute),
                ghi: f[6],
                dhi: f[5],
            })
        })
        .collect();
    Station {
        name,
        site,
        minutes,
    }
}

/// University of Oregon SRML daily file (Eugene, EUPO): day of year and HHMM (PST, UTC−8, the
/// end of the minute) then value-flag pairs of the elements of the header: 1000 GHI, 2010 DNI,
/// 2011 DNI (a second instrument), 7008; flag 99 missing. There is no diffuse sensor: the
/// measured diffuse is the closure GHI − DNI cos Z (the sun's geometric zenith at mid-minute).
fn srml(name: &'static str, file: &str, site: Site) -> Station {
    let text = data(file);
    let year: i32 = text
        .lines()
        .next()
        .and_then(|l| l.split_whitespace().nth(1))
        .and_then(|v| v.parse().ok())
        .expect("year in the header");
    let minutes = text
        .lines()
        .skip(1)
        .filter_map(|l| {
            let f: Vec<f64> = l
                .split_whitespace()
                .map(|v| v.parse().expect("number"))
                .collect();
            if f[3] == 99.0 || f[5] == 99.0 {
                return None;
            }
            let hhmm = f[1] as u32;
            // The minute's start, PST to UTC.
            let start = (hhmm / 100) * 60 + hhmm % 100 - 1 + 8 * 60;
            // 16:00 PST is 00:00 UTC of the next day (the file stays within one year).
            let (doy, start) = (f[0] as u32 + start / 1440, start % 1440);
            let (month, day) = month_day(year, doy);
            let time = (year, month, day, start / 60, start % 60);
            let at = UtcTime::new(year, month, day, start / 60, start % 60, 30.0).expect("time");
            let zenith = sky_core::solar::SunPosition::new(&at, &site)
                .expect("sun")
                .zenith_deg();
            let (ghi, dni) = (f[2], f[4]);
            Some(Minute {
                time,
                ghi,
                dhi: ghi - dni.max(0.0) * zenith.to_radians().cos().max(0.0),
            })
        })
        .collect();
    Station {
        name,
        site,
        minutes,
    }
}

fn month_day(year: i32, doy: u32) -> (u32, u32) {
    let leap = (year % 4 == 0 && year % 100 != 0) || year % 400 == 0;
    let lengths = [
        31,
        if leap { 29 } else { 28 },
        31,
        30,
        31,
        30,
        31,
        31,
        30,
        31,
        30,
        31,
    ];
    let mut d = doy;
    for (m, &n) in lengths.iter().enumerate() {
        if d <= n {
            return (m as u32 + 1, d);
        }
        d -= n;
    }
    panic!("day of year {doy}")
}

/// The stations with the median clear-sky index of the default clear sky on their clear
/// minutes that issue 24 reports (pvlib's detect_clearsky, sun above 5°): 1.36 at Alamosa,
/// 1.09 at UAT; none for the overcast day.
fn stations() -> Vec<(Station, Option<f64>)> {
    vec![
        (
            surfrad("SURFRAD Alamosa 2016-01-01", "surfrad-slv16001-day.dat"),
            Some(1.36),
        ),
        (
            midc(
                "MIDC UAT Tucson 2018-10-18",
                "midc-uat-raw-20181018-day.txt",
                Site::new(32.22969, -110.95534, 786.0).expect("site"),
            ),
            Some(1.09),
        ),
        (
            srml(
                "SRML Eugene 2018-01-01",
                "srml-eupo-20180101-day.txt",
                Site::new(44.0467, -123.0743, 150.0).expect("site"),
            ),
            None,
        ),
    ]
}

/// Bias and RMS of the split's diffuse against the measured, relative to the mean measured
/// DHI, with the number of minutes and the mean measured DHI.
///
/// With `clear_scale`, Engerer2 (`decomposition` giving the coefficients) is run directly with
/// the controller's clear sky times that factor (a diagnostic: the site's measured clear-sky
/// level in place of the default atmosphere's).
fn score(
    station: &Station,
    decomposition: Decomposition,
    clear_scale: Option<f64>,
) -> (f64, f64, usize, f64) {
    let lamp = example_luminaire().expect("lamp");
    let settings = Settings {
        sun: SunAlgorithm::Spa,
        decomposition,
        ..Settings::default()
    };
    let (mut n, mut measured, mut error, mut square) = (0usize, 0.0, 0.0, 0.0);
    for m in &station.minutes {
        let (y, mo, d, h, mi) = m.time;
        let time = UtcTime::new(y, mo, d, h, mi, 0.0).expect("time");
        let s = step(
            &time,
            &station.site,
            &settings,
            &lamp,
            Some(Measurement::GlobalIrradiance(m.ghi as f32)),
        )
        .expect("a raw station reading is accepted");
        if s.sun.zenith_deg() >= 90.0 || m.ghi <= 50.0 {
            continue;
        }
        let w = s.weather.expect("measured");
        let diffuse = match clear_scale {
            None => f64::from(w.diffuse_irradiance),
            Some(scale) => {
                let zenith = s.sun.sun().zenith();
                let day = time.day_of_year();
                let clear = clear_sky_irradiance(w.clear_sky.y, zenith, day);
                let utc = h as f32 + mi as f32 / 60.0;
                let coefficients = if decomposition == Decomposition::Engerer2 {
                    ENGERER2_2015
                } else {
                    ENGERER2_2019_1MIN
                };
                let separation = Separation::Engerer2 {
                    clear_global: (f64::from(clear) * scale) as f32,
                    solar_time: apparent_solar_time(utc, station.site.longitude() as f32, day),
                    coefficients,
                };
                let r = Measurement::GlobalIrradiance(m.ghi as f32)
                    .read_with(zenith, day, &separation)
                    .expect("read");
                f64::from(r.diffuse_irradiance)
            }
        };
        let e = diffuse - m.dhi;
        n += 1;
        measured += m.dhi;
        error += e;
        square += e * e;
    }
    assert!(n > 100, "{}: {n} minutes", station.name);
    let mean = measured / n as f64;
    (
        error / n as f64 / mean,
        (square / n as f64).sqrt() / mean,
        n,
        mean,
    )
}

const MODELS: [(&str, Decomposition); 3] = [
    ("erbs", Decomposition::Erbs),
    ("engerer2", Decomposition::Engerer2),
    ("engerer2-global", Decomposition::Engerer2Global),
];

/// Prints bias and RMS per station and model (docs/weather.md). The clear-day bounds
/// (|bias| ≤ 15 %, RMS ≤ 35 %) hold for none of the models on the two clear days
/// (docs/weather.md states it); what is asserted is what the figures show and the choices rest
/// on: on the clear days, with the controller's clear sky, Erbs has the smallest RMS (so it
/// stays the default), and Engerer2's error falls when its clear sky is the site's measured
/// level (it needs item 1's site clear sky); on the overcast day every model meets the issue's
/// RMS ≤ 25 %.
#[test]
fn split_of_measured_ghi_against_measured_dhi() {
    for (station, index) in &stations() {
        let mut rms_default = Vec::new();
        for (name, model) in MODELS {
            for scale in std::iter::once(None).chain(index.map(Some)) {
                if scale.is_some() && model == Decomposition::Erbs {
                    continue;
                }
                let (bias, rms, n, mean) = score(station, model, scale);
                assert!(bias.is_finite() && rms.is_finite());
                println!(
                    "{:28} {:16} clear x{:4.2} minutes {n:4}  mean DHI {mean:6.1} W/m2  bias {:+6.1} %  RMS {:5.1} %",
                    station.name,
                    name,
                    scale.unwrap_or(1.0),
                    100.0 * bias,
                    100.0 * rms
                );
                if scale.is_none() {
                    rms_default.push(rms);
                } else {
                    let unscaled = *rms_default.last().expect("unscaled first");
                    assert!(
                        rms < unscaled,
                        "{}: {name} with the site's clear sky",
                        station.name
                    );
                }
            }
        }
        if index.is_some() {
            // A clear day: Erbs is the closest with the controller's clear sky.
            assert!(
                rms_default[0] < rms_default[1] && rms_default[0] < rms_default[2],
                "{}: Erbs is no longer the best with the default clear sky: {rms_default:?}; \
                 revisit Decomposition::default and docs/weather.md",
                station.name
            );
        } else {
            // The overcast day: the bound, RMS ≤ 25 %, for every model.
            assert!(
                rms_default.iter().all(|&r| r <= 0.25),
                "{}: {rms_default:?}",
                station.name
            );
        }
    }
}

/// The f64 formula of Engerer 2015 eq. 33, written out from the paper.
fn engerer2_f64(kt: f64, ktc: f64, ast: f64, zenith_deg: f64, kde: f64, k: &[f64; 7]) -> f64 {
    let [c, b0, b1, b2, b3, b4, b5] = *k;
    let kd = c
        + (1.0 - c) / (1.0 + (b0 + b1 * kt + b2 * ast + b3 * zenith_deg + b4 * (ktc - kt)).exp())
        + b5 * kde;
    kd.clamp(0.0, 1.0)
}

/// The published coefficients, as printed (Engerer 2015; Bright & Engerer 2019, 1 min).
const PAPER_2015: [f64; 7] = [
    4.2336e-2, -3.7912, 7.5479, -1.0036e-2, 3.1480e-3, -5.3146, 1.7073,
];
const PAPER_2019: [f64; 7] = [
    1.0562e-1, -4.1332, 8.2578, 1.0087e-2, 8.8801e-4, -4.9302, 4.4378e-1,
];

fn as_f64(c: &Engerer2Coefficients) -> [f64; 7] {
    let b = c.beta.map(f64::from);
    [f64::from(c.c), b[0], b[1], b[2], b[3], b[4], b[5]]
}

#[test]
fn engerer2_matches_the_published_formula() {
    for (ours, paper) in [
        (&ENGERER2_2015, &PAPER_2015),
        (&ENGERER2_2019_1MIN, &PAPER_2019),
    ] {
        for (a, b) in as_f64(ours).iter().zip(paper) {
            assert!(
                (a - b).abs() <= 1e-6 * b.abs(),
                "coefficient {a} against {b}"
            );
        }
        let i0 = 1361.0f64;
        let mut worst = 0.0f64;
        for zenith in [0.0, 15.0, 30.0, 45.0, 60.0, 75.0, 85.0] {
            let cz = f64::cos(f64::to_radians(zenith)).max(0.065);
            for kt in [0.02, 0.1, 0.25, 0.4, 0.55, 0.7, 0.8, 0.9] {
                for ktc in [0.5, 0.7, 0.8] {
                    for ast in [7.0, 10.5, 12.0, 15.25, 18.0] {
                        let ghi = kt * i0 * cz;
                        let clear = ktc * i0 * cz;
                        let kde = (1.0 - clear / ghi).max(0.0);
                        let want = engerer2_f64(kt, ktc, ast, zenith, kde, paper) * ghi;
                        let got = engerer2(
                            ghi as f32,
                            (zenith as f32).to_radians(),
                            i0 as f32,
                            clear as f32,
                            ast as f32,
                            ours,
                        )
                        .expect("valid");
                        let e = (f64::from(got.diffuse) - want).abs() / ghi;
                        worst = worst.max(e);
                        // Diffuse and beam add up to the global.
                        let sum = f64::from(got.diffuse)
                            + f64::from(got.direct_normal) * f64::cos(f64::to_radians(zenith));
                        assert!((sum - ghi).abs() <= 1e-4 * ghi + 1e-3, "{sum} vs {ghi}");
                    }
                }
            }
        }
        // f32 arithmetic and sky-core's exp (relative 2e-6 over this range).
        assert!(worst < 2e-5, "largest error of k_d {worst}");
    }
}

#[test]
fn solar_time_matches_the_noaa_hour_angle() {
    // NOAA's solar calculator spreadsheet's equation of time (from Meeus's series), minutes,
    // evaluated here in f64 for the day's noon; apparent solar time = UTC + lon/15 + EoT.
    for (day, lon) in [
        (1u32, -105.92f64),
        (80, 16.37),
        (172, 0.0),
        (291, -110.955),
        (355, 151.2),
    ] {
        // Julian centuries from J2000.0 to noon UTC of the day in 2026 (9,497 days to 1 January).
        let jc = (9497.0 + f64::from(day) - 1.0) / 36525.0;
        let l0 = (280.46646 + jc * (36000.76983 + jc * 0.0003032)).rem_euclid(360.0);
        let m = 357.52911 + jc * (35999.05029 - 0.0001537 * jc);
        let e = 0.016708634 - jc * (0.000042037 + 0.0000001267 * jc);
        let eps =
            23.0 + (26.0 + (21.448 - jc * (46.815 + jc * (0.00059 - jc * 0.001813))) / 60.0) / 60.0;
        let y = (eps.to_radians() / 2.0).tan().powi(2);
        let (l0r, mr) = (l0.to_radians(), m.to_radians());
        let eot = 4.0
            * (y * (2.0 * l0r).sin() - 2.0 * e * mr.sin()
                + 4.0 * e * y * mr.sin() * (2.0 * l0r).cos()
                - 0.5 * y * y * (4.0 * l0r).sin()
                - 1.25 * e * e * (2.0 * mr).sin())
            .to_degrees();
        let utc = 12.0 - lon / 15.0;
        let want = (utc + lon / 15.0 + eot / 60.0).rem_euclid(24.0);
        let got = f64::from(apparent_solar_time(utc as f32, lon as f32, day));
        // Spencer's series against Meeus's: within about a minute (2026's days).
        assert!(
            (got - want).abs() < 1.5 / 60.0,
            "day {day}: {got} h against {want} h"
        );
    }
}

#[test]
fn clear_sky_irradiance_is_the_clear_sky_through_the_efficacy() {
    // A reading equal to the clear sky's irradiance gives back the clear sky's illuminance.
    let site = Site::new(32.23, -110.96, 786.0).expect("site");
    let time = UtcTime::new(2018, 10, 18, 19, 0, 0.0).expect("time");
    let lamp = example_luminaire().expect("lamp");
    let settings = Settings {
        sun: SunAlgorithm::Spa,
        ..Settings::default()
    };
    let clear = step(&time, &site, &settings, &lamp, None).expect("step");
    let zenith = clear.sun.sun().zenith();
    let wm2 = clear_sky_irradiance(clear.daylight.global().y, zenith, time.day_of_year());
    let i0 = f64::from(extraterrestrial_irradiance(time.day_of_year()));
    let kt = f64::from(wm2) / (i0 * f64::from(zenith).cos());
    assert!((0.6..0.85).contains(&kt), "clear-sky clearness index {kt}");
    let back = step(
        &time,
        &site,
        &Settings {
            decomposition: Decomposition::Erbs,
            ..settings
        },
        &lamp,
        Some(Measurement::GlobalIrradiance(wm2)),
    )
    .expect("step");
    let lux = back.weather.expect("measured").global_illuminance;
    let rel = (f64::from(lux) / f64::from(clear.daylight.global().y) - 1.0).abs();
    assert!(rel < 1e-3, "{lux} lx against {}", clear.daylight.global().y);
}

/// Runs a `sky-train` command line: stdout, or the error's text and whether it is a parameter
/// error (exit status 2).
fn run(args: &[&str]) -> Result<String, (String, bool)> {
    use clap::Parser as _;
    use sky_train::cli::{self, Cli};
    let cli = Cli::try_parse_from(std::iter::once("sky-train").chain(args.iter().copied()))
        .map_err(|e| (e.to_string(), true))?;
    let mut output = Vec::new();
    cli::execute(cli.command, &mut std::io::empty(), &mut output)
        .map_err(|e| (format!("{e:#}"), e.is::<sky_train::sources::ParamError>()))?;
    Ok(String::from_utf8(output).expect("UTF-8"))
}

/// `schedule --decomposition` splits a GHI-only file by the model named, as the controller's
/// step with that setting does; an unknown model is a parameter error naming the flag.
#[test]
fn schedule_decomposition_flag_selects_the_model() {
    let dir = tempfile::tempdir().expect("temp dir");
    let file = dir.path().join("ghi.csv");
    let readings = [
        ("2018-10-18T15:00:00Z", 300.0f32),
        ("2018-10-18T19:00:00Z", 760.0),
        ("2018-10-18T21:30:00Z", 180.0),
    ];
    let mut csv = String::from("utc,ghi_wm2\n");
    for (t, g) in readings {
        csv.push_str(&format!("{t},{g}\n"));
    }
    std::fs::write(&file, csv).expect("write");
    let path = file.to_str().expect("UTF-8 path");
    let site = Site::new(32.23, -110.96, 786.0).expect("site");
    let lamp = example_luminaire().expect("lamp");
    let mut columns = Vec::new();
    for (name, model) in MODELS {
        let out = run(&[
            "schedule",
            "--lat",
            "32.23",
            "--lon",
            "-110.96",
            "--elevation",
            "786",
            "--atmosphere",
            "record",
            "--measurements",
            path,
            "--decomposition",
            name,
        ])
        .unwrap_or_else(|(e, _)| panic!("{name}: {e}"));
        let mut lines = out.lines();
        let header: Vec<&str> = lines.next().expect("header").split(',').collect();
        let at = header
            .iter()
            .position(|&h| h == "dhi_wm2")
            .expect("dhi_wm2 column");
        let dhi: Vec<f64> = lines
            .map(|l| l.split(',').nth(at).expect("dhi").parse().expect("number"))
            .collect();
        assert_eq!(dhi.len(), readings.len());
        let settings = Settings {
            sun: SunAlgorithm::Spa,
            decomposition: model,
            ..Settings::default()
        };
        for ((&(t, g), &d), hour) in readings.iter().zip(&dhi).zip([(15, 0), (19, 0), (21, 30)]) {
            let time = UtcTime::new(2018, 10, 18, hour.0, hour.1, 0.0).expect("time");
            let s = step(
                &time,
                &site,
                &settings,
                &lamp,
                Some(Measurement::GlobalIrradiance(g)),
            )
            .expect("step");
            let want = f64::from(s.weather.expect("measured").diffuse_irradiance);
            assert!(
                (d - want).abs() <= 1e-3 * want.max(1.0),
                "{name} at {t}: {d} against {want}"
            );
        }
        columns.push(dhi);
    }
    assert!(
        columns[0] != columns[1] && columns[1] != columns[2],
        "{columns:?}"
    );
    let (e, param) = run(&[
        "schedule",
        "--lat",
        "32.23",
        "--lon",
        "-110.96",
        "--measurements",
        path,
        "--decomposition",
        "disc",
    ])
    .expect_err("an unknown model");
    assert!(param && e.contains("--decomposition"), "{e}");
}

/// Hostile input: `engerer2` and the controller's Engerer2 path never panic; a result has
/// 0 ≤ diffuse ≤ global and a finite, non-negative beam; NaN, negative clear skies and solar
/// times outside [0, 24] are errors.
#[test]
fn engerer2_is_bounded_on_hostile_input() {
    let values = [
        f32::NAN,
        f32::INFINITY,
        f32::NEG_INFINITY,
        -1.0,
        0.0,
        f32::MIN_POSITIVE,
        1e-30,
        0.5,
        50.0,
        400.0,
        1200.0,
        1e6,
        f32::MAX,
    ];
    let zeniths = [
        f32::NAN,
        -0.1,
        0.0,
        0.7,
        1.5,
        1.52,
        std::f32::consts::FRAC_PI_2,
        1.6,
    ];
    let times = [f32::NAN, -1.0, 0.0, 6.5, 12.0, 23.99, 24.0, 25.0];
    for &g in &values {
        for &c in &values {
            for &z in &zeniths {
                for &t in &times {
                    for k in [&ENGERER2_2015, &ENGERER2_2019_1MIN] {
                        if let Ok(r) = engerer2(g, z, 1361.0, c, t, k) {
                            assert!(r.diffuse >= 0.0 && r.diffuse <= r.global, "{g} {c} {z} {t}");
                            assert!(r.direct_normal.is_finite() && r.direct_normal >= 0.0);
                            assert!(c >= 0.0 && (0.0..=24.0).contains(&t));
                        }
                    }
                }
            }
        }
    }
    for &t in &[f32::NAN, f32::INFINITY, -1e30, -5.0, 0.0, 23.999, 1e30] {
        let ast = apparent_solar_time(t, -110.0, 200);
        assert!((0.0..24.0).contains(&ast), "{t}: {ast}");
    }
    let site = Site::new(-89.0, 179.9, 0.0).expect("site");
    let lamp = example_luminaire().expect("lamp");
    for model in [Decomposition::Engerer2, Decomposition::Engerer2Global] {
        let settings = Settings {
            decomposition: model,
            ..Settings::default()
        };
        for hour in 0..24 {
            let time = UtcTime::new(2030, 12, 21, hour, 0, 0.0).expect("time");
            for &g in &values {
                if let Ok(s) = step(
                    &time,
                    &site,
                    &settings,
                    &lamp,
                    Some(Measurement::GlobalIrradiance(g)),
                ) {
                    let w = s.weather.expect("measured");
                    assert!(w.diffuse_irradiance.is_finite() && w.diffuse_irradiance >= 0.0);
                }
            }
        }
    }
}
