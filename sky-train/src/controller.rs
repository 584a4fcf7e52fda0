//! The lighting controller's day on the host: `sky-train schedule` (sun, colour temperature,
//! illuminance and RGBW levels every few minutes of a day, or at the times of a file of outdoor
//! measurements) and `sky-train cct` (CCT and Duv of chromaticities), both through sky-core, so
//! the firmware computes the same values.

use std::io::Write;

use anyhow::{Context, Result};
use std::path::Path;

use sky_core::SkyError;
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
    /// An NREL MIDC CSV file as the network delivers it, in either of its two layouts: the
    /// raw data (its data API: a header with `Year`, `DOY` and, after it, the time column
    /// named by the station's standard time zone holding HHMM) or the web page's download
    /// (`DATE (MM/DD/YYYY)` or `DATE (YYYY/MM/DD)`, then the time column named by the zone
    /// holding HH:MM). The zones: `EST`, `CST`, `MST`, `PST`, `AKST`, `HST` or `UTC`. GHI is
    /// the first column whose name starts with `Global` and holds `[W/m^2]` (not a standard
    /// deviation, a tilted plane or an ultraviolet band), DHI the first starting with
    /// `Diffuse` likewise. Values of −7999 or less are missing: a row
    /// without the GHI is skipped, a row without the DHI keeps the GHI alone.
    Midc,
    /// A University of Oregon SRML archival file as the network delivers it (tab-separated; the
    /// layout of pvlib's `iotools.read_srml`): a header of the station's number, the year, then
    /// each column's data element number followed by a flag column (`0`); rows of the day of
    /// year, the time HHMM (1 to 2400) at the end of the averaging interval in Pacific Standard
    /// Time (UTC−8, every SRML station), then value-and-flag pairs. GHI is the first element
    /// 100x, DHI the first 300x (x the instrument; elements 1000 and 3000 in most files). A row
    /// is timed at its stamp (pvlib labels the interval's start, one interval earlier). Flag 99
    /// is a missing or bad value: a row whose GHI has it is skipped, a row whose DHI has it
    /// keeps the GHI alone.
    Srml,
    /// A BSRN station-to-archive file as the World Radiation Monitoring Center delivers it
    /// (a month, gzip-compressed or not; the layout of pvlib's `iotools.read_bsrn`): the
    /// first record's second line gives the month (columns 4-6) and the year (8-11); the
    /// basic measurements' record (`*U0100` or `*C0100`) holds two fixed-width lines a minute
    /// (UTC): the day of the month (columns 1-3), the minute of the day (5-9) and the global
    /// irradiance's mean (11-16), then on the second line the diffuse irradiance's mean
    /// (11-16). −999 is a missing value: a minute without the GHI is skipped, one without the
    /// DHI keeps the GHI alone. The other records (station, instruments, upwelling and UV
    /// radiation) are not read.
    Bsrn,
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
    /// Whether the file's diffuse was set aside: in the stations' formats, a diffuse above the
    /// global by more than sky-core's tolerance (two instruments disagreeing, as a cloud's edge
    /// passes or a tracker slips) leaves the global alone, as a flagged diffuse does
    /// ([`station_reading`]).
    pub diffuse_set_aside: bool,
}

impl MeasuredRow {
    /// The row with its global reading alone (a diffuse left out, to be split by the
    /// separation model).
    #[must_use]
    pub fn global_alone(&self) -> Self {
        let measurement = match self.measurement {
            Measurement::Irradiance { global, .. } => Measurement::GlobalIrradiance(global),
            m => m,
        };
        Self {
            measurement,
            diffuse_set_aside: false,
            ..*self
        }
    }
}

/// A reading, and whether the file's diffuse was set aside ([`station_reading`]).
pub type StationReading = (Measurement, bool);

/// A station's global and diffuse reading, W/m², as a measurement: a diffuse above the global
/// by more than sky-core's tolerance (the larger of
/// [`sky_core::measurement::DIFFUSE_EXCESS_TOLERANCE`] and
/// [`sky_core::measurement::DIFFUSE_EXCESS_FRACTION`] of the global) is set aside (`true`) and
/// the global split by the settings' separation model. BSRN's quality control flags the same
/// comparison (Long & Dutton, *BSRN Global Network recommended QC tests*, V2.0, 2010: diffuse
/// over global above 1.05 with the sun more than 15° up).
#[must_use]
pub fn station_reading(global: f32, diffuse: Option<f32>) -> StationReading {
    use sky_core::measurement::{DIFFUSE_EXCESS_FRACTION, DIFFUSE_EXCESS_TOLERANCE};
    match diffuse {
        Some(d) if d > global + DIFFUSE_EXCESS_TOLERANCE.max(DIFFUSE_EXCESS_FRACTION * global) => {
            (Measurement::GlobalIrradiance(global), true)
        }
        Some(diffuse) => (Measurement::Irradiance { global, diffuse }, false),
        None => (Measurement::GlobalIrradiance(global), false),
    }
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
    use std::io::BufRead;
    let source = format!("--measurements {}", path.display());
    let file = crate::csv_input::open(path, MAX_MEASUREMENT_BYTES)
        .map_err(|e| ParamError(format!("{source}: {e}")))?;
    let mut file = std::io::BufReader::new(file);
    let gzip = file
        .fill_buf()
        .map_err(|e| ParamError(format!("{source}: cannot read: {e}")))?
        .starts_with(&[0x1f, 0x8b]);
    if gzip {
        // Decompressed, the file is held to the same length (a small file can inflate to
        // gigabytes).
        let inflated = Bounded {
            inner: flate2::bufread::MultiGzDecoder::new(file),
            left: MAX_MEASUREMENT_BYTES,
        };
        let source = format!("{source} (gzip)");
        parse_measurements(
            &mut std::io::BufReader::new(inflated),
            &source,
            format,
            each,
        )
    } else {
        parse_measurements(&mut file, &source, format, each)
    }
}

/// A reader that fails once more than `left` bytes have been read from it.
struct Bounded<R> {
    inner: R,
    left: u64,
}

impl<R: std::io::Read> std::io::Read for Bounded<R> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let n = self.inner.read(buf)?;
        self.left = self.left.checked_sub(n as u64).ok_or_else(|| {
            std::io::Error::new(
                std::io::ErrorKind::InvalidData,
                format!(
                    "longer than {} MiB decompressed, the largest measurement file read",
                    MAX_MEASUREMENT_BYTES >> 20
                ),
            )
        })?;
        Ok(n)
    }
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
    // The line-based formats' layouts come from their header; BSRN's records have their own
    // reader.
    let layout_of: fn(&str, usize, &str) -> Result<Layout, ParamError> = match format {
        MeasurementFormat::Bsrn => return parse_bsrn(input, source, each),
        MeasurementFormat::Csv => Layout::csv,
        MeasurementFormat::Midc => Layout::midc,
        MeasurementFormat::Srml => Layout::srml,
        MeasurementFormat::Surfrad => |_, _, _| Ok(Layout::Surfrad),
    };
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
    let layout = layout_of(source, header_line, &header)?;
    // SURFRAD's first line names the station, its second gives the latitude, longitude and
    // elevation.
    if matches!(layout, Layout::Surfrad) && next()?.is_none() {
        return Err(ParamError(format!(
            "{source}: a SURFRAD file has two header lines (station; latitude, longitude, elevation)"
        ))
        .into());
    }
    let mut rows = InOrder::default();
    while let Some((n, line)) = next()? {
        let error = |what: String| ParamError(format!("{source} line {n}: {what}"));
        if let Some((unix, reading)) = layout.row(&line, &error)? {
            rows.hand_on(n, unix, reading, &error, each)?;
        }
    }
    Ok(())
}

/// The rows handed on so far: each must come after the one before.
#[derive(Default)]
struct InOrder {
    previous: Option<(usize, f64)>,
}

impl InOrder {
    /// Hands the reading of line `n` at `unix` to `each`, after checking that it comes after
    /// the one before.
    fn hand_on(
        &mut self,
        n: usize,
        unix: UnixTime,
        (measurement, diffuse_set_aside): StationReading,
        error: &dyn Fn(String) -> ParamError,
        each: &mut dyn FnMut(&MeasuredRow) -> Result<()>,
    ) -> Result<()> {
        if let Some((line, t)) = self.previous
            && unix.0 <= t
        {
            return Err(error(format!(
                "utc {}: not after the time on line {line} (the rows must be in time order, each time once)",
                unix.rfc3339()
            ))
            .into());
        }
        self.previous = Some((n, unix.0));
        let (y, mo, d, h, mi, sec) = unix.to_civil();
        let time = UtcTime::new(y, mo, d, h, mi, sec).map_err(|e| error(format!("utc: {e}")))?;
        each(&MeasuredRow {
            line: n,
            time,
            unix,
            measurement,
            diffuse_set_aside,
        })
    }
}

/// A BSRN value at or below this is missing (they are written −999).
const BSRN_MISSING: f32 = -999.0;

/// Parses a BSRN station-to-archive file ([`MeasurementFormat::Bsrn`]): lines are read as
/// bytes (the station's address may be in Latin-1), the basic measurements' lines must be
/// ASCII.
fn parse_bsrn(
    input: &mut dyn std::io::BufRead,
    source: &str,
    each: &mut dyn FnMut(&MeasuredRow) -> Result<()>,
) -> Result<()> {
    use crate::csv_input::{MAX_LINE_BYTES, shown};
    use std::io::{BufRead, Read};
    let mut n = 0usize;
    let mut buf = Vec::new();
    // The next line without its end, `None` at the end of the file.
    let mut next = |buf: &mut Vec<u8>| -> Result<Option<usize>, ParamError> {
        buf.clear();
        n += 1;
        let got = (&mut *input)
            .take(MAX_LINE_BYTES as u64 + 1)
            .read_until(b'\n', buf)
            .map_err(|e| ParamError(format!("{source}: cannot read: {e}")))?;
        if buf.len() > MAX_LINE_BYTES {
            return Err(ParamError(format!(
                "{source} line {n}: the line is longer than {MAX_LINE_BYTES} bytes"
            )));
        }
        while buf.last().is_some_and(|b| *b == b'\n' || *b == b'\r') {
            buf.pop();
        }
        Ok((got > 0).then_some(n))
    };
    let text = |buf: &[u8], n: usize| -> Result<String, ParamError> {
        std::str::from_utf8(buf)
            .ok()
            .filter(|t| t.is_ascii())
            .map(str::to_owned)
            .ok_or_else(|| ParamError(format!("{source} line {n}: not ASCII text")))
    };
    // The first record: `*U0001` (or `*C0001`), then the station, month and year.
    let first = next(&mut buf)?;
    if first.is_none() || !(buf.starts_with(b"*U0001") || buf.starts_with(b"*C0001")) {
        return Err(ParamError(format!(
            "{source} line 1: a BSRN station-to-archive file starts with the record *U0001 (or *C0001)"
        ))
        .into());
    }
    let Some(l) = next(&mut buf)? else {
        return Err(ParamError(format!("{source}: no line after *U0001")).into());
    };
    let date = text(&buf, l)?;
    let field = |t: &str, range: std::ops::Range<usize>| {
        t.get(range)
            .map(str::trim)
            .and_then(|v| v.parse::<u32>().ok())
    };
    let (Some(month), Some(year)) = (
        field(&date, 3..6).filter(|m| (1..=12).contains(m)),
        field(&date, 7..11).filter(|y| (1..=2999).contains(y)),
    ) else {
        return Err(ParamError(format!(
            "{source} line {l}: `{}`: expected the station, the month (columns 4-6, 1-12) and the year (columns 8-11)",
            shown(&date)
        ))
        .into());
    };
    #[allow(clippy::cast_possible_wrap)] // year <= 2999
    let month_start = UnixTime::from_civil(year as i32, month, 1, 0, 0, 0.0).0;
    // To the basic measurements' record.
    loop {
        if next(&mut buf)?.is_none() {
            return Err(ParamError(format!(
                "{source}: no basic measurements (record *U0100 or *C0100)"
            ))
            .into());
        }
        if buf.starts_with(b"*U0100") || buf.starts_with(b"*C0100") {
            break;
        }
    }
    let mut rows = InOrder::default();
    while let Some(a) = next(&mut buf)? {
        if buf.starts_with(b"*") {
            break; // the next record
        }
        let first = text(&buf, a)?;
        let Some(b) = next(&mut buf)? else {
            return Err(ParamError(format!(
                "{source} line {a}: a minute of the basic measurements has two lines; the file ends after the first"
            ))
            .into());
        };
        let second = text(&buf, b)?;
        let error = |what: String| ParamError(format!("{source} line {a}: {what}"));
        let int = |t: &str, range: std::ops::Range<usize>, what: &str, max: u32| {
            field(t, range.clone())
                .filter(|&v| v <= max)
                .ok_or_else(|| {
                    error(format!(
                        "{what} (columns {}-{}) `{}`: expected an integer up to {max}",
                        range.start + 1,
                        range.end,
                        shown(t.get(range.clone()).map_or("", str::trim))
                    ))
                })
        };
        let value = |t: &str, line: usize, what: &str| -> Result<Option<f32>, ParamError> {
            let v = t.get(10..16).map_or("", str::trim);
            let x = field_number(v).ok_or_else(|| {
                ParamError(format!(
                    "{source} line {line}: {what} (columns 11-16) `{}`: expected a finite number",
                    shown(v)
                ))
            })?;
            Ok((x > BSRN_MISSING).then_some(x))
        };
        let day = int(&first, 0..3, "the day", 31)?;
        let minute = int(&first, 4..9, "the minute of the day", 1439)?;
        if day == 0 {
            return Err(error("the day 0: the days of the month count from 1".into()).into());
        }
        let Some(global) = value(&first, a, "the global irradiance")? else {
            continue;
        };
        let diffuse = value(&second, b, "the diffuse irradiance")?;
        let unix = UnixTime(month_start + f64::from(day - 1) * 86_400.0 + f64::from(minute) * 60.0);
        let (_, m, ..) = unix.to_civil();
        if m != month {
            return Err(error(format!("the day {day}: not a day of month {month}")).into());
        }
        rows.hand_on(a, unix, station_reading(global, diffuse), &error, each)?;
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
    /// The date ([`MidcDate`]), the time of day in local standard time `offset_hours` behind
    /// UTC at column `time`, GHI, DHI.
    Midc {
        date: MidcDate,
        time: usize,
        offset_hours: u32,
        ghi: usize,
        dhi: Option<usize>,
    },
    /// Fixed columns (see [`MeasurementFormat::Surfrad`]).
    Surfrad,
    /// The year of the header, the columns of GHI and DHI (each followed by its flag).
    Srml {
        year: u32,
        ghi: usize,
        dhi: Option<usize>,
    },
}

/// Where a MIDC file's date is, and so which of its two layouts it has.
#[derive(Clone, Copy)]
enum MidcDate {
    /// The raw data's `Year` and `DOY` columns; the time is HHMM.
    YearDay { year: usize, doy: usize },
    /// The web download's `DATE (MM/DD/YYYY)` or `DATE (YYYY/MM/DD)` column (`year_first`);
    /// the time is HH:MM.
    Calendar { date: usize, year_first: bool },
}

/// An SRML value whose flag is this is missing or bad.
const SRML_MISSING_FLAG: &str = "99";

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
        let calendar = find("date (mm/dd/yyyy)")
            .map(|date| (date, false))
            .or_else(|| find("date (yyyy/mm/dd)").map(|date| (date, true)));
        let (date, time) = match calendar {
            Some((date, year_first)) => (MidcDate::Calendar { date, year_first }, date + 1),
            None => {
                let year = find("year").ok_or_else(|| {
                    bad("has no DATE (MM/DD/YYYY), DATE (YYYY/MM/DD) or Year column")
                })?;
                let doy = find("doy").ok_or_else(|| bad("has no DOY column"))?;
                (MidcDate::YearDay { year, doy }, doy + 1)
            }
        };
        let offset_hours = match columns.get(time).map(String::as_str) {
            Some("utc" | "gmt" | "ut") => 0,
            Some("est") => 5,
            Some("cst") => 6,
            Some("mst") => 7,
            Some("pst") => 8,
            Some("akst") => 9,
            Some("hst") => 10,
            _ => {
                return Err(bad(&format!(
                    "has no time column after {} named EST, CST, MST, PST, AKST, HST or UTC",
                    match date {
                        MidcDate::Calendar { .. } => "DATE",
                        MidcDate::YearDay { .. } => "DOY",
                    }
                )));
            }
        };
        // A horizontal irradiance: not a standard deviation, a tilted plane (BMS's `Global
        // 40-South CMP11`) or an ultraviolet band, by the words of its name.
        let excluded = [
            "stdev", "std", "north", "south", "east", "west", "tilt", "tilted", "poa", "uv", "uva",
            "uvb",
        ];
        let irradiance = |start: &str| {
            columns.iter().position(|c| {
                c.starts_with(start)
                    && c.contains("[w/m^2]")
                    && !c
                        .split(|ch: char| !ch.is_ascii_alphanumeric())
                        .any(|word| excluded.contains(&word))
            })
        };
        let ghi = irradiance("global")
            .ok_or_else(|| bad("has no column starting with `Global` in [W/m^2]"))?;
        Ok(Self::Midc {
            date,
            time,
            offset_hours,
            ghi,
            dhi: irradiance("diffuse"),
        })
    }

    fn srml(source: &str, header_line: usize, header: &str) -> Result<Self, ParamError> {
        use crate::csv_input::shown;
        let fields: Vec<&str> = header.split('\t').map(str::trim).collect();
        let bad = |what: &str| {
            ParamError(format!(
                "{source} line {header_line}: the SRML header `{}` {what}",
                shown(header)
            ))
        };
        let year = fields
            .get(1)
            .and_then(|y| y.parse::<u32>().ok())
            .filter(|y| (1..=2999).contains(y))
            .ok_or_else(|| bad("has no year (1-2999) in its second field"))?;
        // Data element numbers at 2, 4, …, each followed by its flag column.
        let element = |code: &str| {
            (2..fields.len())
                .step_by(2)
                .find(|&i| fields[i].len() == 4 && fields[i].starts_with(code))
        };
        let ghi = element("100").ok_or_else(|| {
            bad("has no global horizontal irradiance (data element 100x) followed by its flag")
        })?;
        Ok(Self::Srml {
            year,
            ghi,
            dhi: element("300"),
        })
    }

    /// The time and reading of one data line; `None` for a row without a reading (a missing or
    /// flagged GHI in the stations' formats).
    fn row(
        &self,
        line: &str,
        error: &dyn Fn(String) -> ParamError,
    ) -> Result<Option<(UnixTime, StationReading)>, ParamError> {
        use crate::csv_input::shown;
        let strict = |global: f32, diffuse: Option<f32>| match diffuse {
            Some(diffuse) => (Measurement::Irradiance { global, diffuse }, false),
            None => (Measurement::GlobalIrradiance(global), false),
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
                    (Some(i), _) => (
                        Measurement::GlobalIlluminance(number(i, "global_lux")?),
                        false,
                    ),
                    (None, Some(g)) => strict(
                        number(g, "ghi_wm2")?,
                        dhi.map(|d| number(d, "dhi_wm2")).transpose()?,
                    ),
                    (None, None) => return Err(error("no ghi_wm2 or global_lux column".into())),
                };
                Ok(Some((unix, measurement)))
            }
            Self::Midc {
                date,
                time,
                offset_hours,
                ghi,
                dhi,
            } => {
                let fields: Vec<&str> = line.split(',').map(str::trim).collect();
                let int = |i: usize, column: &str, range| integer(&fields, i, column, range, error);
                let number = |i: usize, column: &str| -> Result<Option<f32>, ParamError> {
                    let v = fields.get(i).copied().unwrap_or("");
                    let x = field_number(v).ok_or_else(|| {
                        error(format!("{column} `{}`: expected a finite number", shown(v)))
                    })?;
                    Ok((x > MIDC_MISSING).then_some(x))
                };
                let unix = match date {
                    MidcDate::YearDay { year, doy } => {
                        let y = int(year, "Year", 1..=2999)?;
                        let day = int(doy, "DOY", 1..=366)?;
                        let t = hours_minutes(&fields, time, 0..=2359, error)?;
                        standard_time(y, day, t, offset_hours)
                    }
                    MidcDate::Calendar { date, year_first } => {
                        calendar_time(&fields, date, year_first, time, offset_hours, error)?
                    }
                };
                let Some(g) = number(ghi, "the global irradiance")? else {
                    return Ok(None);
                };
                let d = match dhi {
                    Some(i) => number(i, "the diffuse irradiance")?,
                    None => None,
                };
                Ok(Some((unix, station_reading(g, d))))
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
                Ok(Some((unix, station_reading(g, value(14, "diffuse")?))))
            }
            Self::Srml { year, ghi, dhi } => {
                let fields: Vec<&str> = line.split('\t').map(str::trim).collect();
                let int = |i: usize, column: &str, range| integer(&fields, i, column, range, error);
                let value = |i: usize, column: &str| -> Result<Option<f32>, ParamError> {
                    let (Some(v), Some(flag)) = (fields.get(i), fields.get(i + 1)) else {
                        return Err(error(format!(
                            "no {column} field with its flag (the header names it as column {})",
                            i + 1
                        )));
                    };
                    if *flag == SRML_MISSING_FLAG {
                        return Ok(None);
                    }
                    field_number(v).map(Some).ok_or_else(|| {
                        error(format!("{column} `{}`: expected a finite number", shown(v)))
                    })
                };
                let day = int(0, "the day of year", 1..=366)?;
                let t = hours_minutes(&fields, 1, 1..=2400, error)?;
                let Some(g) = value(ghi, "the global irradiance")? else {
                    return Ok(None);
                };
                let d = match dhi {
                    Some(i) => value(i, "the diffuse irradiance")?,
                    None => None,
                };
                // Pacific Standard Time, 8 hours behind UTC; 2400 is the next day's 00:00.
                let unix = standard_time(year, day, t, 8);
                Ok(Some((unix, station_reading(g, d))))
            }
        }
    }
}

/// Field `i` of `fields` as an integer in `range`, or an error naming `column`.
fn integer(
    fields: &[&str],
    i: usize,
    column: &str,
    range: std::ops::RangeInclusive<u32>,
    error: &dyn Fn(String) -> ParamError,
) -> Result<u32, ParamError> {
    let v = fields.get(i).copied().unwrap_or("");
    v.parse::<u32>()
        .ok()
        .filter(|x| range.contains(x))
        .ok_or_else(|| {
            error(format!(
                "{column} `{}`: expected an integer in {}-{}",
                crate::csv_input::shown(v),
                range.start(),
                range.end()
            ))
        })
}

/// Field `i` of `fields` as a time of day HHMM in `range`, its minutes 0-59, or an error.
fn hours_minutes(
    fields: &[&str],
    i: usize,
    range: std::ops::RangeInclusive<u32>,
    error: &dyn Fn(String) -> ParamError,
) -> Result<u32, ParamError> {
    let t = integer(fields, i, "the time (HHMM)", range, error)?;
    if t % 100 > 59 {
        return Err(error(format!("the time {t:04}: not HHMM")));
    }
    Ok(t)
}

/// The instant of MIDC's web download: field `date` MM/DD/YYYY (YYYY/MM/DD if `year_first`)
/// and field `time` HH:MM (00:00 to 23:59) in a standard time `offset_hours` behind UTC; a
/// malformed or impossible date or time is an error naming the field.
fn calendar_time(
    fields: &[&str],
    date: usize,
    year_first: bool,
    time: usize,
    offset_hours: u32,
    error: &dyn Fn(String) -> ParamError,
) -> Result<UnixTime, ParamError> {
    use crate::csv_input::shown;
    let (layout, widths) = if year_first {
        ("YYYY/MM/DD", [(4, 4), (1, 2), (1, 2)])
    } else {
        ("MM/DD/YYYY", [(1, 2), (1, 2), (4, 4)])
    };
    let (Some(d), Some(t)) = (fields.get(date), fields.get(time)) else {
        return Err(error(format!("no DATE ({layout}) and time fields")));
    };
    // Digits only, each part within its widths.
    let parts = |text: &str, separator: char, widths: &[(usize, usize)]| -> Option<Vec<u32>> {
        let parts: Vec<&str> = text.split(separator).collect();
        let fits = |p: &str, &(least, most): &(usize, usize)| {
            (least..=most).contains(&p.len()) && p.bytes().all(|b| b.is_ascii_digit())
        };
        (parts.len() == widths.len() && parts.iter().zip(widths).all(|(p, w)| fits(p, w)))
            .then(|| parts.iter().filter_map(|p| p.parse().ok()).collect())
    };
    let date = parts(d, '/', &widths)
        .and_then(|v| <[u32; 3]>::try_from(v).ok())
        .map(|[a, b, c]| if year_first { (a, b, c) } else { (c, a, b) })
        .and_then(|(year, month, day)| Some((i32::try_from(year).ok()?, month, day)))
        .filter(|&(year, month, day)| {
            (UtcTime::MIN_YEAR..=UtcTime::MAX_YEAR).contains(&year)
                && (1..=12).contains(&month)
                && (1..=sky_core::solar::days_in_month(year, month)).contains(&day)
        });
    let Some((year, month, day)) = date else {
        return Err(error(format!(
            "DATE ({layout}) `{}`: expected a date {layout} (years 1-2999)",
            shown(d)
        )));
    };
    let Some([hour, minute]) = parts(t, ':', &[(1, 2), (2, 2)])
        .and_then(|v| <[u32; 2]>::try_from(v).ok())
        .filter(|&[h, m]| h <= 23 && m <= 59)
    else {
        return Err(error(format!(
            "the time `{}`: expected HH:MM, 00:00 to 23:59",
            shown(t)
        )));
    };
    let local = UnixTime::from_civil(year, month, day, hour, minute, 0.0);
    Ok(UnixTime(local.0 + f64::from(offset_hours * 3600)))
}

/// The time `hhmm` ([`hours_minutes`]) of day `day` (1 = 1 January) of `year` (1-2999, as the
/// readers check) in a standard time `offset_hours` behind UTC, as the stations' files give it.
fn standard_time(year: u32, day: u32, hhmm: u32, offset_hours: u32) -> UnixTime {
    #[allow(clippy::cast_possible_wrap)] // years up to 2999
    let start = UnixTime::from_civil(year as i32, 1, 1, 0, 0, 0.0).0;
    UnixTime(
        start
            + f64::from(day.saturating_sub(1)) * 86_400.0
            + f64::from((hhmm / 100 + offset_hours) * 3600 + (hhmm % 100) * 60),
    )
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
/// one), and the learned state is written to `calibration.state` at the end. With
/// `global_only` a row's diffuse is left out and its global split by the settings' separation
/// model ([`MeasuredRow::global_alone`]: the split of a GHI-only reading, to compare with the
/// file's diffuse). In the stations' formats a row whose global is above the physical limit
/// (a spike, or a clock off near sunrise or sunset) is skipped in both passes, with a note on
/// standard error; more than 10 such rows that are also more than 1 % of the file refuse it.
///
/// # Errors
/// Bad parameters or a bad reading as a [`ParamError`] naming the file's line; too many rows
/// above the physical limit in a station's file; a state file that cannot be read or is
/// refused; a failed write.
pub fn schedule_measured(
    config: &ScheduleConfig,
    file: &Path,
    format: MeasurementFormat,
    global_only: bool,
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
    };
    // In the stations' formats a global above the physical limit is set aside like a flagged
    // reading (its row skipped), in the project's CSV it is refused.
    let station = format != MeasurementFormat::Csv;
    let skipped = |e: &SkyError| station && above_physical_limit(e).is_some();
    let mut history = History::new();
    let mut set_aside: Option<(usize, usize)> = None; // (rows, the first's line)
    let mut too_bright: Option<(usize, usize, f32)> = None; // (rows, the first's line, reading)
    let alone = |r: &MeasuredRow| if global_only { r.global_alone() } else { *r };
    let mut rows = 0usize;
    read_measurements(file, format, &mut |r| {
        let r = &alone(r);
        rows += 1;
        if let Err(e) = run(r, &mut history) {
            let Some(value) = above_physical_limit(&e).filter(|_| station) else {
                return Err(located(r, e).into());
            };
            let (n, first, value) = too_bright.unwrap_or((0, r.line, value));
            too_bright = Some((n + 1, first, value));
            return Ok(());
        }
        if r.diffuse_set_aside {
            let (n, first) = set_aside.unwrap_or((0, r.line));
            set_aside = Some((n + 1, first));
        }
        Ok(())
    })?;
    if let Some((n, first)) = set_aside {
        eprintln!(
            "note: --measurements {}: {n} row(s) with the diffuse above the global by more than max(10 W/m2, 5 %) (first on line {first}): their diffuse set aside, the global split by the separation model",
            file.display()
        );
    }
    if let Some((n, first, value)) = too_bright {
        // A spike now and then is a sensor's; many are a clock or a site that is not the
        // file's, and a schedule from them would follow the wrong sun.
        if n > MAX_ABOVE_LIMIT_ROWS.max(rows / 100) {
            return Err(ParamError(format!(
                "--measurements {}: {n} of {rows} rows have the global above {} times the extraterrestrial horizontal irradiance (first on line {first}: {value} W/m2), more than {MAX_ABOVE_LIMIT_ROWS} and more than 1 % of the rows: the file's clock not in the time zone its header or format names, --lat/--lon/--elevation not the station's, or a faulty sensor",
                file.display(),
                sky_core::decomposition::MAX_CLEARNESS_INDEX
            ))
            .into());
        }
        eprintln!(
            "note: --measurements {}: {n} row(s) with the global above {} times the extraterrestrial horizontal irradiance, which no sky gives (first on line {first}: {value} W/m2; a spike, or the file's clock off near sunrise or sunset): skipped, as flagged readings are",
            file.display(),
            sky_core::decomposition::MAX_CLEARNESS_INDEX
        );
    }
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
        let r = &alone(r);
        let line = match learner.as_mut() {
            Some(cal) => {
                match step_calibrated(
                    &r.time,
                    &site,
                    &config.settings_in(r.time.month()),
                    &lamp,
                    r.measurement,
                    cal,
                    &mut history,
                ) {
                    Ok((s, c)) => measured_fields(&s, Some(&c)),
                    Err(e) if skipped(&e) => return Ok(()),
                    Err(e) => return Err(located(r, e).into()),
                }
            }
            None => match run(r, &mut history) {
                Ok(s) => measured_fields(&s, None),
                Err(e) if skipped(&e) => return Ok(()),
                Err(e) => return Err(located(r, e).into()),
            },
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

/// The most rows of a station's file skipped for a global above the physical limit before the
/// file is refused, unless 1 % of its rows is more ([`schedule_measured`]).
const MAX_ABOVE_LIMIT_ROWS: usize = 10;

/// The global reading, W/m², that `e` refuses for being above the physical limit (more than
/// [`sky_core::decomposition::MAX_CLEARNESS_INDEX`] times the extraterrestrial horizontal
/// irradiance); `None` for one below the thermal-offset limit or any other error.
fn above_physical_limit(e: &SkyError) -> Option<f32> {
    match *e {
        SkyError::OutOfRange {
            parameter, value, ..
        } if parameter.starts_with("global irradiance") && value > 0.0 => Some(value),
        _ => None,
    }
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
        parse_as(text, MeasurementFormat::Csv)
    }

    fn parse_as(text: &str, format: MeasurementFormat) -> Result<Vec<MeasuredRow>, String> {
        let mut rows = Vec::new();
        parse_measurements(
            &mut text.as_bytes(),
            "--measurements m.csv",
            format,
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

    /// MIDC files: the header's time zone and irradiance columns, the time in UTC, and each
    /// malformed field named with its line.
    #[test]
    fn midc_files_are_read_and_bad_ones_named() {
        let header = "Year,DOY,MST,Global Horiz [W/m^2],Diffuse Horiz [W/m^2]\n";
        let rows = parse_as(
            &format!("{header}2018,291,400,-1.85,0.0\n2018,291,1259,-7999,10\n2018,365,2359,5,3\n"),
            MeasurementFormat::Midc,
        )
        .expect("MIDC");
        assert_eq!(rows.len(), 2, "the missing GHI's row skipped");
        assert_eq!(rows[0].unix.rfc3339(), "2018-10-18T11:00:00Z");
        assert!(
            matches!(rows[0].measurement, Measurement::Irradiance { global, diffuse } if global == -1.85 && diffuse == 0.0)
        );
        assert_eq!(rows[1].unix.rfc3339(), "2019-01-01T06:59:00Z");
        for (row, needle) in [
            ("2018,291,461,5,3", "line 2: the time 0461: not HHMM"),
            ("2018,291,2400,5,3", "line 2: the time (HHMM) `2400`"),
            (
                "0,291,400,5,3",
                "line 2: Year `0`: expected an integer in 1-2999",
            ),
            ("2018,367,400,5,3", "line 2: DOY `367`"),
            ("2018,291,400,x,3", "line 2: the global irradiance `x`"),
        ] {
            let e = parse_as(&format!("{header}{row}\n"), MeasurementFormat::Midc).expect_err(row);
            assert!(e.contains(needle) && !e.contains('\n'), "{row}: {e}");
        }
        let e = parse_as(
            "Year,DOY,CET,Global Horiz [W/m^2]\n",
            MeasurementFormat::Midc,
        )
        .expect_err("zone");
        assert!(e.contains("line 1: the MIDC header"), "{e}");
    }

    /// MIDC's web download (DATE (MM/DD/YYYY), then HH:MM in the header's zone): the time in
    /// UTC across midnight and the year's end, the columns by name, and each malformed date or
    /// time named with its line.
    #[test]
    fn midc_web_downloads_are_read_and_bad_ones_named() {
        let header = "DATE (MM/DD/YYYY),HST,Global PSP [W/m^2],Global PSP (Accumulated) [kWhr/m^2],Diffuse Horiz [W/m^2]\n";
        let rows = parse_as(
            &format!("{header}10/14/2018,00:00,-7.69,4.6,0\n10/14/2018,13:59,-7999,0,3\n12/31/2018,14:30,5,0,3\n02/29/2020,23:59,7,0,-7999\n"),
            MeasurementFormat::Midc,
        )
        .expect("MIDC web download");
        let times: Vec<String> = rows.iter().map(|r| r.unix.rfc3339()).collect();
        assert_eq!(
            times,
            [
                "2018-10-14T10:00:00Z",
                "2019-01-01T00:30:00Z",
                "2020-03-01T09:59:00Z"
            ],
            "HST is 10 hours behind UTC; the missing GHI's row skipped"
        );
        assert!(
            matches!(rows[0].measurement, Measurement::Irradiance { global, diffuse } if global == -7.69 && diffuse == 0.0)
        );
        assert!(matches!(rows[2].measurement, Measurement::GlobalIrradiance(g) if g == 7.0));
        for (row, needle) in [
            (
                "2018-10-14,00:00,5,0,3",
                "line 2: DATE (MM/DD/YYYY) `2018-10-14`: expected a date MM/DD/YYYY",
            ),
            (
                "02/30/2018,00:00,5,0,3",
                "line 2: DATE (MM/DD/YYYY) `02/30/2018`: expected a date MM/DD/YYYY (years 1-2999)",
            ),
            (
                "02/29/2019,00:00,5,0,3",
                "line 2: DATE (MM/DD/YYYY) `02/29/2019`",
            ),
            ("10/14/2018,6:5,5,0,3", "line 2: the time `6:5`"),
            ("10/14/2018", "line 2: no DATE (MM/DD/YYYY) and time fields"),
            (
                "10/14/18,00:00,5,0,3",
                "line 2: DATE (MM/DD/YYYY) `10/14/18`: expected a date MM/DD/YYYY",
            ),
            (
                "13/01/2018,00:00,5,0,3",
                "line 2: DATE (MM/DD/YYYY) `13/01/2018`",
            ),
            (
                "10/14/2018,24:00,5,0,3",
                "line 2: the time `24:00`: expected HH:MM, 00:00 to 23:59",
            ),
            ("10/14/2018,0600,5,0,3", "line 2: the time `0600`"),
            (
                "10/14/2018,06:00,x,0,3",
                "line 2: the global irradiance `x`",
            ),
        ] {
            let e = parse_as(&format!("{header}{row}\n"), MeasurementFormat::Midc).expect_err(row);
            assert!(e.contains(needle) && !e.contains('\n'), "{row}: {e}");
        }
        let e = parse_as(
            "DATE (MM/DD/YYYY),CET,Global PSP [W/m^2]\n",
            MeasurementFormat::Midc,
        )
        .expect_err("zone");
        assert!(
            e.contains("line 1: the MIDC header") && e.contains("after DATE"),
            "{e}"
        );
        // BMS's download: the year first, and a tilted plane's column before the horizontal's.
        let rows = parse_as(
            "DATE (YYYY/MM/DD),MST,Global 40-South CMP11 [W/m^2],Global CMP22 (vent/cor) [W/m^2],Direct NIP [W/m^2],Diffuse CM22-1 (vent/cor) [W/m^2]\n2022/01/20,12:00,700,500,900,60\n",
            MeasurementFormat::Midc,
        )
        .expect("MIDC BMS download");
        assert_eq!(rows[0].unix.rfc3339(), "2022-01-20T19:00:00Z");
        assert!(
            matches!(rows[0].measurement, Measurement::Irradiance { global, diffuse } if global == 500.0 && diffuse == 60.0),
            "{:?}",
            rows[0].measurement
        );
        let e = parse_as(
            "DATE (YYYY/MM/DD),MST,Global PSP [W/m^2]\n01/20/2022,12:00,5\n",
            MeasurementFormat::Midc,
        )
        .expect_err("the other order");
        assert!(
            e.contains("DATE (YYYY/MM/DD) `01/20/2022`: expected a date YYYY/MM/DD"),
            "{e}"
        );
        let e = parse_as("Date,MST,Global PSP [W/m^2]\n", MeasurementFormat::Midc)
            .expect_err("no date");
        assert!(
            e.contains("has no DATE (MM/DD/YYYY), DATE (YYYY/MM/DD) or Year column"),
            "{e}"
        );
    }

    /// SRML and BSRN files: the header's year and elements, the fixed columns, missing values,
    /// and each malformed part named with its line.
    #[test]
    fn srml_and_bsrn_files_are_read_and_bad_ones_named() {
        let srml = "94255\t2018\t1000\t0\t3001\t0\n1\t700\t-2.5\t12\t0\t12\n1\t701\t5\t99\t0\t12\n1\t2400\t10\t11\t30\t99\n";
        let rows = parse_as(srml, MeasurementFormat::Srml).expect("SRML");
        assert_eq!(rows.len(), 2, "the flagged GHI's row skipped");
        assert_eq!(rows[0].unix.rfc3339(), "2018-01-01T15:00:00Z");
        assert!(
            matches!(rows[0].measurement, Measurement::Irradiance { global, diffuse } if global == -2.5 && diffuse == 0.0)
        );
        assert_eq!(rows[1].unix.rfc3339(), "2018-01-02T08:00:00Z");
        assert!(matches!(rows[1].measurement, Measurement::GlobalIrradiance(g) if g == 10.0));
        for (text, needle) in [
            ("94255\t18x\t1000\t0\n", "line 1: the SRML header"),
            ("94255\t2018\t2010\t0\n", "no global horizontal irradiance"),
            (
                "94255\t2018\t1000\t0\n1\t761\t5\t12\n",
                "line 2: the time 0761: not HHMM",
            ),
            (
                "94255\t2018\t1000\t0\n1\t2401\t5\t12\n",
                "line 2: the time (HHMM) `2401`",
            ),
            (
                "94255\t2018\t1000\t0\n1\t700\t5\n",
                "line 2: no the global irradiance field",
            ),
            (
                "94255\t2018\t1000\t0\n1\t700\tx\t12\n",
                "the global irradiance `x`",
            ),
        ] {
            let e = parse_as(text, MeasurementFormat::Srml).expect_err(text);
            assert!(e.contains(needle) && !e.contains('\n'), "{text}: {e}");
        }
        let head = "*U0001\n 21  6 2016  1\n*C0003\nstation caf\u{e9}\n*U0100\n";
        let minute = |d: &str, m: &str, g: &str, dh: &str| {
            format!(
                "{d:>3} {m:>4} {g:>6}   0.1    0    0      0   0.0    0    0\n          {dh:>6}   0.2   -1    0    348   0.3  347  349      9.3 100.5  958\n"
            )
        };
        let good = format!(
            "{head}{}{}{}*U0300\nanything\n",
            minute("1", "0", "-999", "-999"),
            minute("1", "600", "500", "80"),
            minute("2", "1439", "3", "-999")
        );
        let rows = parse_as(&good, MeasurementFormat::Bsrn).expect("BSRN");
        assert_eq!(rows.len(), 2);
        assert_eq!(rows[0].unix.rfc3339(), "2016-06-01T10:00:00Z");
        assert!(
            matches!(rows[0].measurement, Measurement::Irradiance { global, diffuse } if global == 500.0 && diffuse == 80.0)
        );
        assert_eq!(rows[1].unix.rfc3339(), "2016-06-02T23:59:00Z");
        assert!(matches!(rows[1].measurement, Measurement::GlobalIrradiance(g) if g == 3.0));
        for (text, needle) in [
            (
                "*U0002\n".to_owned(),
                "line 1: a BSRN station-to-archive file starts with",
            ),
            (
                "*U0001\n 21 13 2016  1\n".to_owned(),
                "line 2: ` 21 13 2016  1`: expected the station, the month",
            ),
            (
                "*U0001\n 21  6 2016  1\n*U0300\n".to_owned(),
                "no basic measurements",
            ),
            (
                format!("{head}{}", minute("31", "0", "5", "5")),
                "the day 31: not a day of month 6",
            ),
            (
                format!("{head}{}", minute("1", "1440", "5", "5")),
                "the minute of the day (columns 5-9) `1440`",
            ),
            (
                format!("{head}{}", minute("1", "0", "abc", "5")),
                "line 6: the global irradiance (columns 11-16) `abc`",
            ),
            (
                format!("{head}{}", minute("1", "0", "5", "a")),
                "line 7: the diffuse irradiance",
            ),
            (
                format!("{head}  1    0      5   0.1    0    0\n"),
                "the file ends after the first",
            ),
            (
                format!(
                    "{head}{}{}",
                    minute("1", "5", "5", "5"),
                    minute("1", "4", "5", "5")
                ),
                "line 8: utc 2016-06-01T00:04:00Z: not after the time on line 6",
            ),
            (
                format!("{head}{}", minute("1", "0", "5\u{e9}", "5")),
                "line 6: not ASCII text",
            ),
        ] {
            let e = parse_as(&text, MeasurementFormat::Bsrn).expect_err(&text);
            assert!(
                e.starts_with("--measurements m.csv") && e.contains(needle) && !e.contains('\n'),
                "{text}: {e}"
            );
        }
        // A diffuse beyond the tolerance is set aside, within it kept.
        assert_eq!(
            station_reading(382.0, Some(413.0)),
            (Measurement::GlobalIrradiance(382.0), true)
        );
        assert_eq!(
            station_reading(382.0, Some(395.0)),
            (
                Measurement::Irradiance {
                    global: 382.0,
                    diffuse: 395.0
                },
                false
            )
        );
        assert_eq!(
            station_reading(-3.0, Some(6.0)),
            (
                Measurement::Irradiance {
                    global: -3.0,
                    diffuse: 6.0
                },
                false
            )
        );
    }
}
