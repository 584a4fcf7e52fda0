//! The sampled reference behind sky-core's generated daylight tables: the physical atmosphere
//! at every aerosol optical depth and sun elevation of a grid ([`sample`]),
//! and its CSV, one row per grid point in that order, then the row's values
//! ([`crate::daylight_tables`]' diffuse light, [`crate::daylight_planes`]' vertical planes).
//! One sampler, one writer and one checked reader for both.

use std::fmt::Write as _;
use std::io::Write as _;
use std::path::Path;

use anyhow::Result;
use rayon::prelude::*;

use crate::args::ParamError;
use crate::image_io::write_atomically;
use crate::physical::{Atmosphere, PhysicalSky, Resolution, cache};

/// `at(aod, elevation, sky)` for the sky of every optical depth of `aods` (the atmosphere
/// `atmosphere(aod)`) and sun elevation of `elevations` (degrees; the sun at azimuth 0), in
/// that order: each atmosphere precomputed (or read from `cache_dir`) with a progress bar when
/// `progress`, its elevations evaluated in parallel.
///
/// # Errors
/// When an atmosphere cannot be built or cached, or an elevation is out of the reference's
/// range.
pub fn sample<T: Send>(
    (cache_dir, progress): (&cache::CacheDir, bool),
    (aods, atmosphere): (&[f64], fn(f64) -> Atmosphere),
    elevations: &[f64],
    at: impl Fn(f64, f64, &PhysicalSky) -> T + Sync,
) -> Result<Vec<T>> {
    let mut out = Vec::with_capacity(aods.len() * elevations.len());
    for &aod in aods {
        let atm = cache::load_or_build_in(
            &atmosphere(aod),
            &Resolution::default(),
            Some(cache_dir),
            progress,
        )?;
        let rows: Vec<Result<T>> = elevations
            .par_iter()
            .map(|&h| Ok(at(aod, h, &atm.sky(90.0 - h, 0.0)?)))
            .collect();
        for row in rows {
            out.push(row?);
        }
    }
    Ok(out)
}

/// The grid of [`sample`] and of the files: every optical depth of `aods` at every elevation
/// of `elevations`, in that order.
#[must_use]
pub fn grid(aods: &[f64], elevations: &[f64]) -> Vec<(f64, f64)> {
    aods.iter()
        .flat_map(|&a| elevations.iter().map(move |&h| (a, h)))
        .collect()
}

/// One row: the grid point and its values.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    /// Aerosol optical depth at 550 nm.
    pub aod: f64,
    /// Geometric sun elevation, degrees.
    pub elevation_deg: f64,
    /// The values, in the header's order.
    pub values: Vec<f64>,
}

/// Writes `header` and `rows` (each `aod,elevation` then its values, 9 significant digits) to
/// `path`, atomically.
///
/// # Errors
/// When the file cannot be written.
pub fn write<'a>(
    path: &Path,
    header: &str,
    rows: impl IntoIterator<Item = (f64, f64, &'a [f64])>,
) -> Result<()> {
    let mut s = format!("{header}\n");
    for (aod, h, values) in rows {
        let _ = write!(s, "{aod},{h}");
        for v in values {
            let _ = write!(s, ",{v:.9e}");
        }
        s.push('\n');
    }
    write_atomically(path, |f| Ok(f.write_all(s.as_bytes())?))
}

/// Reads `path` (at most `max_bytes`) and checks it is `header` then one row per point of
/// `grid` (optical depth, elevation), in order, each with a value per further column of the
/// header that `check` accepts (`check(column, value)` gives the message for a bad one).
///
/// # Errors
/// A [`ParamError`] (bad input, exit status 2) naming the file and line of the first bad row
/// or field, and for a file without the header or rows; a plain error when it cannot be read.
pub fn read(
    path: &Path,
    max_bytes: u64,
    header: &str,
    grid: &[(f64, f64)],
    check: impl Fn(&str, f64) -> Option<String>,
) -> Result<Vec<Row>> {
    let bad =
        |line: usize, what: String| ParamError(format!("{}: line {line}: {what}", path.display()));
    // Bad input (exit 2): missing, not a regular file, longer than the grid can be, a line
    // longer than the reader takes.
    let input = crate::csv_input::read_lines(path, max_bytes)
        .map_err(|e| ParamError(format!("cannot read {}: {e}", path.display())))?;
    let columns: Vec<&str> = header.split(',').skip(2).collect();
    let mut expected = grid.iter();
    let mut out = Vec::new();
    let mut lines = 0;
    for (n, line) in input.enumerate() {
        let line = line.map_err(|e| bad(n + 1, e.to_string()))?;
        lines = n + 1;
        if n == 0 {
            if line.trim() != header {
                return Err(bad(1, format!("expected the header {header}")).into());
            }
            continue;
        }
        let values: Vec<f64> = line
            .split(',')
            .map(|v| v.trim().parse::<f64>())
            .collect::<Result<_, _>>()
            .map_err(|_| bad(n + 1, "not numbers".into()))?;
        let Some(&(aod, h)) = expected.next() else {
            return Err(bad(n + 1, "more rows than the grid".into()).into());
        };
        if !(values.len() == columns.len() + 2 && values[0] == aod && (values[1] - h).abs() < 1e-9)
        {
            return Err(bad(
                n + 1,
                format!(
                    "expected aod {aod}, elevation {h} and {} values",
                    columns.len()
                ),
            )
            .into());
        }
        for (v, column) in values[2..].iter().zip(&columns) {
            if let Some(message) = check(column, *v) {
                return Err(bad(n + 1, message).into());
            }
        }
        out.push(Row {
            aod,
            elevation_deg: h,
            values: values[2..].to_vec(),
        });
    }
    if lines == 0 {
        return Err(ParamError(format!("{}: the file is empty", path.display())).into());
    }
    if expected.next().is_some() {
        return Err(bad(
            lines,
            format!(
                "the data ends here, before the grid does ({} rows of {})",
                out.len(),
                grid.len()
            ),
        )
        .into());
    }
    Ok(out)
}
