//! Computes the firmware examples' expected values on the host and hands the linker the
//! memory map of the target's board.
//!
//! sky-core is a build-dependency as well as a dependency: here it runs on the host, and the
//! values it gives are written to `$OUT_DIR/expected.rs` (for `src/main.rs`) and
//! `$OUT_DIR/expected_fixed.rs` (for `src/bin/fixed_neural.rs`), `$OUT_DIR/sh_expected.rs` and
//! `$OUT_DIR/controller_expected.rs` (for `src/bin/controller.rs`),
//! their shared `$OUT_DIR/controller_config.rs` (also for the instruction counters), the weather
//! controllers' series of readings `$OUT_DIR/calibrated_series.rs` (for `src/weather.rs` and
//! `src/bin/calibration_instructions.rs`) and its expected values with and without the
//! self-calibration, `$OUT_DIR/calibrated_expected.rs` (for `src/bin/weather_controller.rs`)
//! and `$OUT_DIR/uncalibrated_expected.rs` (for `src/bin/weather_controller_uncalibrated.rs`),
//! as const tables, which the examples include and check against the same evaluation on the
//! target.

use std::error::Error;
use std::fmt::Write as _;
use std::path::PathBuf;
use std::{env, fs};

use sky_core::clear_period::Criteria;
use sky_core::controller::{self, History, Measurement};
use sky_core::led::Luminaire;
use sky_core::neural::{FixedNeuralSky, NeuralSky, fixed, pretrained};
use sky_core::self_calibration::{Bounds, Calibrated, SelfCalibration, Status};
use sky_core::sh::ShSky;
use sky_core::solar::{Site, SunAlgorithm, UtcTime};
use sky_core::{PreethamSky, Sun, Vec3, geom};

/// Sun zenith angles of the cases, in degrees.
const SUN_ZENITHS_DEG: [f32; 5] = [0.0, 20.0, 45.0, 70.0, 85.0];
/// Turbidities of the cases (the model's whole range, 2 to 6).
const TURBIDITIES: [f32; 3] = [2.0, 4.0, 6.0];
/// Zenith angles (degrees) of the rings of view directions; each ring has [`RING_AZIMUTHS`]
/// directions.
const RING_ZENITHS_DEG: [f32; 4] = [20.0, 45.0, 70.0, 88.0];
const RING_AZIMUTHS: u16 = 5;
/// A view below the horizon (zenith, azimuth in degrees): luminance 0 there.
const BELOW_HORIZON_DEG: (f32, f32) = (100.0, 45.0);

fn main() -> Result<(), Box<dyn Error>> {
    let out = PathBuf::from(env::var_os("OUT_DIR").ok_or("OUT_DIR is not set")?);

    // The board follows from the target; the runtime's link.x (cortex-m-rt's or riscv-rt's)
    // needs memory.x, which the linker looks for on its search path.
    let target = env::var("TARGET")?;
    let board = match target.as_str() {
        "thumbv7em-none-eabihf" => "mps2-an386",
        "thumbv7m-none-eabi" => "lm3s6965evb",
        "thumbv6m-none-eabi" => "microbit",
        "riscv32imac-unknown-none-elf" | "riscv32imc-unknown-none-elf" => "virt-rv32",
        other => {
            return Err(format!(
                "no board for target {other}: use thumbv7em-none-eabihf (mps2-an386), \
                 thumbv7m-none-eabi (lm3s6965evb), thumbv6m-none-eabi (microbit), \
                 riscv32imac-unknown-none-elf or riscv32imc-unknown-none-elf (qemu's virt)"
            )
            .into());
        }
    };
    let memory = format!("memory/{board}.x");
    fs::copy(&memory, out.join("memory.x"))?;
    println!("cargo:rustc-link-search={}", out.display());
    println!("cargo:rustc-link-arg-bins=--nmagic");
    // riscv-rt's link.x does not include memory.x itself (cortex-m-rt's does).
    if board == "virt-rv32" {
        println!("cargo:rustc-link-arg-bins=-Tmemory.x");
    }
    println!("cargo:rustc-link-arg-bins=-Tlink.x");
    println!("cargo:rerun-if-changed={memory}");
    println!("cargo:rerun-if-changed=build.rs");

    fs::write(out.join("expected.rs"), expected_table()?)?;
    fs::write(out.join("expected_fixed.rs"), expected_fixed_table()?)?;
    fs::write(out.join("sh_expected.rs"), sh_expected_table()?)?;
    fs::write(
        out.join("controller_expected.rs"),
        controller_expected_table()?,
    )?;
    fs::write(out.join("controller_config.rs"), controller_config())?;
    let series = calibrated_series()?;
    fs::write(
        out.join("calibrated_series.rs"),
        series_readings_table(&series),
    )?;
    fs::write(
        out.join("calibrated_expected.rs"),
        series_expected_table(&series, true)?,
    )?;
    fs::write(
        out.join("uncalibrated_expected.rs"),
        series_expected_table(&series, false)?,
    )?;
    Ok(())
}

/// The SH cases: sun zenith and azimuth (degrees), turbidity, bands, ringing filter.
const SH_CASES: [(f32, f32, f32, usize, bool); 5] = [
    (0.0, 0.0, 2.5, 7, true),
    (35.0, 73.0, 3.1, 7, false),
    (70.0, 200.0, 4.5, 5, true),
    (89.0, 123.0, 2.7, 7, true),
    (90.0, -30.0, 6.0, 3, true),
];
/// Directions (zenith, azimuth in degrees) at which the SH radiance and irradiance are checked.
const SH_DIRECTIONS_DEG: [(f32, f32); 6] = [
    (0.0, 0.0),
    (30.0, 10.0),
    (60.0, 140.0),
    (89.0, 250.0),
    (120.0, 45.0),
    (180.0, 0.0),
];

/// Rust source of `SH_CASES`: for each SH sky (`ShSky::new` or `new_unfiltered`) the 49 RGB
/// coefficients, and the radiance and irradiance at [`SH_DIRECTIONS_DEG`], as the host
/// computes them.
fn sh_expected_table() -> Result<String, Box<dyn Error>> {
    let f = |v: Vec3| format!("[{:?}, {:?}, {:?}]", v.x, v.y, v.z);
    let mut cases = String::new();
    for (zenith_deg, azimuth_deg, turbidity, bands, filter) in SH_CASES {
        let sun = Sun::new(zenith_deg.to_radians(), azimuth_deg.to_radians())?;
        let sky = if filter {
            ShSky::new(sun, turbidity, bands)?
        } else {
            ShSky::new_unfiltered(sun, turbidity, bands)?
        };
        let coefficients: Vec<String> = sky.coefficients().iter().map(|c| f(*c)).collect();
        let mut radiance = Vec::new();
        let mut irradiance = Vec::new();
        for (z, a) in SH_DIRECTIONS_DEG {
            let dir = geom::direction(z.to_radians(), a.to_radians());
            radiance.push(f(sky.radiance(dir)));
            irradiance.push(f(sky.irradiance(dir)));
        }
        writeln!(cases, "    ShCase {{")?;
        writeln!(cases, "        sun_zenith: {:?},", zenith_deg.to_radians())?;
        writeln!(
            cases,
            "        sun_azimuth: {:?},",
            azimuth_deg.to_radians()
        )?;
        writeln!(cases, "        turbidity: {turbidity:?},")?;
        writeln!(cases, "        bands: {bands},")?;
        writeln!(cases, "        filter: {filter},")?;
        writeln!(
            cases,
            "        coefficients: [{}],",
            coefficients.join(", ")
        )?;
        writeln!(cases, "        radiance: [{}],", radiance.join(", "))?;
        writeln!(cases, "        irradiance: [{}],", irradiance.join(", "))?;
        writeln!(cases, "    }},")?;
    }
    let directions: Vec<String> = SH_DIRECTIONS_DEG
        .iter()
        .map(|(z, a)| format!("({:?}, {:?})", z.to_radians(), a.to_radians()))
        .collect();
    Ok(format!(
        "// Generated by firmware/build.rs from sky-core on the host; do not edit.\n\
         /// The directions (zenith, azimuth; radians) of the radiance and irradiance checks.\n\
         #[allow(clippy::approx_constant, clippy::unreadable_literal)]\n\
         const SH_DIRECTIONS: [(f32, f32); {}] = [{}];\n\
         /// The SH cases and the values the host computed for them.\n\
         #[allow(clippy::approx_constant, clippy::unreadable_literal)] // computed values, as printed\n\
         const SH_CASES: [ShCase; {}] = [\n{cases}];\n",
        SH_DIRECTIONS_DEG.len(),
        directions.join(", "),
        SH_CASES.len()
    ))
}

/// Rust source of the fixed-point example's `VIEWS` and `CASES`: per network, skies across the
/// trained domain, and per sky integer directions (a zenith, rings, the sun, below the horizon,
/// and the zero vector) with the radiance `FixedNeuralSky` gives on the host.
fn expected_fixed_table() -> Result<String, Box<dyn Error>> {
    let mut cases = String::new();
    let mut count = 0;
    let mut view_count = None;
    for (name, weights) in [
        ("PREETHAM", &pretrained::PREETHAM_FIXED),
        ("HOSEK", &pretrained::HOSEK_FIXED),
    ] {
        let (t0, t1) = weights.turbidity_range;
        for (index, zenith_deg) in (0u16..).zip(SUN_ZENITHS_DEG) {
            let turbidity = t0 + (t1 - t0) * f32::from(index) / 4.0;
            let sun_azimuth_deg = f32::from(70 * index % 360);
            let (sun_zenith, sun_azimuth) = (zenith_deg.to_radians(), sun_azimuth_deg.to_radians());
            let sun = Sun::new(sun_zenith, sun_azimuth)?;
            let sky = FixedNeuralSky::new(weights, sun, turbidity)?;
            let mut views: Vec<[i16; 3]> = views_deg(zenith_deg, sun_azimuth_deg)
                .into_iter()
                .map(|(z, a)| fixed::direction_q15(geom::direction(z.to_radians(), a.to_radians())))
                .collect();
            views.push([0, 0, 0]);
            view_count = Some(views.len());
            writeln!(cases, "    Case {{")?;
            writeln!(cases, "        network: {name:?},")?;
            writeln!(cases, "        sun_zenith: {sun_zenith:?},")?;
            writeln!(cases, "        sun_azimuth: {sun_azimuth:?},")?;
            writeln!(cases, "        turbidity: {turbidity:?},")?;
            writeln!(cases, "        views: [")?;
            for dir in views {
                writeln!(cases, "            ({dir:?}, {:?}),", sky.rgb(dir))?;
            }
            writeln!(cases, "        ],")?;
            writeln!(cases, "    }},")?;
            count += 1;
        }
    }
    let view_count = view_count.ok_or("no cases")?;
    Ok(format!(
        "// Generated by firmware/build.rs from sky-core on the host; do not edit.\n\
         /// Views per case.\n\
         const VIEWS: usize = {view_count};\n\
         /// The cases and the values the host computed for them.\n\
         #[allow(clippy::approx_constant, clippy::unreadable_literal)] // computed values, as printed\n\
         const CASES: [Case; {count}] = [\n{cases}];\n"
    ))
}

/// The view directions of one case as (zenith, azimuth) in degrees: the zenith, the rings, the
/// sun itself and one direction below the horizon.
fn views_deg(sun_zenith: f32, sun_azimuth: f32) -> Vec<(f32, f32)> {
    let mut views = vec![(0.0, 0.0)];
    for (ring, &zenith) in (0u16..).zip(&RING_ZENITHS_DEG) {
        for k in 0..RING_AZIMUTHS {
            // Each ring is turned a little, so that the azimuths do not line up.
            let azimuth = 360.0 * f32::from(k) / f32::from(RING_AZIMUTHS) + 17.0 * f32::from(ring);
            views.push((zenith, azimuth));
        }
    }
    views.push((sun_zenith, sun_azimuth));
    views.push(BELOW_HORIZON_DEG);
    views
}

/// Rust source of the `VIEWS` and `CASES` consts, every f32 written in its shortest
/// round-tripping form (so the firmware reads back exactly the host's bits).
fn expected_table() -> Result<String, Box<dyn Error>> {
    let mut cases = String::new();
    let mut view_count = None;
    let skies = SUN_ZENITHS_DEG
        .iter()
        .flat_map(|&zenith| TURBIDITIES.iter().map(move |&t| (zenith, t)));
    for (index, (zenith_deg, turbidity)) in (0u16..).zip(skies) {
        let sun_azimuth_deg = f32::from(40 * index % 360);
        let (sun_zenith, sun_azimuth) = (zenith_deg.to_radians(), sun_azimuth_deg.to_radians());
        let sun = Sun::new(sun_zenith, sun_azimuth)?;
        let sky = PreethamSky::new(sun, turbidity)?;
        let neural = NeuralSky::new(&pretrained::PREETHAM, sun, turbidity)?;
        let views = views_deg(zenith_deg, sun_azimuth_deg);
        view_count = Some(views.len());

        writeln!(cases, "    Case {{")?;
        writeln!(cases, "        sun_zenith: {sun_zenith:?},")?;
        writeln!(cases, "        sun_azimuth: {sun_azimuth:?},")?;
        writeln!(cases, "        turbidity: {turbidity:?},")?;
        writeln!(cases, "        views: [")?;
        for (zenith_deg, azimuth_deg) in views {
            let (zenith, azimuth) = (zenith_deg.to_radians(), azimuth_deg.to_radians());
            let dir = geom::direction(zenith, azimuth);
            let c = sky.xyy(dir);
            let rgb = sky.rgb(dir);
            let n = neural.rgb(dir);
            let values = [c.luminance, c.x, c.y, rgb.x, rgb.y, rgb.z, n.x, n.y, n.z];
            if values.iter().any(|v| !v.is_finite()) {
                let at = format!("view {zenith_deg}°, {azimuth_deg}°");
                return Err(format!("non-finite value in {values:?} at {at}").into());
            }
            writeln!(
                cases,
                "            View {{ zenith: {zenith:?}, azimuth: {azimuth:?}, \
                 xyy: [{:?}, {:?}, {:?}], rgb: [{:?}, {:?}, {:?}], neural: [{:?}, {:?}, {:?}] }},",
                c.luminance, c.x, c.y, rgb.x, rgb.y, rgb.z, n.x, n.y, n.z
            )?;
        }
        writeln!(cases, "        ],")?;
        writeln!(cases, "    }},")?;
    }
    let case_count = SUN_ZENITHS_DEG.len() * TURBIDITIES.len();
    let view_count = view_count.ok_or("no cases")?;
    Ok(format!(
        "// Generated by firmware/build.rs from sky-core on the host; do not edit.\n\
         /// Views per case.\n\
         const VIEWS: usize = {view_count};\n\
         /// The cases and the values the host computed for them.\n\
         #[allow(clippy::approx_constant, clippy::unreadable_literal)] // computed values, as printed\n\
         const CASES: [Case; {case_count}] = [\n{cases}];\n"
    ))
}

/// The controller example's site: Vienna (latitude, longitude in degrees, elevation in metres).
const CONTROLLER_SITE: (f64, f64, f64) = (48.21, 16.37, 190.0);
/// Its UTC date: the March equinox of 2026.
const CONTROLLER_DATE: (i32, u32, u32) = (2026, 3, 20);
/// Minutes between steps (144 steps over the day).
const CONTROLLER_STEP_MIN: u32 = 10;
/// Aerosol optical depth at 550 nm of the clear sky: sky-core's default atmosphere.
const CONTROLLER_AOD: f32 = sky_core::daylight::DEFAULT_AOD;
/// Horizontal illuminance (lux) at which the luminaire gives its full output.
const CONTROLLER_FULL_SCALE_LUX: f32 = 10_000.0;
/// PWM resolution of the channel levels, bits.
const CONTROLLER_PWM_BITS: u8 = 12;

/// The controller examples' site, luminaire, and the minute of the day and UTC time of each of
/// their steps.
type ControllerDay = (Site, Luminaire<4>, Vec<(u32, UtcTime)>);

/// The controller examples' day ([`ControllerDay`]).
fn controller_day() -> Result<ControllerDay, Box<dyn Error>> {
    let (lat, lon, elevation) = CONTROLLER_SITE;
    let (year, month, day) = CONTROLLER_DATE;
    let mut times = Vec::new();
    for minute in (0..24 * 60).step_by(usize::try_from(CONTROLLER_STEP_MIN)?) {
        times.push((
            minute,
            UtcTime::new(year, month, day, minute / 60, minute % 60, 0.0)?,
        ));
    }
    Ok((
        Site::new(lat, lon, elevation)?,
        controller::example_luminaire()?,
        times,
    ))
}

/// The controller examples' settings: the global light of the default atmosphere.
fn controller_settings() -> controller::Settings {
    controller::Settings {
        aerosol_optical_depth: CONTROLLER_AOD,
        ozone_du: sky_core::daylight::OZONE_DU,
        precipitable_water: sky_core::efficacy::DEFAULT_PRECIPITABLE_WATER,
        light: controller::Light::Global,
        full_scale_lux: CONTROLLER_FULL_SCALE_LUX,
        sun: SunAlgorithm::Fast,
        decomposition: controller::Decomposition::Erbs,
    }
}

/// CCT and Duv of a step, 0 where undefined (|Duv| > 0.05), as the examples compare them.
fn cct_or_zero(s: &controller::Step) -> (f32, f32) {
    s.cct.map_or((0.0, 0.0), |c| (c.kelvin, c.duv))
}

/// Rust source of the controller example's `STEPS`: for every step of the day (step k at
/// k × [`CONTROLLER_STEP_MIN`] minutes), what
/// [`controller::step`] (the function `sky-train schedule` calls) gives on the host.
fn controller_expected_table() -> Result<String, Box<dyn Error>> {
    let (site, lamp, times) = controller_day()?;
    let mut steps = String::new();
    let mut count = 0;
    for (minute, time) in times {
        let s = controller::step(&time, &site, &controller_settings(), &lamp, None)?;
        let (cct_k, duv) = cct_or_zero(&s);
        let pwm = s.drive.quantise(CONTROLLER_PWM_BITS)?;
        // The fast sun's degrees are f32 values widened: the table keeps them as f32, and the
        // firmware compares them widened again, bit for bit.
        let exact_f32 = |v: f64| {
            #[allow(clippy::cast_possible_truncation)]
            let narrow = v as f32;
            if f64::from(narrow).to_bits() == v.to_bits() {
                Ok(narrow)
            } else {
                Err(format!(
                    "sun angle {v:?} at minute {minute} is not an f32 value"
                ))
            }
        };
        writeln!(
            steps,
            "    Expected {{ zenith_deg: {:?}, azimuth_deg: {:?}, \
             lux: {:?}, cct_k: {:?}, duv: {:?}, levels: {:?}, pwm: {pwm:?} }},",
            exact_f32(s.sun.zenith_deg())?,
            exact_f32(s.sun.azimuth_deg())?,
            s.illuminance.y,
            cct_k,
            duv,
            s.drive.levels,
        )?;
        count += 1;
    }
    Ok(format!(
        "// Generated by firmware/build.rs from sky-core on the host; do not edit.\n\
         /// Every step of the day and the values the host computed for it.\n\
         #[allow(clippy::approx_constant, clippy::unreadable_literal)] // computed values, as printed\n\
         const STEPS: [Expected; {count}] = [\n{steps}];\n"
    ))
}

/// Rust source of the controller examples' configuration: site, date, minutes between steps,
/// aerosol optical depth, full scale and PWM resolution (`controller_config.rs`, included by all
/// three).
fn controller_config() -> String {
    format!(
        "// Generated by firmware/build.rs; do not edit.\n\
         /// Site: latitude, longitude (degrees), elevation (m).\n\
         const SITE: (f64, f64, f64) = {CONTROLLER_SITE:?};\n\
         /// UTC date (year, month, day).\n\
         const DATE: (i32, u32, u32) = {CONTROLLER_DATE:?};\n\
         /// Minutes between steps, from 00:00 UTC (the checks' tables hold the steps themselves).\n\
         #[allow(dead_code)]\n\
         const STEP_MINUTES: u32 = {CONTROLLER_STEP_MIN};\n\
         /// Aerosol optical depth at 550 nm.\n\
         const AOD: f32 = {CONTROLLER_AOD:?};\n\
         /// Horizontal illuminance (lux) at full output.\n\
         const FULL_SCALE_LUX: f32 = {CONTROLLER_FULL_SCALE_LUX:?};\n\
         /// PWM resolution, bits.\n\
         const PWM_BITS: u8 = {CONTROLLER_PWM_BITS};\n"
    )
}

/// The synthesized sky of the weather controllers' last day: the reading over the clear day's
/// at `hours` UTC. Clear until 08:00, a passing cloud to 08:30 (down to 0.4), clear again until
/// 10:00, clouding over until 12:00, overcast (0.25) afterwards.
fn cloud_factor(hours: f32) -> f32 {
    use core::f32::consts::PI;
    match hours {
        h if h < 8.0 => 1.0,
        h if h < 8.5 => 1.0 - 0.6 * (PI * (h - 8.0) / 0.5).sin().powi(2),
        h if h < 10.0 => 1.0,
        h if h < 12.0 => 1.0 - 0.375 * (1.0 - (PI * (h - 10.0) / 2.0).cos()),
        _ => 0.25,
    }
}

/// The calibrated series' dates: three clear days, then, after a restart, the controller
/// example's day with its passing cloud and overcast afternoon ([`cloud_factor`]).
const SERIES_DATES: [(i32, u32, u32); 4] =
    [(2026, 3, 17), (2026, 3, 18), (2026, 3, 19), CONTROLLER_DATE];
/// The day of [`SERIES_DATES`] before which the firmware restarts: the self-calibration's
/// state saved (`to_bytes`) and restored (`from_bytes`), the rest of RAM lost (DIRINT's
/// history among it).
const SERIES_RESTART_DAY: usize = 3;

/// The sensor's clear-day reading over the clear sky's irradiance with the sun `elevation_deg`
/// high: 1.05 + 0.1 (1 − sin e), a site cleaner than the default atmosphere (τ₅₅₀ 0.38), more
/// so with the sun low, as the measured stations are (`docs/weather.md`, "Self-calibration").
fn sensor_level(elevation_deg: f64) -> f64 {
    1.05 + 0.1 * (1.0 - elevation_deg.to_radians().sin().max(0.0))
}

/// The weather controllers' series: the UTC time and the reading of every step, every
/// [`CONTROLLER_STEP_MIN`] minutes from 00:00 UTC of each of [`SERIES_DATES`]. The sensors
/// take turns as a lux sensor, a pyranometer and a pyranometer pair (global and diffuse); on a
/// clear day they read the clear sky (the geometric sun's `Daylight::new` at [`CONTROLLER_AOD`]
/// in lux, [`controller::clear_sky_irradiance`] of it in W/m²; the controller's own clear sky
/// is the refracted one at the site, so this sensor reads its sky a little differently from
/// the controller's model, as a real one does) times [`sensor_level`], on the last day
/// times [`cloud_factor`] too; the pair's diffuse is the clear sky's share of it (its diffuse
/// illuminance over its global), rising to all of it as the cloud thickens (factor 0.25).
fn calibrated_series() -> Result<Vec<(UtcTime, Measurement)>, Box<dyn Error>> {
    let (site, _, _) = controller_day()?;
    let mut series = Vec::new();
    for (day_index, &(year, month, day)) in SERIES_DATES.iter().enumerate() {
        for minute in (0..24 * 60).step_by(usize::try_from(CONTROLLER_STEP_MIN)?) {
            let time = UtcTime::new(year, month, day, minute / 60, minute % 60, 0.0)?;
            let sun = controller_settings().sun.position(&time, &site)?;
            let daylight = sky_core::daylight::Daylight::new(sun.sun(), CONTROLLER_AOD)?;
            let clear_lux = daylight.global().y;
            let clear =
                controller::clear_sky_irradiance(clear_lux, sun.sun().zenith(), time.day_of_year());
            #[allow(clippy::cast_precision_loss)] // minutes of a day
            let cloud = if day_index + 1 == SERIES_DATES.len() {
                f64::from(cloud_factor(minute as f32 / 60.0))
            } else {
                1.0
            };
            let level = sensor_level(sun.elevation_deg()) * cloud;
            let clear_share = if clear_lux > 0.0 {
                f64::from(daylight.diffuse().y / clear_lux)
            } else {
                1.0
            };
            // As sensors report them, in f32.
            #[allow(clippy::cast_possible_truncation)]
            let reading = match series.len() % 3 {
                0 => Measurement::GlobalIlluminance((f64::from(clear_lux) * level) as f32),
                1 => Measurement::GlobalIrradiance((f64::from(clear) * level) as f32),
                _ => {
                    let global = f64::from(clear) * level;
                    let share = clear_share + (1.0 - clear_share) * (1.0 - cloud) / 0.75;
                    Measurement::Irradiance {
                        global: global as f32,
                        diffuse: (global * share.min(1.0)) as f32,
                    }
                }
            };
            series.push((time, reading));
        }
    }
    Ok(series)
}

/// The calibrated series' settings: the controller examples' with the default separation
/// model (DIRINT, with its history).
fn series_settings() -> controller::Settings {
    controller::Settings {
        decomposition: controller::Decomposition::Dirint,
        ..controller_settings()
    }
}

/// The self-calibration of the series: Jordan & Hansen 2023's criteria for its interval, the
/// site's longitude, the default bounds.
fn series_calibration() -> Result<(Criteria, u32, f32, Bounds), Box<dyn Error>> {
    #[allow(clippy::cast_precision_loss)] // 10
    let criteria = Criteria::jordan_hansen_2023(CONTROLLER_STEP_MIN as f32)?;
    #[allow(clippy::cast_possible_truncation)] // degrees
    let longitude = CONTROLLER_SITE.1 as f32;
    Ok((
        criteria,
        60 * CONTROLLER_STEP_MIN,
        longitude,
        Bounds::DEFAULT,
    ))
}

/// A status as the firmware stores it: 0 learning, 1 calibrated, 2 drifted, 3 sensor suspect.
fn status_code(status: Status) -> u8 {
    match status {
        Status::Learning => 0,
        Status::Calibrated => 1,
        Status::Drifted => 2,
        Status::SensorSuspect => 3,
    }
}

/// Rust source of the series' configuration and readings (`calibrated_series.rs`).
fn series_readings_table(series: &[(UtcTime, Measurement)]) -> String {
    let readings: Vec<String> = series
        .iter()
        .map(|(_, r)| match *r {
            Measurement::GlobalIlluminance(v) => format!("Measurement::GlobalIlluminance({v:?})"),
            Measurement::GlobalIrradiance(v) => format!("Measurement::GlobalIrradiance({v:?})"),
            Measurement::Irradiance { global, diffuse } => {
                format!("Measurement::Irradiance {{ global: {global:?}, diffuse: {diffuse:?} }}")
            }
        })
        .collect();
    format!(
        "// Generated by firmware/build.rs from sky-core on the host; do not edit.\n\
         /// The series' UTC dates (year, month, day), each stepped every `STEP_MINUTES` from 00:00.\n\
         const SERIES_DATES: [(i32, u32, u32); {}] = {SERIES_DATES:?};\n\
         /// The day before which the firmware restarts (the calibration's state saved and restored).\n\
         const SERIES_RESTART_DAY: usize = {SERIES_RESTART_DAY};\n\
         /// The reading of each step: lux (a lux sensor) or W/m² (a pyranometer, a pair).\n\
         #[allow(clippy::approx_constant, clippy::unreadable_literal)] // computed values, as printed\n\
         const READINGS: [Measurement; {}] = [{}];\n",
        SERIES_DATES.len(),
        series.len(),
        readings.join(", ")
    )
}

/// Rust source of the series' expected values (`SERIES`): every step of [`calibrated_series`]
/// through [`controller::step_calibrated`] with a [`SelfCalibration`] carried across the restart
/// in its bytes (`SAVED_STATE`, the bytes saved there), or, with `calibrated` false, through
/// [`controller::step_with_history`] alone (the build whose flash the calibrated one's is
/// compared with); DIRINT's history is lost at the restart in both.
fn series_expected_table(
    series: &[(UtcTime, Measurement)],
    calibrated: bool,
) -> Result<String, Box<dyn Error>> {
    let (site, lamp, _) = controller_day()?;
    let settings = series_settings();
    let (criteria, interval, longitude, bounds) = series_calibration()?;
    let mut cal = SelfCalibration::new(criteria, interval, longitude, bounds)?;
    let mut history = History::new();
    let steps_per_day = series.len() / SERIES_DATES.len();
    let mut saved = None;
    let mut steps = String::new();
    for (index, &(time, reading)) in series.iter().enumerate() {
        if index == SERIES_RESTART_DAY * steps_per_day {
            history = History::new();
            if calibrated {
                let bytes = cal.to_bytes();
                cal = SelfCalibration::from_bytes(&bytes, criteria, interval, longitude, bounds)?;
                saved = Some(bytes);
            }
        }
        let m = reading;
        let (s, c) = if calibrated {
            controller::step_calibrated(&time, &site, &settings, &lamp, m, &mut cal, &mut history)?
        } else {
            let s = controller::step_with_history(
                &time,
                &site,
                &settings,
                &lamp,
                Some(m),
                &mut history,
            )?;
            let nothing = Calibrated {
                factor: 1.0,
                verdict: sky_core::clear_period::Verdict::default(),
                status: Status::Learning,
            };
            (s, nothing)
        };
        let w = s.weather.ok_or("a measured step has its weather")?;
        writeln!(
            steps,
            "    SeriesExpected {{ lux: {:?}, cct_k: {:?}, duv: {:?}, diffuse: {:?}, \
             clear_sky_index: {:?}, clear_sky_factor: {:?}, factor: {:?}, levels: {:?}, \
             pwm: {:?}, sky_type: {}, status: {}, newly_clear: {} }},",
            s.illuminance.y,
            cct_or_zero(&s).0,
            cct_or_zero(&s).1,
            w.diffuse_irradiance,
            w.clear_sky_index.unwrap_or(-1.0),
            w.clear_sky_factor,
            c.factor,
            s.drive.levels,
            s.drive.quantise(CONTROLLER_PWM_BITS)?,
            w.sky_type,
            status_code(c.status),
            u8::try_from(c.verdict.newly_clear)?,
        )?;
    }
    let state = match saved {
        Some(bytes) => format!(
            "/// The self-calibration's state saved at the restart ({} bytes).\n\
             const SAVED_STATE: [u8; {}] = {bytes:?};\n",
            bytes.len(),
            bytes.len()
        ),
        None => String::new(),
    };
    Ok(format!(
        "// Generated by firmware/build.rs from sky-core on the host; do not edit.\n\
         /// Every step of the calibrated series and the values the host computed for it.\n\
         #[allow(clippy::approx_constant, clippy::unreadable_literal)] // computed values, as printed\n\
         const SERIES: [SeriesExpected; {}] = [\n{steps}];\n{state}",
        series.len()
    ))
}
