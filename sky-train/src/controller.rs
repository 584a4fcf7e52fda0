//! The lighting controller's day on the host: `sky-train schedule` (sun, colour temperature,
//! illuminance and RGBW levels every few minutes of a day, or at the times of a file of outdoor
//! measurements) and `sky-train cct` (CCT and Duv of chromaticities), both through sky-core, so
//! the firmware computes the same values.

use std::io::Write;

use anyhow::{Context, Result};
use std::path::Path;

use sky_core::clear_period::Criteria;
use sky_core::controller::{
    History, Measurement, Settings, Step, example_luminaire, step, step_calibrated,
    step_with_history,
};
use sky_core::self_calibration::{Bounds, Calibrated, SelfCalibration};
use sky_core::solar::{Site, UtcTime};

use crate::captures::manifest::UnixTime;

use crate::args::ParamError;

/// What `schedule` needs.
#[derive(Debug, Clone, Copy)]
pub struct ScheduleConfig {
    /// Latitude, degrees north.
    pub latitude: f64,
    /// Longitude, degrees east.
    pub longitude: f64,
    /// Elevation, metres.
    pub elevation: f64,
    /// The UTC date (year, month, day).
    pub date: (i32, u32, u32),
    /// Minutes between rows (1 to 1440).
    pub step_minutes: u32,
    /// The controller's settings: aerosol optical depth, the light followed, full scale.
    pub settings: Settings,
    /// Each month's aerosol optical depth, ozone column and precipitable water (January
    /// first), in place of the settings' for a row of that month; `None` keeps the settings'
    /// all year.
    pub monthly: Option<[(f32, f32, f32); 12]>,
}

impl ScheduleConfig {
    /// The settings for a time in `month` (1-12): [`Self::settings`] with the month's
    /// aerosol optical depth, ozone column and precipitable water when [`Self::monthly`] has
    /// them.
    #[must_use]
    pub fn settings_in(&self, month: u32) -> Settings {
        match self.monthly {
            Some(months) => {
                let (aod, ozone, water) = months[(month.clamp(1, 12) - 1) as usize];
                Settings {
                    aerosol_optical_depth: aod,
                    ozone_du: ozone,
                    precipitable_water: water,
                    ..self.settings
                }
            }
            None => self.settings,
        }
    }
}

/// The CSV header of `schedule`.
///
/// `horizontal_lux`, `x`, `y`, `cct_k`, `duv` and `melanopic_edi_lux` are of the light followed
/// (global, or the sky alone), `cct_k` and `duv` empty where |Duv| > 0.05; `global_lux`,
/// `diffuse_lux` and `direct_lux` are the clear-sky daylight's. With measurements the header is
/// [`MEASURED_HEADER`].
pub const SCHEDULE_HEADER: &str = "utc,sun_zenith_deg,sun_azimuth_deg,sun_elevation_deg,apparent_zenith_deg,cct_k,duv,horizontal_lux,red,green,blue,white,global_lux,diffuse_lux,direct_lux,x,y,melanopic_edi_lux";

/// The columns of `schedule --measurements` after the sun's and the light followed's
/// ([`MEASURED_HEADER`]).
pub const MEASURED_COLUMNS: &str = "ghi_wm2,dhi_wm2,dni_wm2,global_lux,diffuse_lux,direct_lux,clear_global_lux,clear_sky_index,sky_type,clear_sky_factor,clear_window,calibration_status";

/// The CSV header of `schedule --measurements`. `horizontal_lux`, `x`, `y`, `cct_k`, `duv`,
/// `melanopic_edi_lux` and the RGBW levels are of the light followed (the measured global or
/// diffuse light with its colour under cloud); `ghi_wm2` the reading (or a lux reading over
/// Perez's global efficacy), `dhi_wm2` the file's diffuse where it has one and else the split
/// of the settings' separation model (DIRINT by default, `--decomposition`), `dni_wm2` the direct normal of that split; `global_lux`, `diffuse_lux` and
/// `direct_lux` (on the horizontal plane) the measured light through Perez's global efficacy
/// and its diffuse and direct parts (the global apportioned by his diffuse and direct
/// efficacies, so they sum to it: `sky_core::measurement::Reading::parts_illuminance`);
/// `clear_global_lux` the clear sky's global illuminance, `clear_sky_index` the ratio
/// `global_lux / clear_global_lux`, empty where the clear sky is below
/// `sky_core::controller::MIN_CLEAR_SKY_LUX` (100 lx); `sky_type` the Perez sky-clearness bin
/// (1-8, 0 with the sun below the horizon); `clear_sky_factor` the site's clear-sky level
/// learned by the self-calibration before this row (`sky_core::self_calibration`; the model's
/// clear sky times it is `clear_global_lux`; 1 with the calibration off), `clear_window` 1
/// where the window of readings ending at this row is clear by Reno & Hansen's criteria
/// (`sky_core::clear_period`), else 0 (empty with the calibration off), `calibration_status`
/// `learning`, `calibrated`, `drifted` or `sensor-suspect` (empty with it off).
pub const MEASURED_HEADER: &str = "utc,sun_zenith_deg,sun_azimuth_deg,sun_elevation_deg,apparent_zenith_deg,cct_k,duv,horizontal_lux,red,green,blue,white,x,y,melanopic_edi_lux,ghi_wm2,dhi_wm2,dni_wm2,global_lux,diffuse_lux,direct_lux,clear_global_lux,clear_sky_index,sky_type,clear_sky_factor,clear_window,calibration_status";

/// How a measurement file is laid out.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum MeasurementFormat {
    /// CSV with a header naming `utc` and `global_lux`, or `ghi_wm2` and optionally `dhi_wm2`
    /// ([`parse_measurements`]).
    #[default]
    Csv,
    /// A NOAA SURFRAD daily file as the network delivers it: two header lines (station; lat,
    /// lon, elevation), then fixed-width rows of year, day of year, month, day, hour, minute
    /// (UTC), decimal time, sun zenith, then value-and-flag pairs, `dw_solar` (GHI) the first,
    /// `direct_n` the third and `diffuse` the fourth (pvlib's `iotools.read_surfrad` column
    /// list). A row whose GHI is missing (−9999.9) or flagged bad (flag not 0) is skipped; a
    /// missing or flagged diffuse leaves the GHI alone (split by `--decomposition`).
    Surfrad,
    /// An NREL MIDC raw-data CSV file as the network delivers it: a header with `Year`, `DOY`
    /// and, after it, the time column named by the station's standard time zone (`EST`, `CST`,
    /// `MST`, `PST` or `UTC`) holding HHMM; GHI the first column whose name starts with
    /// `Global` and holds `[W/m^2]` (not a standard deviation), DHI the first starting with
    /// `Diffuse` likewise. Values of −7999 or less are missing: a row without the GHI is
    /// skipped, a row without the DHI keeps the GHI alone.
    Midc,
}

/// One row of a measurement file: its line, UTC time and reading.
#[derive(Debug, Clone, Copy)]
pub struct MeasuredRow {
    /// The file's 1-based line number of the row.
    pub line: usize,
    /// The time of the reading.
    pub time: UtcTime,
    /// The same, as Unix time (for the output's RFC 3339).
    pub unix: UnixTime,
    /// The reading.
    pub measurement: Measurement,
}

/// The largest measurement file read, in bytes: a year of readings every minute (525,600
/// lines of some 40 bytes) fits three times over.
pub const MAX_MEASUREMENT_BYTES: u64 = 64 << 20;

/// Reads the measurement file `path` of `format` row by row, at most [`MAX_MEASUREMENT_BYTES`]
/// long, handing each row to `each` as it is read (memory does not grow with the rows).
///
/// # Errors
/// A [`ParamError`] naming `--measurements` and the file: it is not a regular file, cannot be
/// read, is too long ([`crate::csv_input::open`]), or its parser refuses it
/// ([`parse_measurements`]); or `each`'s error.
pub fn read_measurements(
    path: &Path,
    format: MeasurementFormat,
    each: &mut dyn FnMut(&MeasuredRow) -> Result<()>,
) -> Result<()> {
    let source = format!("--measurements {}", path.display());
    let file = crate::csv_input::open(path, MAX_MEASUREMENT_BYTES)
        .map_err(|e| ParamError(format!("{source}: {e}")))?;
    parse_measurements(&mut std::io::BufReader::new(file), &source, format, each)
}

/// The thermal-offset and range rule is sky-core's ([`sky_core::measurement::Measurement`]);
/// a field must at least be a finite number.
fn field_number(text: &str) -> Option<f32> {
    text.parse::<f32>().ok().filter(|x| x.is_finite())
}

/// Parses outdoor measurements of `format` ([`MeasurementFormat`]; [`crate::csv_input::lines`]
/// for the line rules) and hands each row to `each`. For [`MeasurementFormat::Csv`]: a header
/// naming the columns `utc` (RFC 3339) and either `global_lux` or `ghi_wm2` with an optional
/// `dhi_wm2` (in any order, any case, each once; other columns are ignored), then one reading
/// per line (blank lines and `#` comments skipped): finite numbers, the times strictly
/// increasing. Thermal offsets, a diffuse slightly above the global and night readings are
/// sky-core's rules ([`sky_core::measurement::Measurement`]), applied by the step.
///
/// # Errors
/// A one-line [`ParamError`] starting with `source` and naming the line and the column for a
/// missing, repeated or ambiguous column, a bad time, a field that is not a number, or a time
/// not after the one before; none for a file without rows.
pub fn parse_measurements(
    input: &mut dyn std::io::BufRead,
    source: &str,
    format: MeasurementFormat,
    each: &mut dyn FnMut(&MeasuredRow) -> Result<()>,
) -> Result<()> {
    let mut lines = crate::csv_input::lines(input, source);
    let mut next = || loop {
        match lines.next_line() {
            Some(Ok(l)) if l.starts_with('#') && format == MeasurementFormat::Csv => {}
            other => return other.transpose().map(|l| l.map(|l| (lines.line(), l))),
        }
    };
    let Some((header_line, header)) = next()? else {
        return Err(ParamError(format!("{source}: the file is empty (no header line)")).into());
    };
    let layout = match format {
        MeasurementFormat::Csv => Layout::csv(source, header_line, &header)?,
        MeasurementFormat::Midc => Layout::midc(source, header_line, &header)?,
        MeasurementFormat::Surfrad => {
            // The station's name, then its latitude, longitude and elevation.
            if next()?.is_none() {
                return Err(ParamError(format!(
                    "{source}: a SURFRAD file has two header lines (station; latitude, longitude, elevation)"
                ))
                .into());
            }
            Layout::Surfrad
        }
    };
    let mut previous: Option<(usize, f64)> = None;
    while let Some((n, line)) = next()? {
        let error = |what: String| ParamError(format!("{source} line {n}: {what}"));
        let Some((unix, measurement)) = layout.row(&line, &error)? else {
            continue;
        };
        if let Some((line, t)) = previous
            && unix.0 <= t
        {
            return Err(error(format!(
                "utc {}: not after the time on line {line} (the rows must be in time order, each time once)",
                unix.rfc3339()
            ))
            .into());
        }
        previous = Some((n, unix.0));
        let (y, mo, d, h, mi, sec) = unix.to_civil();
        let time = UtcTime::new(y, mo, d, h, mi, sec).map_err(|e| error(format!("utc: {e}")))?;
        each(&MeasuredRow {
            line: n,
            time,
            unix,
            measurement,
        })?;
    }
    Ok(())
}

/// Where a file's fields are.
enum Layout {
    /// `utc` and `global_lux`, or `ghi_wm2` and optionally `dhi_wm2`, by column index.
    Csv {
        utc: usize,
        lux: Option<usize>,
        ghi: Option<usize>,
        dhi: Option<usize>,
    },
    /// Year, day of year, HHMM local standard time `offset_hours` behind UTC, GHI, DHI.
    Midc {
        year: usize,
        doy: usize,
        hhmm: usize,
        offset_hours: u32,
        ghi: usize,
        dhi: Option<usize>,
    },
    /// Fixed columns (see [`MeasurementFormat::Surfrad`]).
    Surfrad,
}

/// A MIDC value at or below this is missing.
const MIDC_MISSING: f32 = -7999.0;

/// A SURFRAD value at or below this is missing (they are written −9999.9).
const SURFRAD_MISSING: f32 = -9999.0;

impl Layout {
    fn csv(source: &str, header_line: usize, header: &str) -> Result<Self, ParamError> {
        use crate::csv_input::shown;
        let columns: Vec<String> = header
            .split(',')
            .map(|c| c.trim().to_ascii_lowercase())
            .collect();
        for (i, c) in columns.iter().enumerate() {
            let known = ["utc", "global_lux", "ghi_wm2", "dhi_wm2"].contains(&c.as_str());
            if known && columns[..i].contains(c) {
                return Err(ParamError(format!(
                    "{source} line {header_line}: the header `{}` names the column {c} twice (columns {} and {})",
                    shown(header),
                    columns[..i].iter().position(|h| h == c).unwrap_or(0) + 1,
                    i + 1
                )));
            }
        }
        let find = |c: &str| columns.iter().position(|h| h == c);
        let missing = || {
            ParamError(format!(
                "{source} line {header_line}: the header `{}` needs the columns utc and global_lux, or utc and ghi_wm2 (with dhi_wm2 optionally)",
                shown(header)
            ))
        };
        let utc = find("utc").ok_or_else(missing)?;
        let (lux, ghi, dhi) = (find("global_lux"), find("ghi_wm2"), find("dhi_wm2"));
        if lux.is_some() && (ghi.is_some() || dhi.is_some()) || (lux.is_none() && ghi.is_none()) {
            return Err(missing());
        }
        Ok(Self::Csv { utc, lux, ghi, dhi })
    }

    fn midc(source: &str, header_line: usize, header: &str) -> Result<Self, ParamError> {
        use crate::csv_input::shown;
        let columns: Vec<String> = header
            .split(',')
            .map(|c| c.trim().to_ascii_lowercase())
            .collect();
        let bad = |what: &str| {
            ParamError(format!(
                "{source} line {header_line}: the MIDC header `{}` {what}",
                shown(header)
            ))
        };
        let find = |c: &str| columns.iter().position(|h| h == c);
        let year = find("year").ok_or_else(|| bad("has no Year column"))?;
        let doy = find("doy").ok_or_else(|| bad("has no DOY column"))?;
        let hhmm = doy + 1;
        let offset_hours = match columns.get(hhmm).map(String::as_str) {
            Some("utc" | "gmt" | "ut") => 0,
            Some("est") => 5,
            Some("cst") => 6,
            Some("mst") => 7,
            Some("pst") => 8,
            _ => {
                return Err(bad(
                    "has no time column after DOY named EST, CST, MST, PST or UTC",
                ));
            }
        };
        let irradiance = |start: &str| {
            columns
                .iter()
                .position(|c| c.starts_with(start) && c.contains("[w/m^2]") && !c.contains("stdev"))
        };
        let ghi = irradiance("global")
            .ok_or_else(|| bad("has no column starting with `Global` in [W/m^2]"))?;
        Ok(Self::Midc {
            year,
            doy,
            hhmm,
            offset_hours,
            ghi,
            dhi: irradiance("diffuse"),
        })
    }

    /// The time and reading of one data line; `None` for a row without a reading (a missing or
    /// flagged GHI in the stations' formats).
    fn row(
        &self,
        line: &str,
        error: &dyn Fn(String) -> ParamError,
    ) -> Result<Option<(UnixTime, Measurement)>, ParamError> {
        use crate::csv_input::shown;
        let reading = |global: f32, diffuse: Option<f32>| match diffuse {
            Some(diffuse) => Measurement::Irradiance { global, diffuse },
            None => Measurement::GlobalIrradiance(global),
        };
        match *self {
            Self::Csv { utc, lux, ghi, dhi } => {
                let fields: Vec<&str> = line.split(',').map(str::trim).collect();
                let at = |i: usize, column: &str| {
                    fields
                        .get(i)
                        .copied()
                        .ok_or_else(|| error(format!("no {column} field")))
                };
                let number = |i: usize, column: &str| -> Result<f32, ParamError> {
                    let v = at(i, column)?;
                    field_number(v).ok_or_else(|| {
                        error(format!("{column} `{}`: expected a finite number", shown(v)))
                    })
                };
                let text = at(utc, "utc")?;
                let unix = UnixTime::parse(text).map_err(|e| error(format!("utc: {e:#}")))?;
                let measurement = match (lux, ghi) {
                    (Some(i), _) => Measurement::GlobalIlluminance(number(i, "global_lux")?),
                    (None, Some(g)) => reading(
                        number(g, "ghi_wm2")?,
                        dhi.map(|d| number(d, "dhi_wm2")).transpose()?,
                    ),
                    (None, None) => return Err(error("no ghi_wm2 or global_lux column".into())),
                };
                Ok(Some((unix, measurement)))
            }
            Self::Midc {
                year,
                doy,
                hhmm,
                offset_hours,
                ghi,
                dhi,
            } => {
                let fields: Vec<&str> = line.split(',').map(str::trim).collect();
                let int = |i: usize, column: &str, max: u32| -> Result<u32, ParamError> {
                    let v = fields.get(i).copied().unwrap_or("");
                    v.parse::<u32>().ok().filter(|&x| x <= max).ok_or_else(|| {
                        error(format!(
                            "{column} `{}`: expected an integer up to {max}",
                            shown(v)
                        ))
                    })
                };
                let number = |i: usize, column: &str| -> Result<Option<f32>, ParamError> {
                    let v = fields.get(i).copied().unwrap_or("");
                    let x = field_number(v).ok_or_else(|| {
                        error(format!("{column} `{}`: expected a finite number", shown(v)))
                    })?;
                    Ok((x > MIDC_MISSING).then_some(x))
                };
                let y = int(year, "Year", 2999)?;
                let day = int(doy, "DOY", 366)?;
                let t = int(hhmm, "the time (HHMM)", 2359)?;
                if y < 1 || day < 1 || t % 100 > 59 {
                    return Err(error(format!(
                        "Year {y}, DOY {day}, time {t:04}: not a time (years 1-2999, DOY 1-366, HHMM)"
                    )));
                }
                let Some(g) = number(ghi, "the global irradiance")? else {
                    return Ok(None);
                };
                let d = match dhi {
                    Some(i) => number(i, "the diffuse irradiance")?,
                    None => None,
                };
                #[allow(clippy::cast_possible_wrap)] // y <= 2999
                let start = UnixTime::from_civil(y as i32, 1, 1, 0, 0, 0.0).0;
                let unix = UnixTime(
                    start
                        + f64::from(day - 1) * 86_400.0
                        + f64::from((t / 100 + offset_hours) * 3600 + (t % 100) * 60),
                );
                Ok(Some((unix, reading(g, d))))
            }
            Self::Surfrad => {
                let fields: Vec<&str> = line.split_whitespace().collect();
                if fields.len() < 16 {
                    return Err(error(format!(
                        "`{}`: a SURFRAD row has at least 16 fields (time, zenith, GHI, upwelling, DNI and diffuse with their flags), got {}",
                        shown(line),
                        fields.len()
                    )));
                }
                let int = |i: usize, column: &str| -> Result<u32, ParamError> {
                    fields[i].parse::<u32>().map_err(|_| {
                        error(format!(
                            "{column} `{}`: expected an integer",
                            shown(fields[i])
                        ))
                    })
                };
                let value = |i: usize, column: &str| -> Result<Option<f32>, ParamError> {
                    let x = field_number(fields[i]).ok_or_else(|| {
                        error(format!(
                            "{column} `{}`: expected a finite number",
                            shown(fields[i])
                        ))
                    })?;
                    let flag = int(i + 1, &format!("{column}_flag"))?;
                    Ok((x > SURFRAD_MISSING && flag == 0).then_some(x))
                };
                let (y, mo, d) = (int(0, "year")?, int(2, "month")?, int(3, "day")?);
                let (h, mi) = (int(4, "hour")?, int(5, "minute")?);
                let time = format!("{y:04}-{mo:02}-{d:02}T{h:02}:{mi:02}:00Z");
                let unix = UnixTime::parse(&time).map_err(|e| error(format!("the time: {e:#}")))?;
                let Some(g) = value(8, "dw_solar")? else {
                    return Ok(None);
                };
                Ok(Some((unix, reading(g, value(14, "diffuse")?))))
            }
        }
    }
}

/// The fields of one schedule row after its time ([`SCHEDULE_HEADER`]), each number by
/// [`crate::csv_output::number`].
fn row_fields(s: &Step) -> String {
    let (e, d) = (s.illuminance, s.daylight);
    [
        light_fields(s),
        number(d.global().y),
        number(d.diffuse().y),
        number(d.direct().y),
        chromaticity_fields(e),
        number(s.melanopic_edi),
    ]
    .join(",")
}

/// An f32 as a CSV field, by [`crate::csv_output::number`]'s rule.
fn number(v: f32) -> String {
    crate::csv_output::number(f64::from(v))
}

/// The sun's columns, CCT, Duv, the followed light's illuminance and the RGBW levels.
fn light_fields(s: &Step) -> String {
    let (sun, e, levels) = (s.sun, s.illuminance, s.drive.levels);
    let f = |v: Option<f32>| v.map_or_else(String::new, number);
    [
        crate::csv_output::number(sun.zenith_deg()),
        crate::csv_output::number(sun.azimuth_deg()),
        crate::csv_output::number(sun.elevation_deg()),
        crate::csv_output::number(sun.apparent_zenith_deg()),
        f(s.cct.map(|c| c.kelvin)),
        f(s.cct.map(|c| c.duv)),
        number(e.y),
        number(levels[0]),
        number(levels[1]),
        number(levels[2]),
        number(levels[3]),
    ]
    .join(",")
}

fn chromaticity_fields(e: sky_core::Vec3) -> String {
    let (x, y) = sky_core::daylight::chromaticity(e);
    [number(x), number(y)].join(",")
}

/// The fields of one measured row after its time ([`MEASURED_HEADER`]), with what the
/// self-calibration made of it (`None`: the calibration is off).
fn measured_fields(s: &Step, calibrated: Option<&Calibrated>) -> String {
    let Some(w) = s.weather else {
        return String::new();
    };
    [
        light_fields(s),
        chromaticity_fields(s.illuminance),
        number(s.melanopic_edi),
        number(w.global_irradiance),
        number(w.diffuse_irradiance),
        number(w.direct_normal_irradiance),
        number(w.global_illuminance),
        number(w.diffuse_illuminance),
        number(w.direct_illuminance),
        number(w.clear_sky.y),
        w.clear_sky_index.map_or_else(String::new, number),
        w.sky_type.to_string(),
        number(w.clear_sky_factor),
        calibrated.map_or_else(String::new, |c| {
            u8::from(c.verdict.window_clear).to_string()
        }),
        calibrated.map_or_else(String::new, |c| c.status.name().to_owned()),
    ]
    .join(",")
}

/// The self-calibration of `schedule --measurements` ([`schedule_measured`]).
#[derive(Debug, Clone, Default)]
pub struct CalibrationConfig {
    /// Learn the site's clear-sky level from the readings' clear periods (off: the model's
    /// clear sky as it is).
    pub enabled: bool,
    /// A state file to start from when it exists, and to write the learned state to at the
    /// end (atomically).
    pub state: Option<std::path::PathBuf>,
}

/// The readings' interval, seconds: the most frequent difference between successive rows'
/// times (the smallest of equally frequent ones), rounded to the second; 60 without two rows.
fn interval_of(file: &Path, format: MeasurementFormat) -> Result<u32> {
    let mut counts: std::collections::BTreeMap<i64, usize> = std::collections::BTreeMap::new();
    let mut last: Option<f64> = None;
    read_measurements(file, format, &mut |r| {
        if let Some(t) = last {
            #[allow(clippy::cast_possible_truncation)] // seconds between rows
            let d = (r.unix.0 - t).round() as i64;
            *counts.entry(d).or_default() += 1;
        }
        last = Some(r.unix.0);
        Ok(())
    })?;
    let best = counts
        .iter()
        .max_by(|a, b| a.1.cmp(b.1).then(b.0.cmp(a.0)))
        .map_or(60, |(&d, _)| d);
    u32::try_from(best)
        .ok()
        .filter(|d| (1..=86_400).contains(d))
        .ok_or_else(|| {
            ParamError(format!(
                "--measurements {}: the rows are {best} s apart, outside [1, 86400] s",
                file.display()
            ))
            .into()
        })
}

/// Reno & Hansen 2016's criteria for 1-minute readings, Jordan & Hansen 2023's for other
/// intervals of 1 to 30 minutes.
fn criteria_for(interval_seconds: u32) -> Result<Criteria, ParamError> {
    if interval_seconds == 60 {
        return Ok(Criteria::RENO_HANSEN_2016);
    }
    #[allow(clippy::cast_precision_loss)]
    Criteria::jordan_hansen_2023(interval_seconds as f32 / 60.0).map_err(|_| {
        ParamError(format!(
            "--measurements: readings every {interval_seconds} s: the self-calibration's clear-period detection takes readings every 1 to 30 minutes (--no-self-calibration to run without it)"
        ))
    })
}

/// The self-calibration for `config`'s site and the file's interval, from the state file
/// when there is one.
fn calibration_for(
    config: &ScheduleConfig,
    calibration: &CalibrationConfig,
    interval_seconds: u32,
) -> Result<SelfCalibration> {
    let criteria = criteria_for(interval_seconds)?;
    #[allow(clippy::cast_possible_truncation)] // degrees
    let longitude = config.longitude as f32;
    let bounds = Bounds::DEFAULT;
    match &calibration.state {
        Some(path) if path.exists() => {
            let bytes = crate::csv_input::open(path, 4096)
                .and_then(|mut f| {
                    let mut b = Vec::new();
                    std::io::Read::read_to_end(&mut f, &mut b).map(|_| b)
                })
                .map_err(|e| ParamError(format!("--calibration-state {}: {e}", path.display())))?;
            SelfCalibration::from_bytes(&bytes, criteria, interval_seconds, longitude, bounds)
                .map_err(|e| {
                    ParamError(format!(
                        "--calibration-state {}: refused: {e} (delete the file to start learning anew)",
                        path.display()
                    ))
                    .into()
                })
        }
        _ => Ok(SelfCalibration::new(
            criteria,
            interval_seconds,
            longitude,
            bounds,
        )?),
    }
}

/// Writes the schedule at the times of the measurement file `file` ([`read_measurements`])
/// driven by its readings: the columns of [`MEASURED_HEADER`]. The file is read twice, a row
/// at a time: first every row is checked (parsed and stepped), then the rows are written, so
/// that a bad row is refused before anything is written and memory stays flat in the number
/// of rows. With `calibration.enabled` the second pass runs the self-calibration over the rows
/// in order ([`sky_core::controller::step_calibrated`]; the interval is the rows' most frequent
/// one), and the learned state is written to `calibration.state` at the end.
///
/// # Errors
/// Bad parameters or a bad reading as a [`ParamError`] naming the file's line; a state file
/// that cannot be read or is refused; a failed write.
pub fn schedule_measured(
    config: &ScheduleConfig,
    file: &Path,
    format: MeasurementFormat,
    calibration: &CalibrationConfig,
    output: &mut dyn Write,
) -> Result<()> {
    let site = Site::new(config.latitude, config.longitude, config.elevation)
        .map_err(|e| ParamError(format!("--lat/--lon/--elevation: {e}")))?;
    let lamp = example_luminaire()?;
    let located = |r: &MeasuredRow, e| {
        let what = crate::args::describe(e, column_name, " ");
        ParamError(format!(
            "--measurements {} line {} ({}): {what}",
            file.display(),
            r.line,
            r.unix.rfc3339()
        ))
    };
    // DIRINT's stability index: each row against the row before (one pass at a time).
    let run = |r: &MeasuredRow, history: &mut History| {
        step_with_history(
            &r.time,
            &site,
            &config.settings_in(r.time.month()),
            &lamp,
            Some(r.measurement),
            history,
        )
        .map_err(|e| located(r, e))
    };
    let mut history = History::new();
    read_measurements(file, format, &mut |r| {
        run(r, &mut history).map(|_| ()).map_err(Into::into)
    })?;
    // Readings more than 30 minutes apart (or less than one): no clear-period detection, so
    // no calibration, unless a state file asks for one (then its error).
    let mut learner = if calibration.enabled {
        let interval = interval_of(file, format)?;
        match calibration_for(config, calibration, interval) {
            Err(_) if calibration.state.is_none() && !(60..=1800).contains(&interval) => None,
            other => Some(other?),
        }
    } else {
        None
    };
    writeln!(output, "{MEASURED_HEADER}")?;
    let mut history = History::new();
    read_measurements(file, format, &mut |r| {
        let line = match learner.as_mut() {
            Some(cal) => {
                let (s, c) = step_calibrated(
                    &r.time,
                    &site,
                    &config.settings_in(r.time.month()),
                    &lamp,
                    r.measurement,
                    cal,
                    &mut history,
                )
                .map_err(|e| located(r, e))?;
                measured_fields(&s, Some(&c))
            }
            None => measured_fields(&run(r, &mut history)?, None),
        };
        writeln!(output, "{},{line}", r.unix.rfc3339())?;
        Ok(())
    })?;
    if let (Some(cal), Some(path)) = (&learner, &calibration.state) {
        let bytes = cal.to_bytes();
        crate::output_path::write_atomically(path, |f| {
            std::io::Write::write_all(f, &bytes)?;
            Ok(())
        })?;
    }
    Ok(())
}

/// The file's column for a sky-core parameter.
fn column_name(parameter: &str) -> String {
    match parameter {
        "global irradiance" => "the global irradiance (ghi_wm2)",
        "diffuse irradiance" => "the diffuse irradiance (dhi_wm2)",
        "global illuminance" => "the global illuminance (global_lux)",
        other => other,
    }
    .to_owned()
}

/// Writes the schedule of one UTC day as CSV ([`SCHEDULE_HEADER`]): one row every
/// `step_minutes` from 00:00 UTC.
///
/// # Errors
/// Bad parameters as a [`ParamError`]; a failed write.
pub fn schedule(config: &ScheduleConfig, output: &mut dyn Write) -> Result<()> {
    if !(1..=24 * 60).contains(&config.step_minutes) {
        return Err(ParamError(format!(
            "--step {} minutes is outside the valid range [1, 1440]",
            config.step_minutes
        ))
        .into());
    }
    let site = Site::new(config.latitude, config.longitude, config.elevation)
        .map_err(|e| ParamError(format!("--lat/--lon/--elevation: {e}")))?;
    let lamp = example_luminaire()?;
    let (year, month, day) = config.date;
    let settings = config.settings_in(month);
    writeln!(output, "{SCHEDULE_HEADER}")?;
    let mut minute = 0u32;
    while minute < 24 * 60 {
        let (hour, min) = (minute / 60, minute % 60);
        let time = UtcTime::new(year, month, day, hour, min, 0.0)
            .map_err(|e| ParamError(format!("--date: {e}")))?;
        let s = step(&time, &site, &settings, &lamp, None).with_context(|| {
            format!("schedule at {year:04}-{month:02}-{day:02}T{hour:02}:{min:02} (--aod, --full-scale-lux)")
        })?;
        writeln!(
            output,
            "{year:04}-{month:02}-{day:02}T{hour:02}:{min:02}:00Z,{}",
            row_fields(&s)
        )?;
        minute += config.step_minutes;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<Vec<MeasuredRow>, String> {
        let mut rows = Vec::new();
        parse_measurements(
            &mut text.as_bytes(),
            "--measurements m.csv",
            MeasurementFormat::Csv,
            &mut |r| {
                rows.push(*r);
                Ok(())
            },
        )
        .map_err(|e| format!("{e:#}"))?;
        Ok(rows)
    }

    /// Bad rows are refused with the file, the line and the column; good files with a
    /// byte-order mark, comments, blank lines, columns in any order and case are read.
    #[test]
    fn bad_measurement_rows_name_the_file_and_line() {
        let good = "\u{feff}# site A\nUTC, ghi_wm2 ,DHI_WM2,note\n\n2026-06-21T10:00:00Z,800,100,a\n2026-06-21T10:01:00Z,810,820.5e-1,b\n";
        let rows = parse(good).expect("read");
        assert_eq!(rows.len(), 2);
        assert!(matches!(
            rows[1].measurement,
            Measurement::Irradiance { global, diffuse } if global == 810.0 && diffuse == 82.05
        ));
        let header = "utc,ghi_wm2,dhi_wm2\n2026-06-21T10:00:00Z,800,100\n";
        for (row, needle) in [
            (
                "2026-06-21T10:01:00Z,NaN,100",
                "line 3: ghi_wm2 `NaN`: expected a finite number",
            ),
            ("2026-06-21T10:01:00Z,inf,100", "line 3: ghi_wm2 `inf`"),
            ("2026-06-21 10:01,800,100", "line 3: utc"),
            ("yesterday,800,100", "line 3: utc"),
            (
                "2026-06-21T09:00:00Z,800,100",
                "line 3: utc 2026-06-21T09:00:00Z: not after the time on line 2",
            ),
            (
                "2026-06-21T10:00:00Z,800,100",
                "line 3: utc 2026-06-21T10:00:00Z: not after the time on line 2",
            ),
            (
                "2026-06-21T12:00:00+02:00,800,100",
                "not after the time on line 2",
            ),
            ("2026-06-21T10:01:00Z,800", "line 3: no dhi_wm2 field"),
            ("2026-06-21T10:01:00Z,8\u{1b}[2J,1", "ghi_wm2 `8\\u{1b}[2J`"),
        ] {
            let e = parse(&format!("{header}{row}\n")).expect_err(row);
            assert!(e.starts_with("--measurements m.csv line 3: "), "{e}");
            assert!(e.contains(needle) && !e.contains('\n'), "{row}: {e}");
        }
        for bad_header in [
            "time,ghi_wm2",
            "utc,global_lux,ghi_wm2",
            "utc,dhi_wm2",
            "utc,ghi_wm2,GHI_WM2",
            "2026-06-21T10:00:00Z,800",
        ] {
            let e = parse(&format!("# c\n{bad_header}\n")).expect_err(bad_header);
            assert!(
                e.starts_with("--measurements m.csv line 2: the header"),
                "{e}"
            );
        }
        assert!(parse("").expect_err("empty").contains("the file is empty"));
        let long = format!(
            "utc,global_lux\n{}\n",
            "1".repeat(crate::csv_input::MAX_LINE_BYTES + 1)
        );
        assert!(
            parse(&long)
                .expect_err("long")
                .contains("line 2: the line is longer")
        );
    }
}
