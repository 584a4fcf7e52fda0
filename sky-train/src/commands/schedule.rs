//! `sky-train schedule`: a lighting controller's day as CSV.

use std::io::{BufWriter, Write};
use std::path::PathBuf;

use anyhow::Result;
use clap::Args;

use crate::args::{date, in_range, latitude, longitude};
use sky_core::controller::{Decomposition, Light, Settings};
use sky_core::solar::SunAlgorithm;

use crate::controller::{
    CalibrationConfig, MeasurementFormat, ScheduleConfig, schedule, schedule_measured,
};

/// `schedule`'s arguments.
#[derive(Args)]
pub struct ScheduleArgs {
    /// Latitude in degrees, north positive (-90 to 90).
    #[arg(long, value_name = "DEG", allow_negative_numbers = true, value_parser = latitude)]
    pub lat: f64,
    /// Longitude in degrees, east positive (-180 to 180).
    #[arg(long, value_name = "DEG", allow_negative_numbers = true, value_parser = longitude)]
    pub lon: f64,
    /// The UTC date, YYYY-MM-DD (years 1 to 2999); required unless --measurements is given.
    #[arg(long, value_name = "YYYY-MM-DD", value_parser = date, required_unless_present = "measurements", conflicts_with = "measurements")]
    pub date: Option<(i32, u32, u32)>,
    /// Drive the schedule by outdoor measurements instead of the clear sky: a file of readings
    /// (--measurements-format; the default CSV's header names `utc` (RFC 3339) and `global_lux`
    /// (a lux sensor) or `ghi_wm2` with optional `dhi_wm2` (pyranometers)). Thermal offsets
    /// down to -20 W/m2 (-2200 lx) count as 0, a diffuse up to max(10 W/m2, 5 %) above the
    /// global as the global; night readings are used. One output row per reading (in the
    /// stations' formats a row without a reading, flagged or missing, or with a global above
    /// what any sky gives, is skipped): the sun; the
    /// light followed (cct_k, duv, horizontal_lux, RGBW, x, y, melanopic_edi_lux: the measured
    /// light with its colour under cloud); ghi_wm2, dhi_wm2, dni_wm2 (the reading and its
    /// split: the file's diffuse, else --decomposition's); global_lux, diffuse_lux, direct_lux (the
    /// measured light through Perez's efficacies, the diffuse and direct summing to the global); clear_global_lux (the clear sky's, on the row's
    /// day's Earth-Sun distance); clear_sky_index (global_lux over clear_global_lux, empty where
    /// the clear sky is below 100 lx, at night); sky_type (the Perez sky-clearness bin, 1 overcast to 8 clear; 0 with
    /// the sun below the horizon); clear_sky_factor (the self-calibration's learned clear-sky
    /// level: clear_global_lux is the model's times it), clear_window (1 where the readings'
    /// window ending at the row is clear by Reno and Hansen's criteria, else 0) and
    /// calibration_status (learning, calibrated, drifted, sensor-suspect).
    #[arg(long, value_name = "FILE")]
    pub measurements: Option<PathBuf>,
    /// The layout of --measurements, each as the network delivers it and optionally
    /// gzip-compressed: csv (the header above), surfrad (a NOAA SURFRAD daily file: GHI
    /// dw_solar, DHI diffuse, rows with a bad flag or missing GHI skipped), midc (an NREL MIDC
    /// file, raw data or the web page's download: Year and DOY, or DATE (MM/DD/YYYY or
    /// YYYY/MM/DD), then a time column named by its time zone; the first horizontal Global...
    /// and Diffuse... columns in W/m^2), srml (a University of Oregon SRML archival file: PST, the
    /// time at the interval's end, elements 100x GHI and 300x DHI, flag 99 missing) or bsrn (a
    /// BSRN station-to-archive month: the basic measurements' record, UTC). In the stations'
    /// formats a diffuse above the global by more than max(10 W/m2, 5 %) is set aside (the
    /// global split by --decomposition; a note on stderr counts such rows), and a row whose
    /// global is above 1.5 times the extraterrestrial horizontal irradiance is skipped (a note
    /// counts them; more than 10 such rows that are also more than 1 % of the file refuse it: a
    /// clock or site that is not the station's, or a faulty sensor).
    #[arg(long, value_enum, value_name = "FORMAT", default_value_t = FormatArg::Csv, requires = "measurements")]
    pub measurements_format: FormatArg,
    /// Read only the global of --measurements, leaving out its diffuse: every row's global is
    /// split by --decomposition (dhi_wm2 is then the split's, to compare with the file's).
    #[arg(long, requires = "measurements")]
    pub global_only: bool,
    /// Minutes between rows, from 00:00 UTC (1 to 1440; not with --measurements).
    #[arg(long, value_name = "MIN", default_value_t = 10, value_parser = clap::value_parser!(u32).range(1..=1440), conflicts_with = "measurements")]
    pub step: u32,
    /// Elevation of the site in metres above sea level (-500 to 5000): the sun's parallax and
    /// the clear sky's surface pressure (default: the 1-degree grid's mean elevation, a coarse
    /// stand-in that can be hundreds of metres off in mountains: give it).
    #[arg(long, value_name = "M", allow_negative_numbers = true, value_parser = elevation)]
    pub elevation: Option<f64>,
    /// The clear atmosphere: by default the site's month (`sky-train site`: aerosol optical
    /// depth from the SoDa Linke turbidity climatology, ozone by Van Heuklon 1979, and the
    /// precipitable water at which Perez's efficacy turns a measured W/m2 into lux; each row
    /// by its month), else a named preset: record (the USNO clear-sky record's turbid sky, AOD
    /// 0.38, 300 DU, for validation against it) or clean (OPAC continental average, AOD
    /// 0.151, 300 DU). --aod, --turbidity, --ozone-du and --water-vapour replace its values.
    #[arg(long, value_enum, value_name = "PRESET")]
    pub atmosphere: Option<crate::physical::atmosphere::Preset>,
    /// Aerosol optical depth at 550 nm of the clear atmosphere (0.05 to 0.8; default the
    /// site's month's, clamped to that range, or the preset's).
    #[arg(long, value_name = "TAU", value_parser = aod, conflicts_with = "turbidity")]
    pub aod: Option<f32>,
    /// Total ozone column of the clear atmosphere, Dobson units (200 to 500; default the site's
    /// month's, or 300 with a preset). It matters in twilight: 7-14 % of the light per 50 DU.
    #[arg(long, value_name = "DU", value_parser = ozone)]
    pub ozone_du: Option<f32>,
    /// Precipitable water in cm (0 to 10) at which Perez's efficacy turns a measured W/m2 into
    /// lux (default the site's month's, or 2 with a preset; the clear sky's light itself does
    /// not depend on it, docs/daylight.md).
    #[arg(long, value_name = "CM", value_parser = water)]
    pub water_vapour: Option<f32>,
    /// Preetham's turbidity instead of --aod (2 to 8.5), mapped to the aerosol optical depth as
    /// the physical atmosphere maps it (`Atmosphere::from_turbidity`).
    #[arg(long, value_name = "T", value_parser = turbidity)]
    pub turbidity: Option<f32>,
    /// Follow the sky alone (the diffuse light: a north-facing window or a skylight) instead
    /// of the global light of sun and sky.
    #[arg(long)]
    pub sky_only: bool,
    /// The separation model splitting a GHI-only reading into diffuse and direct: dirint
    /// (Perez et al. 1992, continuous across its bins, at the site's pressure (--elevation),
    /// with each reading's stability against the row before), dirindex (Perez et al. 2002:
    /// DIRINT scaled to the clear sky's beam), erbs (Erbs et al. 1982), engerer2 (Engerer
    /// 2015's coefficients) or engerer2-global (Engerer2 with Bright and Engerer's 2019
    /// world-wide 1-minute coefficients); the clear sky of dirindex and engerer2 is the
    /// schedule's (the site's month, or --aod and the preset), not scaled by the
    /// self-calibration, and must fit the site's beam. docs/weather.md compares them with
    /// measured diffuse irradiance.
    #[arg(long, value_enum, value_name = "MODEL", default_value_t = DecompositionArg::Dirint)]
    pub decomposition: DecompositionArg,
    /// Run without the self-calibration: the clear sky (clear_global_lux, clear_sky_index)
    /// stays the model's (clear_sky_factor 1; clear_window and calibration_status empty). By
    /// default the site's clear-sky level is learned from the readings' clear periods (Reno and
    /// Hansen 2016's criteria; Jordan and Hansen 2023's for readings 2 to 30 minutes apart),
    /// one figure per clear day in four bands of sun elevation, bounded (0.75 to 1.6; a level
    /// beyond, or a day clear only above 1.6: calibration_status sensor-suspect), and applied
    /// from the next day on; readings more than 30 minutes apart are not calibrated (the
    /// columns as with this flag).
    #[arg(long, requires = "measurements")]
    pub no_self_calibration: bool,
    /// A file holding the self-calibration's learned state (36 bytes): read at the start when
    /// it exists (a corrupted or foreign file is refused), written at the end (atomically).
    #[arg(
        long,
        value_name = "FILE",
        requires = "measurements",
        conflicts_with = "no_self_calibration"
    )]
    pub calibration_state: Option<PathBuf>,
    /// Horizontal illuminance in lux at which the luminaire gives its full output (1 to 200000).
    #[arg(long, value_name = "LUX", default_value_t = 10_000.0, value_parser = full_scale_lux)]
    pub full_scale_lux: f32,
}

/// `--decomposition`.
#[derive(Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum DecompositionArg {
    /// DIRINT, Perez et al. 1992.
    Dirint,
    /// DIRINDEX, Perez et al. 2002.
    Dirindex,
    /// Engerer2, Bright and Engerer's 2019 world-wide 1-minute coefficients.
    Engerer2Global,
    /// Engerer2, Engerer 2015's coefficients.
    Engerer2,
    /// Erbs et al. 1982.
    Erbs,
}

/// `--measurements-format`.
#[derive(Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum FormatArg {
    /// CSV with a header naming utc and global_lux, or ghi_wm2 and optionally dhi_wm2.
    Csv,
    /// A NOAA SURFRAD daily file.
    Surfrad,
    /// An NREL MIDC file (raw data or the web page's download).
    Midc,
    /// A University of Oregon SRML archival file (times in PST, at the interval's end).
    Srml,
    /// A BSRN station-to-archive file (a month; gzip-compressed or not).
    Bsrn,
}

#[allow(clippy::cast_possible_truncation)]
fn aod(s: &str) -> Result<f32, String> {
    // sky-core's daylight::MIN_AOD and MAX_AOD, as decimals (Daylight::new checks them again).
    in_range(s, 0.05, 0.8, "an aerosol optical depth").map(|v| v as f32)
}

/// Preetham's turbidity, mapped to the aerosol optical depth (2 to 8.5: 0.100 to 0.75).
#[allow(clippy::cast_possible_truncation)]
fn turbidity(s: &str) -> Result<f32, String> {
    let t = in_range(s, 2.0, 8.5, "a turbidity")?;
    let atm = crate::physical::Atmosphere::from_turbidity(t).map_err(|e| e.to_string())?;
    Ok(atm.aod_550 as f32)
}

/// Precipitable water, cm (what sky-core's efficacy takes,
/// `efficacy::PRECIPITABLE_WATER_RANGE_CM`).
#[allow(clippy::cast_possible_truncation)]
fn water(s: &str) -> Result<f32, String> {
    let (lo, hi) = sky_core::efficacy::PRECIPITABLE_WATER_RANGE_CM;
    in_range(
        s,
        f64::from(lo),
        f64::from(hi),
        "a precipitable water in cm",
    )
    .map(|v| v as f32)
}

/// A site's elevation the clear sky takes (sky-core's `daylight::ELEVATION_RANGE_M`).
fn elevation(s: &str) -> Result<f64, String> {
    in_range(s, -500.0, 5000.0, "an elevation in metres")
}

#[allow(clippy::cast_possible_truncation)]
fn ozone(s: &str) -> Result<f32, String> {
    // sky-core's daylight::OZONE_RANGE_DU.
    in_range(s, 200.0, 500.0, "an ozone column in Dobson units").map(|v| v as f32)
}

/// The elevation a schedule uses: `--elevation`, else the site climatology's 1-degree grid's.
fn site_elevation(args: &ScheduleArgs) -> f64 {
    args.elevation
        .unwrap_or_else(|| crate::site::grid_elevation_m(args.lat, args.lon).clamp(-500.0, 5000.0))
}

/// Each month's (aerosol optical depth, ozone column, precipitable water) of the site's clear
/// atmosphere, the optical depth clamped to sky-core's tables' range; `--aod`/`--turbidity`,
/// `--ozone-du` and `--water-vapour` replace theirs. `None` with a preset.
///
/// # Errors
/// A [`crate::args::ParamError`] for a site the climatology refuses.
#[allow(clippy::cast_possible_truncation)]
fn monthly(args: &ScheduleArgs, elevation: f64) -> Result<Option<[(f32, f32, f32); 12]>> {
    if args.atmosphere.is_some() {
        return Ok(None);
    }
    let mut months = [(0.0, 0.0, 0.0); 12];
    for (m, out) in (1..=12).zip(months.iter_mut()) {
        let s = crate::site::site_month(args.lat, args.lon, Some(elevation), m)?;
        let aod =
            (s.aod_550 as f32).clamp(sky_core::daylight::MIN_AOD, sky_core::daylight::MAX_AOD);
        let (lo, hi) = sky_core::daylight::OZONE_RANGE_DU;
        *out = (
            args.aod.or(args.turbidity).unwrap_or(aod),
            args.ozone_du.unwrap_or((s.ozone_du as f32).clamp(lo, hi)),
            args.water_vapour.unwrap_or(s.water_vapour_cm as f32),
        );
    }
    Ok(Some(months))
}

#[allow(clippy::cast_possible_truncation)]
fn full_scale_lux(s: &str) -> Result<f32, String> {
    in_range(s, 1.0, 200_000.0, "an illuminance in lux").map(|v| v as f32)
}

/// Writes the day's schedule to `output` ([`crate::controller::schedule`]), or the schedule at
/// the times of `--measurements` driven by them ([`crate::controller::schedule_measured`]).
///
/// # Errors
/// Bad parameters as a [`crate::args::ParamError`], a failed write.
pub fn run(args: &ScheduleArgs, output: &mut dyn Write) -> Result<()> {
    let elevation = site_elevation(args);
    #[allow(clippy::cast_possible_truncation)]
    let preset = args.atmosphere.unwrap_or_default().atmosphere().aod_550 as f32;
    let config = ScheduleConfig {
        latitude: args.lat,
        longitude: args.lon,
        elevation,
        monthly: monthly(args, elevation)?,
        // Unused with --measurements (their rows carry the dates).
        date: args.date.unwrap_or((2000, 1, 1)),
        step_minutes: args.step,
        settings: Settings {
            aerosol_optical_depth: args.aod.or(args.turbidity).unwrap_or(preset),
            ozone_du: args.ozone_du.unwrap_or(sky_core::daylight::OZONE_DU),
            precipitable_water: args
                .water_vapour
                .unwrap_or(sky_core::efficacy::DEFAULT_PRECIPITABLE_WATER),
            light: if args.sky_only {
                Light::Sky
            } else {
                Light::Global
            },
            full_scale_lux: args.full_scale_lux,
            // The CLI takes the years 1-2999.
            sun: SunAlgorithm::Spa,
            decomposition: match args.decomposition {
                DecompositionArg::Engerer2Global => Decomposition::Engerer2Global,
                DecompositionArg::Engerer2 => Decomposition::Engerer2,
                DecompositionArg::Erbs => Decomposition::Erbs,
                DecompositionArg::Dirint => Decomposition::Dirint,
                DecompositionArg::Dirindex => Decomposition::Dirindex,
            },
        },
    };
    let mut out = BufWriter::new(output);
    match &args.measurements {
        Some(file) => {
            let format = match args.measurements_format {
                FormatArg::Csv => MeasurementFormat::Csv,
                FormatArg::Surfrad => MeasurementFormat::Surfrad,
                FormatArg::Midc => MeasurementFormat::Midc,
                FormatArg::Srml => MeasurementFormat::Srml,
                FormatArg::Bsrn => MeasurementFormat::Bsrn,
            };
            if let Some(state) = &args.calibration_state {
                crate::output_path::file(
                    "--calibration-state",
                    state,
                    crate::output_path::Folder::Existing,
                )?;
            }
            let calibration = CalibrationConfig {
                enabled: !args.no_self_calibration,
                state: args.calibration_state.clone(),
            };
            schedule_measured(
                &config,
                file,
                format,
                args.global_only,
                &calibration,
                &mut out,
            )?;
        }
        None => schedule(&config, &mut out)?,
    }
    out.flush()?;
    Ok(())
}
