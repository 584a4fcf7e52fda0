//! The lighting controller's day on the host: `sky-train schedule` (sun, colour temperature,
//! illuminance and RGBW levels every few minutes of a day, or at the times of a file of outdoor
//! measurements) and `sky-train cct` (CCT and Duv of chromaticities), both through sky-core, so
//! the firmware computes the same values.

use std::io::{BufRead, Write};

use anyhow::{Context, Result};
use std::path::Path;

use sky_core::cct;
use sky_core::controller::{Measurement, Step, example_luminaire, step};
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
    /// Preetham turbidity (2 to 6).
    pub turbidity: f32,
    /// The horizontal illuminance (lux) at which the luminaire gives its full output.
    pub full_scale_lux: f32,
}

/// The CSV header of `schedule`.
pub const SCHEDULE_HEADER: &str = "utc,sun_zenith_deg,sun_azimuth_deg,sun_elevation_deg,apparent_zenith_deg,cct_k,duv,horizontal_lux,red,green,blue,white";

/// The columns `schedule --measurements` adds to [`SCHEDULE_HEADER`].
pub const MEASURED_COLUMNS: &str = "sky_type,clear_sky_index";

/// One row of a measurement file: its UTC time and reading.
#[derive(Debug, Clone, Copy)]
pub struct MeasuredRow {
    /// The time of the reading.
    pub time: UtcTime,
    /// The same, as Unix time (for the output's RFC 3339).
    pub unix: UnixTime,
    /// The reading.
    pub measurement: Measurement,
}

/// Reads a CSV file of outdoor measurements: a header naming the columns `utc` (RFC 3339) and
/// either `global_lux` or `ghi_wm2` with an optional `dhi_wm2` (in any order; other columns
/// are ignored), then one reading per line (blank lines and `#` comments skipped).
///
/// # Errors
/// A [`ParamError`] naming the file, the line and the column for an unreadable file, a missing
/// or ambiguous column, a bad time or a field that is not a number; none for a file without rows.
pub fn read_measurements(path: &Path) -> Result<Vec<MeasuredRow>> {
    let name = path.display();
    let text = std::fs::read_to_string(path)
        .map_err(|e| ParamError(format!("--measurements {name}: {e}")))?;
    let mut lines = text
        .lines()
        .enumerate()
        .map(|(n, l)| (n + 1, l.trim()))
        .filter(|(_, l)| !l.is_empty() && !l.starts_with('#'));
    let Some((_, header)) = lines.next() else {
        return Err(ParamError(format!("--measurements {name}: the file is empty")).into());
    };
    let columns: Vec<&str> = header.split(',').map(str::trim).collect();
    let find = |c: &str| columns.iter().position(|h| *h == c);
    let missing = || {
        ParamError(format!(
            "--measurements {name}: the header `{header}` needs the columns utc and global_lux, or utc and ghi_wm2 (with dhi_wm2 optionally)"
        ))
    };
    let utc = find("utc").ok_or_else(missing)?;
    let (lux, ghi, dhi) = (find("global_lux"), find("ghi_wm2"), find("dhi_wm2"));
    if lux.is_some() && (ghi.is_some() || dhi.is_some()) || (lux.is_none() && ghi.is_none()) {
        return Err(missing().into());
    }
    let mut rows = Vec::new();
    for (n, line) in lines {
        let fields: Vec<&str> = line.split(',').map(str::trim).collect();
        let at = |i: usize, column: &str| {
            fields.get(i).copied().ok_or_else(|| {
                ParamError(format!("--measurements {name} line {n}: no {column} field"))
            })
        };
        let number = |i: usize, column: &str| -> Result<f32, ParamError> {
            let v = at(i, column)?;
            v.parse::<f32>().map_err(|_| {
                ParamError(format!(
                    "--measurements {name} line {n}: {column} `{v}` is not a number"
                ))
            })
        };
        let unix = UnixTime::parse(at(utc, "utc")?)
            .map_err(|e| ParamError(format!("--measurements {name} line {n}: {e:#}")))?;
        let (y, mo, d, h, mi, sec) = unix.to_civil();
        let time = UtcTime::new(y, mo, d, h, mi, sec)
            .map_err(|e| ParamError(format!("--measurements {name} line {n}: utc: {e}")))?;
        let measurement = match (lux, ghi, dhi) {
            (Some(i), _, _) => Measurement::GlobalIlluminance(number(i, "global_lux")?),
            (None, Some(g), Some(d)) => Measurement::Irradiance {
                global: number(g, "ghi_wm2")?,
                diffuse: number(d, "dhi_wm2")?,
            },
            (None, Some(g), None) => Measurement::GlobalIrradiance(number(g, "ghi_wm2")?),
            (None, None, _) => return Err(missing().into()),
        };
        rows.push(MeasuredRow {
            time,
            unix,
            measurement,
        });
    }
    Ok(rows)
}

/// The fields of one schedule row after its time: sun, CCT, illuminance, levels.
fn row_fields(s: &Step) -> String {
    let (sun, c, e, levels) = (s.sun, s.cct, s.illuminance, s.drive.levels);
    format!(
        "{:.5},{:.5},{:.5},{:.5},{:.2},{:.6},{:.6e},{:.6},{:.6},{:.6},{:.6}",
        sun.zenith_deg(),
        sun.azimuth_deg(),
        sun.elevation_deg(),
        sun.apparent_zenith_deg(),
        c.kelvin,
        c.duv,
        e.y,
        levels[0],
        levels[1],
        levels[2],
        levels[3],
    )
}

/// Writes the schedule at the times of `rows` (from [`read_measurements`]) driven by their
/// readings: the columns of [`SCHEDULE_HEADER`] and [`MEASURED_COLUMNS`] (`sky_type`, the Perez
/// sky-clearness bin 1-8, 0 with the sun below the horizon; `clear_sky_index`, measured over the
/// clear sky's horizontal illuminance). Every row is computed before anything is written.
///
/// # Errors
/// Bad parameters or a bad reading as a [`ParamError`] naming the file's line.
pub fn schedule_measured(
    config: &ScheduleConfig,
    rows: &[MeasuredRow],
    file: &Path,
    output: &mut dyn Write,
) -> Result<()> {
    let site = Site::new(config.latitude, config.longitude, config.elevation)
        .map_err(|e| ParamError(format!("--lat/--lon/--elevation: {e}")))?;
    let lamp = example_luminaire()?;
    let mut lines = Vec::with_capacity(rows.len());
    for (i, r) in rows.iter().enumerate() {
        let s = step(
            &r.time,
            &site,
            config.turbidity,
            config.full_scale_lux,
            &lamp,
            Some(r.measurement),
        )
        .map_err(|e| {
            let what = crate::args::describe(e, str::to_owned, " = ");
            ParamError(format!(
                "--measurements {} data row {} ({}): {what}",
                file.display(),
                i + 1,
                r.unix.rfc3339()
            ))
        })?;
        let w = s
            .weather
            .map_or((0, 0.0), |w| (w.sky_type, w.clear_sky_index));
        lines.push(format!(
            "{},{},{},{:.6}",
            r.unix.rfc3339(),
            row_fields(&s),
            w.0,
            w.1
        ));
    }
    writeln!(output, "{SCHEDULE_HEADER},{MEASURED_COLUMNS}")?;
    for l in lines {
        writeln!(output, "{l}")?;
    }
    Ok(())
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
    writeln!(output, "{SCHEDULE_HEADER}")?;
    let mut minute = 0u32;
    while minute < 24 * 60 {
        let (hour, min) = (minute / 60, minute % 60);
        let time = UtcTime::new(year, month, day, hour, min, 0.0)
            .map_err(|e| ParamError(format!("--date: {e}")))?;
        let s = step(&time, &site, config.turbidity, config.full_scale_lux, &lamp, None).with_context(
            || format!("schedule at {year:04}-{month:02}-{day:02}T{hour:02}:{min:02} (--turbidity, --full-scale-lux)"),
        )?;
        writeln!(
            output,
            "{year:04}-{month:02}-{day:02}T{hour:02}:{min:02}:00Z,{}",
            row_fields(&s)
        )?;
        minute += config.step_minutes;
    }
    Ok(())
}

/// Reads `x,y` lines ([`crate::csv_input`]: a header line `x,y` is allowed, blank lines are
/// skipped) and writes `x,y,cct_k,duv`, a line at a time.
///
/// # Errors
/// A line that is not two finite numbers, or a chromaticity without a CCT, named by its line
/// number.
pub fn cct_lines(input: &mut dyn BufRead, output: &mut dyn Write) -> Result<()> {
    writeln!(output, "x,y,cct_k,duv")?;
    for row in crate::csv_input::rows(input, ["x", "y"]) {
        let row = row?;
        #[allow(clippy::cast_possible_truncation)] // sky-core's chromaticities are f32
        let [x, y] = row.values.map(|v| v as f32);
        let c = cct::cct_duv(x, y).map_err(|e| {
            ParamError(format!(
                "stdin line {}: {} (x in [0, 1], y in (0, 1], CCT between {} and {} K)",
                row.line,
                crate::args::describe(e, str::to_owned, " = "),
                cct::MIN_CCT,
                cct::MAX_CCT
            ))
        })?;
        let [xs, ys] = &row.text;
        writeln!(output, "{xs},{ys},{:.3},{:.7}", c.kelvin, c.duv)?;
    }
    Ok(())
}
