//! The lighting controller's day on the host: `sky-train schedule` (sun, colour temperature,
//! illuminance and RGBW levels every few minutes of a day, or at the times of a file of outdoor
//! measurements) and `sky-train cct` (CCT and Duv of chromaticities), both through sky-core, so
//! the firmware computes the same values.

use std::io::{BufRead, Write};

use anyhow::{Context, Result};
use std::path::Path;

use sky_core::cct;
use sky_core::controller::{Measurement, Settings, Step, example_luminaire, step};
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
}

/// The CSV header of `schedule`.
///
/// `horizontal_lux`, `x`, `y`, `cct_k`, `duv` and `melanopic_edi_lux` are of the light followed
/// (global, or the sky alone; under cloud with measurements), `cct_k` and `duv` empty where
/// |Duv| > 0.05; `global_lux`, `diffuse_lux` and `direct_lux` are the clear-sky daylight's.
pub const SCHEDULE_HEADER: &str = "utc,sun_zenith_deg,sun_azimuth_deg,sun_elevation_deg,apparent_zenith_deg,cct_k,duv,horizontal_lux,red,green,blue,white,global_lux,diffuse_lux,direct_lux,x,y,melanopic_edi_lux";

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

/// The largest measurement file read, in bytes: a year of readings every minute (525,600
/// lines of some 40 bytes) fits three times over.
pub const MAX_MEASUREMENT_BYTES: u64 = 64 << 20;

/// Reads a CSV file of outdoor measurements ([`parse_measurements`]), at most
/// [`MAX_MEASUREMENT_BYTES`] long.
///
/// # Errors
/// A [`ParamError`] naming `--measurements` and the file: it cannot be read, is too long, or
/// [`parse_measurements`] refuses it.
pub fn read_measurements(path: &Path) -> Result<Vec<MeasuredRow>, ParamError> {
    let source = format!("--measurements {}", path.display());
    let file = crate::csv_input::open(path, MAX_MEASUREMENT_BYTES)
        .map_err(|e| ParamError(format!("{source}: {e}")))?;
    parse_measurements(&mut std::io::BufReader::new(file), &source)
}

/// Parses outdoor measurements ([`crate::csv_input::lines`]): a header naming the columns `utc`
/// (RFC 3339) and either `global_lux` or `ghi_wm2` with an optional `dhi_wm2` (in any order,
/// any case; other columns are ignored), then one reading per line (blank lines and `#`
/// comments skipped): finite, non-negative, the diffuse part not above the global, the times
/// strictly increasing.
///
/// # Errors
/// A one-line [`ParamError`] starting with `source` and naming the line and the column for a
/// missing or ambiguous column, a bad time, a field that is not a number or out of range, or a
/// time not after the one before; none for a file without rows.
pub fn parse_measurements(
    input: &mut dyn std::io::BufRead,
    source: &str,
) -> Result<Vec<MeasuredRow>, ParamError> {
    use crate::csv_input::shown;
    let mut lines = crate::csv_input::lines(input, source);
    let mut next = || loop {
        match lines.next_line() {
            Some(Ok(l)) if l.starts_with('#') => {}
            other => return other.transpose().map(|l| l.map(|l| (lines.line(), l))),
        }
    };
    let Some((header_line, header)) = next()? else {
        return Err(ParamError(format!("{source}: the file is empty")));
    };
    let columns: Vec<String> = header
        .split(',')
        .map(|c| c.trim().to_ascii_lowercase())
        .collect();
    let find = |c: &str| columns.iter().position(|h| h == c);
    let missing = || {
        ParamError(format!(
            "{source} line {header_line}: the header `{}` needs the columns utc and global_lux, or utc and ghi_wm2 (with dhi_wm2 optionally)",
            shown(&header)
        ))
    };
    let utc = find("utc").ok_or_else(missing)?;
    let (lux, ghi, dhi) = (find("global_lux"), find("ghi_wm2"), find("dhi_wm2"));
    if lux.is_some() && (ghi.is_some() || dhi.is_some()) || (lux.is_none() && ghi.is_none()) {
        return Err(missing());
    }
    let mut rows: Vec<MeasuredRow> = Vec::new();
    let mut previous: Option<(usize, f64)> = None;
    while let Some((n, line)) = next()? {
        let error = |what: String| ParamError(format!("{source} line {n}: {what}"));
        let fields: Vec<&str> = line.split(',').map(str::trim).collect();
        let at = |i: usize, column: &str| {
            fields
                .get(i)
                .copied()
                .ok_or_else(|| error(format!("no {column} field")))
        };
        let number = |i: usize, column: &str| -> Result<f32, ParamError> {
            let v = at(i, column)?;
            match v.parse::<f32>() {
                Ok(x) if x.is_finite() && x >= 0.0 => Ok(x),
                _ => Err(error(format!(
                    "{column} `{}`: expected a finite number, at least 0",
                    shown(v)
                ))),
            }
        };
        let text = at(utc, "utc")?;
        let unix = UnixTime::parse(text).map_err(|e| error(format!("utc: {e:#}")))?;
        if let Some((line, t)) = previous
            && unix.0 <= t
        {
            return Err(error(format!(
                "utc {}: not after the time on line {line} (the rows must be in time order, each time once)",
                shown(text)
            )));
        }
        previous = Some((n, unix.0));
        let (y, mo, d, h, mi, sec) = unix.to_civil();
        let time = UtcTime::new(y, mo, d, h, mi, sec).map_err(|e| error(format!("utc: {e}")))?;
        let measurement = match (lux, ghi, dhi) {
            (Some(i), _, _) => Measurement::GlobalIlluminance(number(i, "global_lux")?),
            (None, Some(g), Some(d)) => {
                let (global, diffuse) = (number(g, "ghi_wm2")?, number(d, "dhi_wm2")?);
                if diffuse > global {
                    return Err(error(format!(
                        "dhi_wm2 {diffuse} is above ghi_wm2 {global} (the diffuse part of the global irradiance)"
                    )));
                }
                Measurement::Irradiance { global, diffuse }
            }
            (None, Some(g), None) => Measurement::GlobalIrradiance(number(g, "ghi_wm2")?),
            (None, None, _) => return Err(missing()),
        };
        rows.push(MeasuredRow {
            time,
            unix,
            measurement,
        });
    }
    Ok(rows)
}

/// The fields of one schedule row after its time ([`SCHEDULE_HEADER`]).
fn row_fields(s: &Step) -> String {
    let (sun, e, levels, d) = (s.sun, s.illuminance, s.drive.levels, s.daylight);
    let (cct_k, duv) = s.cct.map_or((String::new(), String::new()), |c| {
        (format!("{:.2}", c.kelvin), format!("{:.6}", c.duv))
    });
    let (x, y) = sky_core::daylight::chromaticity(e);
    format!(
        "{:.5},{:.5},{:.5},{:.5},{cct_k},{duv},{:.6e},{:.6},{:.6},{:.6},{:.6},{:.6e},{:.6e},{:.6e},{x:.6},{y:.6},{:.6e}",
        sun.zenith_deg(),
        sun.azimuth_deg(),
        sun.elevation_deg(),
        sun.apparent_zenith_deg(),
        e.y,
        levels[0],
        levels[1],
        levels[2],
        levels[3],
        d.global().y,
        d.diffuse().y,
        d.direct().y,
        s.melanopic_edi,
    )
}

/// Writes the schedule at the times of `rows` (from [`read_measurements`]) driven by their
/// readings: the columns of [`SCHEDULE_HEADER`] and [`MEASURED_COLUMNS`] (`sky_type`, the Perez
/// sky-clearness bin 1-8, 0 with the sun below the horizon; `clear_sky_index`, measured over the
/// clear sky's global horizontal illuminance). Every row is computed before anything is written.
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
        let s =
            step(&r.time, &site, &config.settings, &lamp, Some(r.measurement)).map_err(|e| {
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
        let s = step(&time, &site, &config.settings, &lamp, None).with_context(|| {
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

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<Vec<MeasuredRow>, String> {
        parse_measurements(&mut text.as_bytes(), "--measurements m.csv").map_err(|e| e.0)
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
            (
                "2026-06-21T10:01:00Z,800,-1",
                "line 3: dhi_wm2 `-1`: expected a finite number, at least 0",
            ),
            (
                "2026-06-21T10:01:00Z,100,200",
                "line 3: dhi_wm2 200 is above ghi_wm2 100",
            ),
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
            "2026-06-21T10:00:00Z,800",
        ] {
            let e = parse(&format!("# c\n{bad_header}\n")).expect_err(bad_header);
            assert!(
                e.starts_with("--measurements m.csv line 2: the header"),
                "{e}"
            );
        }
        assert!(parse("").expect_err("empty").ends_with("the file is empty"));
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
