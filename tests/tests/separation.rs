//! The separation of a global reading against measurement (issue 24 item 5).
//!
//! * The implementations against pvlib's: DISC, DIRINT and DIRINDEX against pvlib 0.16.1's on
//!   random inputs and on every daylight minute of the station days (fixtures written by
//!   `tests/reference/gen_separation_fixtures.py`), DIRINT's coefficient table against the
//!   published one; Engerer2 against an f64 evaluation of the published formula written out
//!   here, its solar time against an independent (NOAA) expression.
//! * The split against measurement: the measured GHI of four public radiometric stations'
//!   days, as delivered, split by the controller's own step (`controller::step_with_history`
//!   with a GHI-only measurement: the clear sky DIRINDEX and Engerer2 use is the controller's,
//!   sky-core's `Daylight` at the default aerosol optical depth), and again by the models that
//!   need a clear sky with an independent one that fits the site (pvlib's Ineichen-Perez clear
//!   sky with its Linke-turbidity climatology, from the fixture); the split's diffuse against
//!   the measured DHI on daylight minutes with GHI above 50 W/m².

use std::collections::HashMap;

use sky_core::controller::{
    Decomposition, History, Measurement, Settings, clear_sky_irradiance, example_luminaire, step,
    step_with_history,
};
use sky_core::decomposition::{
    ClearSky, DirintForm, ENGERER2_2015, ENGERER2_2019_1MIN, Engerer2Coefficients,
    MAX_STABILITY_GAP_MINUTES, Separation, apparent_solar_time, dirindex, dirint,
    dirint_coefficient, disc, disc_air_mass, engerer2, kt_prime, pressure_from_elevation,
    stability_index,
};
use sky_core::solar::{Site, SunAlgorithm, SunPosition, UtcTime, extraterrestrial_irradiance};
use sky_tests::fixtures::{self, num};

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

/// The layout of an NREL MIDC raw file: its hours behind UTC and the columns of GHI and DHI.
/// Every such file starts Year, DOY, local standard time (HHMM); missing values are −7999.
struct MidcLayout {
    utc_offset_hours: u32,
    ghi: usize,
    dhi: usize,
}

/// UAT (Tucson): MST (UTC−7), then DNI, DHI, GHI (tracker), …
const MIDC_UAT: MidcLayout = MidcLayout {
    utc_offset_hours: 7,
    ghi: 6,
    dhi: 5,
};

/// UTPASRL (University of Texas Rio Grande Valley, Edinburg): CST (UTC−6), then battery, Direct
/// Normal, its standard deviation, CHP1 temperature and its standard deviation, Global
/// Horizontal, its standard deviation, Diffuse Horizontal, … (the header names 20 columns, the
/// rows have 26: pvlib's `read_midc_raw_data_from_nrel` handles the mismatch by the header's
/// first columns, as here).
const MIDC_UTPASRL: MidcLayout = MidcLayout {
    utc_offset_hours: 6,
    ghi: 9,
    dhi: 11,
};

/// An NREL MIDC raw file of `layout`; the rows that fall on the next UTC day or miss a value
/// are left out (the day files keep daylight rows, within the UTC day).
fn midc(name: &'static str, file: &str, site: Site, layout: &MidcLayout) -> Station {
    let text = data(file);
    let minutes = text
        .lines()
        .skip(1)
        .filter_map(|l| {
            let f: Vec<f64> = l.split(',').map(|v| v.parse().expect("number")).collect();
            let (year, doy, hhmm) = (f[1] as i32, f[2] as u32, f[3] as u32);
            let (hour, minute) = (hhmm / 100 + layout.utc_offset_hours, hhmm % 100);
            let (ghi, dhi) = (f[layout.ghi], f[layout.dhi]);
            if hour >= 24 || ghi < -100.0 || dhi < -100.0 {
                return None;
            }
            let (month, day) = month_day(year, doy);
            Some(Minute {
                time: (year, month, day, hour, minute),
                ghi,
                dhi,
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

/// The sky of a station day.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Sky {
    Clear,
    Overcast,
    /// Broken cloud: bounded by no goal, reported.
    Broken,
}

/// The station days: the fixture's name for each, and its sky.
fn stations() -> Vec<(Station, &'static str, Sky)> {
    vec![
        (
            surfrad("SURFRAD Alamosa 2016-01-01", "surfrad-slv16001-day.dat"),
            "alamosa",
            Sky::Clear,
        ),
        (
            midc(
                "MIDC UAT Tucson 2018-10-18",
                "midc-uat-raw-20181018-day.txt",
                Site::new(32.22969, -110.95534, 786.0).expect("site"),
                &MIDC_UAT,
            ),
            "tucson",
            Sky::Clear,
        ),
        (
            srml(
                "SRML Eugene 2018-01-01",
                "srml-eupo-20180101-day.txt",
                Site::new(44.0467, -123.0743, 150.0).expect("site"),
            ),
            "eugene",
            Sky::Overcast,
        ),
        (
            midc(
                "MIDC UTPASRL Edinburg 2019-11-15",
                "midc-utpasrl-raw-20191115-day.txt",
                Site::new(26.3059, -98.1716, 45.0).expect("site"),
                &MIDC_UTPASRL,
            ),
            "edinburg",
            Sky::Broken,
        ),
    ]
}

/// pvlib's values at one minute of a station day (`separation_days.csv`).
struct Reference {
    zenith_deg: f64,
    ghi: f64,
    kt_prime: f64,
    delta_kt_prime: f64,
    dirint_dni: f64,
    ghi_clear: f64,
    dni_clear: f64,
    clear_delta_kt_prime: f64,
    dirindex_dni: f64,
}

/// The fixture of the station days, by station and UTC minute (`2016-01-01T14:24Z`).
fn references() -> HashMap<(String, String), Reference> {
    fixtures::rows("separation_days.csv")
        .into_iter()
        .map(|r| {
            let n = |i: usize| num(&r[i]);
            (
                (r[0].clone(), r[1].clone()),
                Reference {
                    zenith_deg: n(2),
                    ghi: n(3),
                    kt_prime: n(4),
                    delta_kt_prime: n(5),
                    dirint_dni: n(6),
                    ghi_clear: n(7),
                    dni_clear: n(8),
                    clear_delta_kt_prime: n(9),
                    dirindex_dni: n(10),
                },
            )
        })
        .collect()
}

fn utc_key(time: (i32, u32, u32, u32, u32)) -> String {
    let (y, mo, d, h, mi) = time;
    format!("{y:04}-{mo:02}-{d:02}T{h:02}:{mi:02}Z")
}

/// A split to score: a model through the controller (the site's clear sky), DIRINT as
/// published, DIRINT one reading at a time, or a model with the fixture's clear sky (pvlib's
/// Ineichen-Perez).
#[derive(Debug, Clone, Copy, PartialEq)]
enum Split {
    /// `sky-train schedule --measurements` given only the site's latitude, longitude and
    /// elevation (the controller's step with the site's month's clear sky, a history across the
    /// rows) and `--decomposition`.
    Schedule(Decomposition),
    /// `controller::step`, each minute alone (DIRINT without its stability index).
    Alone(Decomposition),
    /// DIRINT as published (`DirintForm::Binned`), the stability index from the minute before.
    Binned,
    /// The model with the fixture's clear sky times a factor (1: as it is; 0.95 and 1.05:
    /// a clear sky 5 % too dim or too bright), the stability index from the minute before.
    Ineichen(Decomposition, f32),
}

/// The CLI's name of a model.
fn model_name(d: Decomposition) -> &'static str {
    match d {
        Decomposition::Dirint => "dirint",
        Decomposition::Dirindex => "dirindex",
        Decomposition::Erbs => "erbs",
        Decomposition::Engerer2 => "engerer2",
        Decomposition::Engerer2Global => "engerer2-global",
    }
}

impl Split {
    fn label(self) -> String {
        match self {
            Split::Schedule(d) => model_name(d).to_owned(),
            Split::Alone(d) => format!("{}, alone", model_name(d)),
            Split::Binned => "dirint, binned".to_owned(),
            Split::Ineichen(d, 1.0) => format!("{}, Ineichen", model_name(d)),
            Split::Ineichen(d, scale) => format!("{}, Ineichen x{scale}", model_name(d)),
        }
    }
}

/// What is scored: the controller's split by every model with the site's clear sky; DIRINT as
/// published and reading by reading; the clear-sky models with pvlib's clear sky, and two of
/// them with that clear sky 5 % off.
const SPLITS: [Split; 14] = [
    Split::Schedule(Decomposition::Dirint),
    Split::Schedule(Decomposition::Dirindex),
    Split::Schedule(Decomposition::Erbs),
    Split::Schedule(Decomposition::Engerer2),
    Split::Schedule(Decomposition::Engerer2Global),
    Split::Binned,
    Split::Alone(Decomposition::Dirint),
    Split::Ineichen(Decomposition::Dirindex, 1.0),
    Split::Ineichen(Decomposition::Engerer2, 1.0),
    Split::Ineichen(Decomposition::Engerer2Global, 1.0),
    Split::Ineichen(Decomposition::Dirindex, 0.95),
    Split::Ineichen(Decomposition::Dirindex, 1.05),
    Split::Ineichen(Decomposition::Engerer2Global, 0.95),
    Split::Ineichen(Decomposition::Engerer2Global, 1.05),
];

/// `sky-train schedule --measurements` over the station's minutes (GHI only, as a CSV) given
/// the site's latitude, longitude and elevation and `--decomposition`: each minute's `dhi_wm2`.
fn schedule_diffuse(station: &Station, model: Decomposition) -> Vec<f64> {
    let dir = tempfile::tempdir().expect("temp dir");
    let file = dir.path().join("ghi.csv");
    let mut csv = String::from("utc,ghi_wm2\n");
    for m in &station.minutes {
        let (y, mo, d, h, mi) = m.time;
        csv.push_str(&format!(
            "{y:04}-{mo:02}-{d:02}T{h:02}:{mi:02}:00Z,{}\n",
            m.ghi
        ));
    }
    std::fs::write(&file, csv).expect("write");
    let site = &station.site;
    let (lat, lon, elevation) = (
        site.latitude().to_string(),
        site.longitude().to_string(),
        site.elevation().to_string(),
    );
    let out = run(&[
        "schedule",
        "--lat",
        &lat,
        "--lon",
        &lon,
        "--elevation",
        &elevation,
        "--measurements",
        file.to_str().expect("UTF-8 path"),
        "--decomposition",
        model_name(model),
    ])
    .unwrap_or_else(|(e, _)| panic!("{}: {e}", station.name));
    let mut lines = out.lines();
    let header: Vec<&str> = lines.next().expect("header").split(',').collect();
    let at = header
        .iter()
        .position(|&h| h == "dhi_wm2")
        .expect("dhi_wm2");
    let dhi: Vec<f64> = lines
        .map(|l| num(l.split(',').nth(at).expect("dhi_wm2")))
        .collect();
    assert_eq!(dhi.len(), station.minutes.len(), "{}", station.name);
    dhi
}

/// The minutes since the day's first of `time` (the station days stay within one UTC day).
fn day_minute(time: (i32, u32, u32, u32, u32)) -> f32 {
    (time.3 * 60 + time.4) as f32
}

/// Bias and RMS of the split's diffuse against the measured, relative to the mean measured
/// DHI, with the number of minutes, the mean measured DHI and the split's diffuse on those
/// minutes.
fn score(
    station: &Station,
    key: &str,
    split: Split,
    references: &HashMap<(String, String), Reference>,
) -> (f64, f64, usize, f64, Vec<f64>) {
    let lamp = example_luminaire().expect("lamp");
    let settings = |decomposition| Settings {
        sun: SunAlgorithm::Spa,
        decomposition,
        ..Settings::default()
    };
    let pressure = pressure_from_elevation(station.site.elevation() as f32);
    let scheduled = match split {
        Split::Schedule(model) => schedule_diffuse(station, model),
        _ => Vec::new(),
    };
    // The minute before's: the minute, the reading's k_t' and the clear sky's.
    let mut last: Option<(f32, f32, f32)> = None;
    let (mut n, mut measured, mut error, mut square) = (0usize, 0.0, 0.0, 0.0);
    let mut split_diffuse = Vec::new();
    for (i, m) in station.minutes.iter().enumerate() {
        let (y, mo, d, h, mi) = m.time;
        let time = UtcTime::new(y, mo, d, h, mi, 0.0).expect("time");
        let reading = Measurement::GlobalIrradiance(m.ghi as f32);
        let sun = SunPosition::new(&time, &station.site).expect("sun");
        let diffuse = match split {
            Split::Schedule(_) => (sun.zenith_deg() < 90.0).then(|| scheduled[i] as f32),
            Split::Alone(model) => {
                let s = step(&time, &station.site, &settings(model), &lamp, Some(reading))
                    .expect("a raw station reading is accepted");
                (s.sun.zenith_deg() < 90.0).then(|| s.weather.expect("measured").diffuse_irradiance)
            }
            Split::Binned | Split::Ineichen(..) => {
                let zenith = sun.sun().zenith();
                let day = time.day_of_year();
                let Some(r) = references.get(&(key.to_owned(), utc_key(m.time))) else {
                    // A night minute (the fixture holds the daylight ones).
                    last = None;
                    continue;
                };
                let scale = match split {
                    Split::Ineichen(_, scale) => scale,
                    _ => 1.0,
                };
                let (ghi_clear, dni_clear) =
                    (scale * r.ghi_clear as f32, scale * r.dni_clear as f32);
                let i0 = extraterrestrial_irradiance(day);
                let minute = day_minute(m.time);
                let ktp = kt_prime(m.ghi.max(0.0) as f32, zenith, i0, pressure);
                let clear_ktp = kt_prime(ghi_clear, zenith, i0, pressure);
                let (stability, clear_stability) = match last {
                    Some((t, k, c)) if minute - t <= MAX_STABILITY_GAP_MINUTES => (
                        stability_index(ktp, Some(k), None),
                        stability_index(clear_ktp, Some(c), None),
                    ),
                    _ => (None, None),
                };
                last = Some((minute, ktp, clear_ktp));
                let utc = h as f32 + mi as f32 / 60.0;
                let separation = match split {
                    Split::Ineichen(Decomposition::Dirindex, _) => Separation::Dirindex {
                        pressure,
                        stability,
                        clear: ClearSky {
                            global: ghi_clear,
                            direct_normal: dni_clear,
                            stability: clear_stability,
                        },
                        form: DirintForm::Interpolated,
                    },
                    Split::Ineichen(model, _) => Separation::Engerer2 {
                        clear_global: ghi_clear,
                        solar_time: apparent_solar_time(utc, station.site.longitude() as f32, day),
                        coefficients: if model == Decomposition::Engerer2 {
                            ENGERER2_2015
                        } else {
                            ENGERER2_2019_1MIN
                        },
                    },
                    _ => Separation::Dirint {
                        pressure,
                        stability,
                        form: DirintForm::Binned,
                    },
                };
                let r = reading
                    .read_with(zenith, day, &separation)
                    .expect("a raw station reading is accepted");
                Some(r.diffuse_irradiance)
            }
        };
        let Some(diffuse) = diffuse else { continue };
        if m.ghi <= 50.0 {
            continue;
        }
        let e = f64::from(diffuse) - m.dhi;
        split_diffuse.push(f64::from(diffuse));
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
        split_diffuse,
    )
}

/// Prints bias and RMS per station day and split (docs/weather.md), and holds what the
/// figures show and the choices rest on:
///
/// * the default model (DIRINT, continuous, through the controller with its history) meets the
///   issue's clear-day RMS bound (≤ 35 %) on both clear days and its bias bound (|bias| ≤ 15 %)
///   at Tucson; at Alamosa (2,317 m, winter, no snow: albedo 0.18) its bias is above 15 %, the one bound not met
///   (docs/weather.md says so); it meets the overcast bound (RMS ≤ 25 %) at Eugene;
/// * over the station days (clear, overcast and broken) the default has the smallest mean RMS
///   of the models through the controller with the site's clear sky (else
///   `Decomposition::default` and docs/weather.md are to be revisited; on a single day another
///   model may be closer: DIRINDEX at Alamosa, Erbs and Engerer2 at Eugene);
/// * DIRINT's stability index helps: with it the clear days' RMS is lower than reading by
///   reading;
/// * (printed) how far the continuous form's diffuse is from the published one's, relative to
///   the mean measured DHI;
/// * DIRINDEX depends on its clear sky: the site-fitting clear sky 5 % dimmer or brighter moves
///   its clear-day bias by more than 15 points.
#[test]
fn split_of_measured_ghi_against_measured_dhi() {
    let references = references();
    // The RMS of each model through the controller, summed over the station days.
    let mut controller_rms: HashMap<String, f64> = HashMap::new();
    let stations = stations();
    for (station, key, sky) in &stations {
        let mut rms = HashMap::new();
        let mut bias = HashMap::new();
        let mut diffuse = HashMap::new();
        for split in SPLITS {
            let (b, r, n, mean, d) = score(station, key, split, &references);
            assert!(b.is_finite() && r.is_finite());
            println!(
                "{:32} {:24} minutes {n:4}  mean DHI {mean:6.1} W/m2  bias {:+6.1} %  RMS {:5.1} %",
                station.name,
                split.label(),
                100.0 * b,
                100.0 * r
            );
            rms.insert(split.label(), r);
            bias.insert(split.label(), b);
            diffuse.insert(split.label(), (d, mean));
        }
        let ((smooth, mean), (binned, _)) = (&diffuse["dirint"], &diffuse["dirint, binned"]);
        let difference = smooth
            .iter()
            .zip(binned)
            .map(|(a, b)| (a - b).powi(2))
            .sum::<f64>();
        println!(
            "{:32} continuous DIRINT against the published: RMS difference of the diffuse {:.1} % of the mean DHI",
            station.name,
            100.0 * (difference / smooth.len() as f64).sqrt() / mean
        );
        let default = Split::Schedule(Decomposition::default()).label();
        for s in SPLITS.iter().filter(|s| matches!(s, Split::Schedule(_))) {
            *controller_rms.entry(s.label()).or_default() += rms[&s.label()];
        }
        match sky {
            Sky::Clear => {
                assert!(
                    rms[&default] <= 0.35,
                    "{}: the default's RMS {}",
                    station.name,
                    rms[&default]
                );
                if *key == "tucson" {
                    assert!(bias[&default].abs() <= 0.15, "{}", station.name);
                }
                assert!(
                    rms["dirint"] < rms["dirint, alone"],
                    "{}: the stability index",
                    station.name
                );
                // DIRINDEX follows its clear sky: 5 % either way moves the bias by over 15
                // points (DIRINT needs none).
                let swing = bias["dirindex, Ineichen x1.05"] - bias["dirindex, Ineichen x0.95"];
                assert!(swing.abs() > 0.15, "{}: {swing}", station.name);
            }
            Sky::Overcast => {
                assert!(rms[&default] <= 0.25, "{}: {rms:?}", station.name);
            }
            Sky::Broken => {}
        }
    }
    let default = Split::Schedule(Decomposition::default()).label();
    let n = stations.len() as f64;
    for (label, sum) in &controller_rms {
        println!(
            "mean RMS over the {n} station days: {label:24} {:5.1} %",
            100.0 * sum / n
        );
    }
    assert!(
        controller_rms
            .values()
            .all(|&r| r >= controller_rms[&default]),
        "the default is no longer the closest over the station days: {controller_rms:?}; \
         revisit Decomposition::default and docs/weather.md"
    );
}

/// BSRN Payerne's clear minutes of June 2016 (16 days; `tests/data/stations/`, pvlib's
/// `detect_clearsky` with the sun above 5°, GHI and shaded-pyranometer DHI as delivered), a
/// station none of the models was chosen on: the GHI alone through `sky-train schedule
/// --measurements` (the site's clear sky, each row against the row before) by every model,
/// each day's clear minutes with GHI above 50 W/m² against the measured DHI. Prints each
/// model's share of days within the clear-day bounds (|bias| ≤ 15 %, RMS ≤ 35 %) and
/// its median bias and RMS (docs/weather.md), and holds that the default has the smallest
/// median RMS of them (else `Decomposition::default` is to be revisited).
#[test]
fn split_of_payerne_clear_minutes() {
    let text = data("bsrn-pay-201606-clear.csv");
    let rows: Vec<(String, f64, f64)> = text
        .lines()
        .skip(1)
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            (f[0].to_owned(), num(f[1]), num(f[2]))
        })
        .collect();
    let dir = tempfile::tempdir().expect("temp dir");
    let file = dir.path().join("ghi.csv");
    let mut csv = String::from("utc,ghi_wm2\n");
    for (t, g, _) in &rows {
        csv.push_str(&format!("{t},{g}\n"));
    }
    std::fs::write(&file, csv).expect("write");
    let mut median_rms = Vec::new();
    for (name, model) in MODELS.iter().skip(1) {
        let out = run(&[
            "schedule",
            "--lat",
            "46.815",
            "--lon",
            "6.944",
            "--elevation",
            "491",
            "--measurements",
            file.to_str().expect("UTF-8 path"),
            "--decomposition",
            name,
        ])
        .unwrap_or_else(|(e, _)| panic!("{name}: {e}"));
        let mut lines = out.lines();
        let header: Vec<&str> = lines.next().expect("header").split(',').collect();
        let at = header
            .iter()
            .position(|&h| h == "dhi_wm2")
            .expect("dhi_wm2");
        // Per day: the split's errors and the measured DHI.
        let mut by_day: std::collections::BTreeMap<&str, (Vec<f64>, f64)> = Default::default();
        for ((t, g, dhi), line) in rows.iter().zip(lines) {
            if *g <= 50.0 {
                continue;
            }
            let split = num(line.split(',').nth(at).expect("dhi_wm2"));
            let day = by_day.entry(&t[..10]).or_default();
            day.0.push(split - dhi);
            day.1 += dhi;
        }
        // The days with at least 30 minutes.
        let kept: Vec<&(Vec<f64>, f64)> = by_day.values().filter(|(e, _)| e.len() >= 30).collect();
        let mut scores: Vec<(f64, f64)> = kept
            .iter()
            .map(|(e, sum)| {
                let mean = sum / e.len() as f64;
                let bias = e.iter().sum::<f64>() / e.len() as f64 / mean;
                let rms = (e.iter().map(|x| x * x).sum::<f64>() / e.len() as f64).sqrt() / mean;
                (bias, rms)
            })
            .collect();
        let within = scores
            .iter()
            .filter(|(b, r)| b.abs() <= 0.15 && *r <= 0.35)
            .count();
        let median = |v: &mut Vec<f64>| {
            v.sort_by(f64::total_cmp);
            v[v.len() / 2]
        };
        let days = scores.len();
        let mut b: Vec<f64> = scores.iter().map(|s| s.0).collect();
        let mut r: Vec<f64> = scores.iter_mut().map(|s| s.1).collect();
        let (b, r) = (median(&mut b), median(&mut r));
        // Every clear minute of those days pooled, relative to their mean measured DHI.
        let (mut n, mut e1, mut e2, mut sum) = (0.0, 0.0, 0.0, 0.0);
        for (e, s) in &kept {
            n += e.len() as f64;
            e1 += e.iter().sum::<f64>();
            e2 += e.iter().map(|x| x * x).sum::<f64>();
            sum += s;
        }
        let mean = sum / n;
        println!(
            "Payerne 2016-06, clear minutes of {days} days: {name:16} within the clear-day bounds on {within:2} days, median bias {:+5.1} %, median RMS {:5.1} %; pooled bias {:+5.1} %, RMS {:5.1} %",
            100.0 * b,
            100.0 * r,
            100.0 * e1 / n / mean,
            100.0 * (e2 / n).sqrt() / mean
        );
        assert!(days >= 10, "{days} days");
        median_rms.push((*model, r));
    }
    let default = median_rms
        .iter()
        .find(|(m, _)| *m == Decomposition::default())
        .map(|&(_, r)| r)
        .expect("the default is among the models");
    assert!(
        median_rms.iter().all(|&(_, r)| r >= default),
        "the default is no longer the closest at Payerne: {median_rms:?}; revisit \
         Decomposition::default and docs/weather.md"
    );
}

/// The published table (`dirint_coefficients.csv`, pvlib's), `[k_t'][zenith][Δk_t']`, 0-based
/// (the last Δk_t' column: not known).
fn published_table() -> [[[f64; 7]; 6]; 6] {
    let mut t = [[[f64::NAN; 7]; 6]; 6];
    for r in fixtures::rows("dirint_coefficients.csv") {
        let b = |i: usize| r[i].parse::<usize>().expect("bin") - 1;
        t[b(0)][b(1)][b(2)] = num(&r[3]);
    }
    t
}

/// The middle of each bin between `edges` (the first bin from `low`, the last up to `high`,
/// or, where `high` is `None`, the last bin open: its lower edge plus half the width below).
fn centres(low: f64, edges: &[f64; 5], high: Option<f64>) -> [f64; 6] {
    let mut c = [0.0; 6];
    let mut lower = low;
    for (i, &e) in edges.iter().enumerate() {
        c[i] = 0.5 * (lower + e);
        lower = e;
    }
    c[5] = high.map_or(edges[4] + 0.5 * (edges[4] - edges[3]), |h| {
        0.5 * (edges[4] + h)
    });
    c
}

/// The lower centre's index and the upper one's weight of `x` among `c` (the ends' values
/// beyond them).
fn bracket(x: f64, c: &[f64; 6]) -> (usize, f64) {
    if x <= c[0] {
        (0, 0.0)
    } else if x >= c[5] {
        (4, 1.0)
    } else {
        let i = (0..5).rfind(|&i| c[i] <= x).expect("inside");
        (i, (x - c[i]) / (c[i + 1] - c[i]))
    }
}

/// DIRINT's coefficient interpolated between the published table's bin centres, written out
/// here in f64 from docs/weather.md's description: linear in k_t' (bins from 0 to its cap 1),
/// the zenith (from 0° to 90°) and a known Δk_t' (from 0; the open bin's centre 0.3 + 0.075),
/// the table's value beyond the first and the last centre; bilinear over the column of an
/// unknown Δk_t'.
fn interpolated_f64(
    t: &[[[f64; 7]; 6]; 6],
    kt_prime: f64,
    zenith_deg: f64,
    stability: Option<f64>,
) -> f64 {
    let (k, tk) = bracket(kt_prime, &centres(0.0, &KT_EDGES, Some(1.0)));
    let (s, ts) = bracket(zenith_deg, &centres(0.0, &ZENITH_EDGES, Some(90.0)));
    let (d, td, d1) = match stability {
        Some(x) => {
            let (d, td) = bracket(x, &centres(0.0, &DELTA_EDGES, None));
            (d, td, d + 1)
        }
        None => (6, 0.0, 6),
    };
    let mut c = 0.0;
    for (ki, wk) in [(k, 1.0 - tk), (k + 1, tk)] {
        for (si, ws) in [(s, 1.0 - ts), (s + 1, ts)] {
            for (di, wd) in [(d, 1.0 - td), (d1, td)] {
                c += wk * ws * wd * t[ki][si][di];
            }
        }
    }
    c
}

/// A reproducible uniform number in [0, 1) (a 64-bit linear congruential generator).
fn uniform(state: &mut u64) -> f64 {
    *state = state
        .wrapping_mul(6_364_136_223_846_793_005)
        .wrapping_add(1_442_695_040_888_963_407);
    (*state >> 11) as f64 / (1u64 << 53) as f64
}

/// DIRINT's continuous form (`DirintForm::Interpolated`) against the published table: at every
/// bin centre the table's value, and at 20,000 points anywhere (k_t' −0.05 to 1.05, the zenith
/// 0° to 90°, Δk_t' unknown or 0 to 0.6) the f64 interpolation of pvlib's table written out
/// above, within the table's storage unit (2.5e-4) plus f32 rounding. Prints how far the
/// continuous coefficient departs from the binned one (docs/weather.md).
#[test]
fn dirint_interpolation_is_the_published_table_between_bin_centres() {
    let t = published_table();
    let kc = centres(0.0, &KT_EDGES, Some(1.0));
    let zc = centres(0.0, &ZENITH_EDGES, Some(90.0));
    let dc = centres(0.0, &DELTA_EDGES, None);
    for (i, k) in kc.iter().enumerate() {
        for (j, z) in zc.iter().enumerate() {
            for (d, stability) in dc.iter().map(|&d| Some(d)).chain([None]).enumerate() {
                let got = dirint_coefficient(
                    *k as f32,
                    (*z as f32).to_radians(),
                    stability.map(|x| x as f32),
                    DirintForm::Interpolated,
                );
                assert!(
                    (f64::from(got) - t[i][j][d]).abs() <= 2.5e-4 + 1e-6,
                    "centre {i} {j} {d}: {got} against {}",
                    t[i][j][d]
                );
            }
        }
    }
    let mut state = 24u64;
    let (mut worst, mut deviation, mut relative, mut sum) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    // The same where the beam is most of the global (k_t' at least 0.56).
    let (mut clear_deviation, mut clear_relative) = (0.0f64, 0.0f64);
    let n = 20_000;
    for _ in 0..n {
        let kt = -0.05 + 1.1 * uniform(&mut state);
        let zenith = 90.0 * uniform(&mut state);
        let stability = (uniform(&mut state) > 0.2).then(|| 0.6 * uniform(&mut state));
        let want = interpolated_f64(&t, kt, zenith, stability);
        let z = (zenith as f32).to_radians();
        let st = stability.map(|x| x as f32);
        let got = f64::from(dirint_coefficient(
            kt as f32,
            z,
            st,
            DirintForm::Interpolated,
        ));
        let e = (got - want).abs();
        assert!(
            e <= 2.5e-4 + 1e-6 * want.abs().max(1.0),
            "k_t' {kt}, zenith {zenith}, Δk_t' {stability:?}: {got} against {want}"
        );
        worst = worst.max(e);
        let binned = f64::from(dirint_coefficient(kt as f32, z, st, DirintForm::Binned));
        deviation = deviation.max((got - binned).abs());
        relative = relative.max((got - binned).abs() / binned);
        sum += (got - binned).abs();
        if kt >= 0.56 {
            clear_deviation = clear_deviation.max((got - binned).abs());
            clear_relative = clear_relative.max((got - binned).abs() / binned);
        }
    }
    println!(
        "interpolated coefficient within {worst:.1e} of the f64 interpolation of pvlib's table; \
         against the binned coefficient: mean |difference| {:.3}, largest {deviation:.2} \
         ({:.0} % of the binned value; with k_t' at least 0.56: {clear_deviation:.3}, {:.1} %)",
        sum / f64::from(n),
        100.0 * relative,
        100.0 * clear_relative
    );
}

/// The diffuse fraction k_d of `dirint` in `form`, or NaN where the reading is refused.
fn diffuse_fraction(g: f32, z: f32, p: f32, stability: Option<f32>, form: DirintForm) -> f64 {
    dirint(g, z, 1361.0, p, stability, form).map_or(f64::NAN, |c| f64::from(c.diffuse / c.global))
}

/// DIRINT's split is continuous across its bin edges (issue 24 item 6, as the efficacy's): at
/// every edge of k_t' (0.24 … 0.8), of DISC's two fits (k_t = 0.6), of Δk_t' (0.015 … 0.3, the
/// reading moving against a fixed reading before) and of the zenith (25° … 80°, k_t fixed), at
/// ten sun zeniths, seven stability indices and two pressures, the continuous form's diffuse
/// fraction changes across the edge by at most 4 times the relative change of the reading (for
/// the zenith edges: 4 per radian of zenith); inside the bins DISC's own slope reaches 3.2.
/// The published (binned) form steps there by more than 100 times the input's change. Near
/// the horizon the continuous form fades the beam out between 86° and 87° (at most 1 of k_d
/// per degree), where the published form cuts it at 87°.
#[test]
fn dirint_split_is_continuous_across_its_bin_edges() {
    const KT_DISC_EDGE: f32 = 0.6;
    let scale = 1370.0 / sky_core::solar::SOLAR_CONSTANT;
    let stabilities = [
        None,
        Some(0.005f32),
        Some(0.02),
        Some(0.05),
        Some(0.1),
        Some(0.2),
        Some(0.5),
    ];
    let mut worst = HashMap::new();
    for form in [DirintForm::Binned, DirintForm::Interpolated] {
        // Largest change of k_d per relative change of the reading (k_t', DISC, Δk_t' edges)
        // and per radian of zenith (zenith edges).
        let (mut reading, mut zenith) = (0.0f64, 0.0f64);
        for elevation in [0.0f32, 2300.0] {
            let p = pressure_from_elevation(elevation);
            for zd in [3.0f32, 12.5, 20.0, 30.0, 45.0, 60.0, 72.0, 78.0, 84.0, 85.5] {
                let z = zd.to_radians();
                let per_watt = kt_prime(1000.0, z, 1361.0, p) / 1000.0;
                let h = 1e-4f32;
                let across = |g: f32, f: &dyn Fn(f32) -> f64| {
                    (f(g * (1.0 + h)) - f(g * (1.0 - h))).abs() / (2.0 * f64::from(h))
                };
                for st in stabilities {
                    let f = |g: f32| diffuse_fraction(g, z, p, st, form);
                    for e in KT_EDGES {
                        reading = reading.max(across(e as f32 / per_watt, &f));
                    }
                    let disc_edge = KT_DISC_EDGE * 1361.0 * scale * z.cos().max(0.065);
                    reading = reading.max(across(disc_edge, &f));
                }
                for e in DELTA_EDGES {
                    for now in [0.3f32, 0.5, 0.65, 0.75, 0.85] {
                        let before = now - e as f32;
                        if before < 0.0 {
                            continue;
                        }
                        let f = |g: f32| {
                            let k = kt_prime(g, z, 1361.0, p);
                            diffuse_fraction(g, z, p, stability_index(k, Some(before), None), form)
                        };
                        reading = reading.max(across(now / per_watt, &f));
                    }
                }
                for e in ZENITH_EDGES {
                    for kt in [0.2f32, 0.35, 0.5, 0.6, 0.7, 0.75, 0.8] {
                        for st in stabilities {
                            let at = |zd: f32| {
                                let z = zd.to_radians();
                                diffuse_fraction(kt * 1361.0 * z.cos(), z, p, st, form)
                            };
                            let dz = 0.01f32;
                            let change = (at(e as f32 + dz) - at(e as f32 - dz)).abs();
                            zenith = zenith.max(change / f64::from((2.0 * dz).to_radians()));
                        }
                    }
                }
            }
        }
        // The beam's end at 87°: the change of k_d over ±0.01° about it, per degree.
        let mut horizon = 0.0f64;
        for kt in [0.3f32, 0.6, 0.8] {
            let at = |zd: f32| {
                let z = zd.to_radians();
                diffuse_fraction(kt * 1361.0 * z.cos().max(0.065), z, 101_325.0, None, form)
            };
            horizon = horizon.max((at(87.01) - at(86.99)).abs() / 0.02);
        }
        println!(
            "{form:?}: across the bin edges k_d changes by up to {reading:.2} times the relative \
             change of the reading, {zenith:.2} per radian of zenith; at 87° by {horizon:.2} per degree"
        );
        worst.insert(form, (reading, zenith, horizon));
    }
    let (reading, zenith, horizon) = worst[&DirintForm::Interpolated];
    assert!(reading <= 4.0 && zenith <= 4.0, "{reading} {zenith}");
    assert!(horizon <= 1.0, "{horizon}");
    let (reading, zenith, horizon) = worst[&DirintForm::Binned];
    assert!(
        reading > 100.0 && zenith > 100.0 && horizon > 5.0,
        "the published form's steps are what the interpolation removes: {reading} {zenith} {horizon}"
    );
}

/// Whether `x` is within `tolerance` of one of `edges` (where f32 and f64 may bin apart).
fn near_edge(x: f64, edges: &[f64], tolerance: f64) -> bool {
    edges.iter().any(|e| (x - e).abs() < tolerance)
}

const KT_EDGES: [f64; 5] = [0.24, 0.4, 0.56, 0.7, 0.8];
const ZENITH_EDGES: [f64; 5] = [25.0, 40.0, 55.0, 70.0, 80.0];
const DELTA_EDGES: [f64; 5] = [0.015, 0.035, 0.07, 0.15, 0.3];

/// A direct normal irradiance against pvlib's, whose beam is not cut to the global: within
/// 0.5 W/m² (the table's unit, 2.5e-4 of DISC's direct normal irradiance, at most 0.35 W/m²;
/// f32) plus `relative` of the value; returns |difference|, W/m².
fn assert_dni(got: f32, pvlib: f64, ghi: f64, zenith_deg: f64, relative: f64, what: &str) -> f64 {
    let cut = pvlib.min(ghi / zenith_deg.to_radians().cos());
    let got = f64::from(got);
    let e = (got - cut).abs();
    assert!(
        e <= 0.5 + relative * cut.abs(),
        "{what}: {got} against pvlib's {pvlib} (cut {cut})"
    );
    e
}

/// DISC, k_t', DIRINT and DIRINDEX (stability index unknown) against pvlib 0.16.1 on 600 random
/// readings, days and elevations: the pressure of the elevation within 1e-5, DISC's air mass
/// within 1e-5, k_t' within 1e-5, the direct normal irradiances within 0.5 W/m² + 1e-4 of the
/// value (DIRINDEX, a ratio of two DIRINTs: 6e-4).
#[test]
fn disc_dirint_and_dirindex_match_pvlib() {
    let (mut compared, mut worst) = (0, [0.0f64; 3]);
    for r in fixtures::rows("dirint_synthetic.csv") {
        let n = |i: usize| num(&r[i]);
        let (ghi, zenith_deg, day) = (n(0), n(1), r[2].parse::<u32>().expect("day"));
        let (elevation, pressure, i0) = (n(3), n(4), n(5));
        let (am, disc_dni, ktp, dirint_dni) = (n(7), n(8), n(9), n(10));
        let (ghi_clear, dni_clear, dirindex_dni) = (n(11), n(12), n(13));
        let p = pressure_from_elevation(elevation as f32);
        assert!(
            (f64::from(p) / pressure - 1.0).abs() < 1e-5,
            "{p} against {pressure}"
        );
        assert!((f64::from(extraterrestrial_irradiance(day)) / i0 - 1.0).abs() < 1e-5);
        let z = (zenith_deg as f32).to_radians();
        let got_am = disc_air_mass(z, pressure as f32);
        assert!(
            (f64::from(got_am) / am - 1.0).abs() < 1e-5,
            "{got_am} against {am}"
        );
        let got_ktp = kt_prime(ghi as f32, z, i0 as f32, pressure as f32);
        assert!(
            (f64::from(got_ktp) - ktp).abs() < 1e-5,
            "{got_ktp} against {ktp}"
        );
        let d = disc(ghi as f32, z, i0 as f32, pressure as f32).expect("valid");
        worst[0] = worst[0].max(assert_dni(
            d.direct_normal,
            disc_dni,
            ghi,
            zenith_deg,
            1e-4,
            "DISC",
        ));
        if near_edge(ktp, &KT_EDGES, 1e-5) || near_edge(zenith_deg, &ZENITH_EDGES, 1e-4) {
            continue;
        }
        let binned = DirintForm::Binned;
        let di = dirint(ghi as f32, z, i0 as f32, pressure as f32, None, binned).expect("valid");
        worst[1] = worst[1].max(assert_dni(
            di.direct_normal,
            dirint_dni,
            ghi,
            zenith_deg,
            1e-4,
            "DIRINT",
        ));
        let clear = ClearSky {
            global: ghi_clear as f32,
            direct_normal: dni_clear as f32,
            stability: None,
        };
        let dx = dirindex(
            ghi as f32,
            z,
            i0 as f32,
            pressure as f32,
            None,
            &clear,
            binned,
        )
        .expect("valid");
        let clear_ktp = kt_prime(ghi_clear as f32, z, i0 as f32, pressure as f32);
        if dirindex_dni.is_finite() && !near_edge(f64::from(clear_ktp), &KT_EDGES, 1e-5) {
            worst[2] = worst[2].max(assert_dni(
                dx.direct_normal,
                dirindex_dni,
                ghi,
                zenith_deg,
                6e-4,
                "DIRINDEX",
            ));
        }
        // Diffuse and beam add up to the global, the diffuse within [0, global].
        for c in [d, di, dx] {
            let sum = c.diffuse + c.direct_normal * z.cos();
            assert!((sum - c.global).abs() <= 1e-3 * c.global + 1e-3, "{c:?}");
            assert!((0.0..=c.global).contains(&c.diffuse));
        }
        compared += 1;
    }
    assert!(compared > 550, "{compared} readings compared");
    println!(
        "random readings: largest |DNI - pvlib's|: DISC {:.3}, DIRINT {:.3}, DIRINDEX {:.3} W/m2",
        worst[0], worst[1], worst[2]
    );
}

/// DIRINT and DIRINDEX with their stability indices against pvlib's on every daylight minute of
/// the station days (Δk_t' from both neighbours, as pvlib computes it, passed in; DIRINDEX with
/// pvlib's Ineichen clear sky): within 0.5 W/m² + 1e-4 of the value (DIRINDEX 6e-4).
#[test]
fn dirint_and_dirindex_match_pvlib_on_the_station_days() {
    let elevation: HashMap<&str, f32> = stations()
        .iter()
        .map(|(s, key, _)| (*key, s.site.elevation() as f32))
        .collect();
    let (mut compared, mut worst) = (0, [0.0f64; 2]);
    for r in fixtures::rows("separation_days.csv") {
        let reference = references_row(&r);
        let key = r[0].as_str();
        let day: u32 = {
            let date = &r[1][..10];
            let (y, m, d) = (
                date[..4].parse().expect("year"),
                date[5..7].parse().expect("month"),
                date[8..10].parse().expect("day"),
            );
            UtcTime::new(y, m, d, 0, 0, 0.0)
                .expect("date")
                .day_of_year()
        };
        let p = pressure_from_elevation(elevation[key]);
        let z = (reference.zenith_deg as f32).to_radians();
        let (ghi, zd) = (reference.ghi, reference.zenith_deg);
        if zd > 87.0
            || near_edge(reference.kt_prime, &KT_EDGES, 1e-5)
            || near_edge(zd, &ZENITH_EDGES, 1e-4)
            || near_edge(reference.delta_kt_prime, &DELTA_EDGES, 1e-5)
        {
            continue;
        }
        let i0 = extraterrestrial_irradiance(day);
        let ktp = kt_prime(ghi as f32, z, i0, p);
        assert!(
            (f64::from(ktp) - reference.kt_prime).abs() < 2e-5,
            "{key} {}: k_t' {ktp} against {}",
            r[1],
            reference.kt_prime
        );
        let stability = Some(reference.delta_kt_prime as f32);
        let di = dirint(ghi as f32, z, i0, p, stability, DirintForm::Binned).expect("valid");
        worst[0] = worst[0].max(assert_dni(
            di.direct_normal,
            reference.dirint_dni,
            ghi,
            zd,
            1e-4,
            "DIRINT",
        ));
        let clear_ktp = f64::from(kt_prime(reference.ghi_clear as f32, z, i0, p));
        if reference.dirindex_dni.is_finite()
            && !near_edge(clear_ktp, &KT_EDGES, 1e-5)
            && !near_edge(reference.clear_delta_kt_prime, &DELTA_EDGES, 1e-5)
        {
            let clear = ClearSky {
                global: reference.ghi_clear as f32,
                direct_normal: reference.dni_clear as f32,
                stability: Some(reference.clear_delta_kt_prime as f32),
            };
            let dx = dirindex(ghi as f32, z, i0, p, stability, &clear, DirintForm::Binned)
                .expect("valid");
            worst[1] = worst[1].max(assert_dni(
                dx.direct_normal,
                reference.dirindex_dni,
                ghi,
                zd,
                6e-4,
                "DIRINDEX",
            ));
        }
        compared += 1;
    }
    assert!(compared > 2000, "{compared} minutes compared");
    println!(
        "station days ({compared} minutes): largest |DNI - pvlib's|: DIRINT {:.3}, DIRINDEX {:.3} W/m2",
        worst[0], worst[1]
    );
}

fn references_row(r: &[String]) -> Reference {
    let n = |i: usize| num(&r[i]);
    Reference {
        zenith_deg: n(2),
        ghi: n(3),
        kt_prime: n(4),
        delta_kt_prime: n(5),
        dirint_dni: n(6),
        ghi_clear: n(7),
        dni_clear: n(8),
        clear_delta_kt_prime: n(9),
        dirindex_dni: n(10),
    }
}

/// The controller's history gives DIRINT the stability index of the reading before: a step
/// with a history splits as `decomposition::dirint` with |k_t' − k_t',before| (computed here
/// from the two readings), and without one (or after a gap of more than
/// `MAX_STABILITY_GAP_MINUTES`, or after a night step) as DIRINT with the index unknown.
#[test]
fn the_history_gives_dirint_the_reading_before() {
    let site = Site::new(32.22969, -110.95534, 786.0).expect("site");
    let lamp = example_luminaire().expect("lamp");
    let settings = Settings {
        sun: SunAlgorithm::Spa,
        decomposition: Decomposition::Dirint,
        ..Settings::default()
    };
    let p = pressure_from_elevation(786.0);
    let at = |h, m| UtcTime::new(2018, 10, 18, h, m, 0.0).expect("time");
    let zenith = |t: &UtcTime| SunPosition::new(t, &site).expect("sun").sun().zenith();
    let i0 = extraterrestrial_irradiance(291);
    let readings = [
        (at(19, 0), 820.0f32),
        (at(19, 1), 700.0),
        (at(21, 0), 650.0),
    ];
    let mut history = History::new();
    let mut previous: Option<f32> = None;
    for (i, (t, g)) in readings.iter().enumerate() {
        let s = step_with_history(
            t,
            &site,
            &settings,
            &lamp,
            Some(Measurement::GlobalIrradiance(*g)),
            &mut history,
        )
        .expect("step");
        let z = zenith(t);
        let k = kt_prime(*g, z, i0, p);
        // The 21:00 reading is two hours after the one before: no index.
        let stability = if i == 1 {
            previous.map(|before| (k - before).abs())
        } else {
            None
        };
        let want = dirint(*g, z, i0, p, stability, DirintForm::Interpolated)
            .expect("dirint")
            .diffuse;
        let got = s.weather.expect("measured").diffuse_irradiance;
        assert!(
            (got - want).abs() <= 1e-3 * want,
            "{i}: {got} against {want}"
        );
        previous = Some(k);
    }
    // A night step forgets the reading before.
    let mut history = History::new();
    for t in [at(19, 0), at(6, 0)] {
        step_with_history(&t, &site, &settings, &lamp, None, &mut history).expect("step");
    }
    assert_eq!(history, History::new());
}

const MODELS: [(&str, Decomposition); 6] = [
    ("(default)", Decomposition::Dirint),
    ("dirint", Decomposition::Dirint),
    ("dirindex", Decomposition::Dirindex),
    ("erbs", Decomposition::Erbs),
    ("engerer2", Decomposition::Engerer2),
    ("engerer2-global", Decomposition::Engerer2Global),
];

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
/// step with that setting and a history across the rows does (DIRINT's stability index from
/// the row before); without the flag it is DIRINT; an unknown model is a parameter error
/// naming the flag.
#[test]
fn schedule_decomposition_flag_selects_the_model() {
    let dir = tempfile::tempdir().expect("temp dir");
    let file = dir.path().join("ghi.csv");
    let readings = [
        ("2018-10-18T15:00:00Z", 300.0f32),
        ("2018-10-18T19:00:00Z", 760.0),
        ("2018-10-18T19:01:00Z", 700.0),
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
        let mut args = vec![
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
        ];
        if name != "(default)" {
            args.extend(["--decomposition", name]);
        }
        let out = run(&args).unwrap_or_else(|(e, _)| panic!("{name}: {e}"));
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
        let mut history = History::new();
        let times = [(15, 0), (19, 0), (19, 1), (21, 30)];
        for ((&(t, g), &d), hour) in readings.iter().zip(&dhi).zip(times) {
            let time = UtcTime::new(2018, 10, 18, hour.0, hour.1, 0.0).expect("time");
            let s = step_with_history(
                &time,
                &site,
                &settings,
                &lamp,
                Some(Measurement::GlobalIrradiance(g)),
                &mut history,
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
    for (i, a) in columns.iter().enumerate().skip(1) {
        for b in &columns[i + 1..] {
            assert!(a != b, "{columns:?}");
        }
    }
    assert_eq!(columns[0], columns[1], "the default is DIRINT");
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

/// Hostile input: `engerer2`, `dirint`, `dirindex`, `kt_prime` and the controller's paths of
/// every model (with a history) never panic; a result has 0 ≤ diffuse ≤ global and a finite,
/// non-negative beam; NaN, negative clear skies, solar times outside [0, 24] and pressures
/// outside the range are errors.
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
    let pressures = [
        f32::NAN,
        -1.0,
        0.0,
        29_999.0,
        30_000.0,
        101_325.0,
        110_000.0,
        2e5,
    ];
    let stabilities = [
        None,
        Some(f32::NAN),
        Some(-1.0),
        Some(0.0),
        Some(0.2),
        Some(5.0),
    ];
    for &g in &values {
        for &z in &zeniths {
            for &p in &pressures {
                let k = kt_prime(g, z, 1361.0, p);
                assert!((0.0..=1.0).contains(&k), "{g} {z} {p}: {k}");
                for &st in &stabilities {
                    let ok = (30_000.0..=110_000.0).contains(&p);
                    let results = [
                        dirint(g, z, 1361.0, p, st, DirintForm::Binned),
                        dirint(g, z, 1361.0, p, st, DirintForm::Interpolated),
                        disc(g, z, 1361.0, p),
                    ];
                    for r in results.into_iter().flatten() {
                        assert!(ok, "{p}");
                        assert!(r.diffuse >= 0.0 && r.diffuse <= r.global, "{g} {z} {p}");
                        assert!(r.direct_normal.is_finite() && r.direct_normal >= 0.0);
                    }
                    for &c in &values {
                        let clear = ClearSky {
                            global: c,
                            direct_normal: c,
                            stability: st,
                        };
                        for form in [DirintForm::Binned, DirintForm::Interpolated] {
                            if let Ok(r) = dirindex(g, z, 1361.0, p, st, &clear, form) {
                                assert!(ok && (0.0..=1361.0).contains(&c), "{p} {c}");
                                assert!(r.diffuse >= 0.0 && r.diffuse <= r.global, "{g} {z} {c}");
                                assert!(r.direct_normal.is_finite() && r.direct_normal >= 0.0);
                            }
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
    for (_, model) in MODELS {
        let settings = Settings {
            decomposition: model,
            ..Settings::default()
        };
        let mut history = History::new();
        for hour in 0..24 {
            let time = UtcTime::new(2030, 12, 21, hour, 0, 0.0).expect("time");
            for &g in &values {
                if let Ok(s) = step_with_history(
                    &time,
                    &site,
                    &settings,
                    &lamp,
                    Some(Measurement::GlobalIrradiance(g)),
                    &mut history,
                ) {
                    let w = s.weather.expect("measured");
                    assert!(w.diffuse_irradiance.is_finite() && w.diffuse_irradiance >= 0.0);
                }
            }
        }
    }
}
