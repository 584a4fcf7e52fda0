//! The lighting controller's day on the host: `sky-train schedule` (sun, colour temperature,
//! illuminance and RGBW levels every few minutes of a day) and `sky-train cct` (CCT and Duv of
//! chromaticities), both through sky-core, so the firmware computes the same values.

use std::io::{BufRead, Write};

use anyhow::{Context, Result, bail};
use sky_core::cct;
use sky_core::controller::{example_luminaire, step};
use sky_core::solar::{Site, UtcTime};

use crate::args::{ParamError, stdin_pairs};

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
        let s = step(&time, &site, config.turbidity, config.full_scale_lux, &lamp).with_context(
            || format!("schedule at {year:04}-{month:02}-{day:02}T{hour:02}:{min:02} (--turbidity, --full-scale-lux)"),
        )?;
        let (sun, c, e, levels) = (s.sun, s.cct, s.illuminance, s.drive.levels);
        writeln!(
            output,
            "{year:04}-{month:02}-{day:02}T{hour:02}:{min:02}:00Z,{:.5},{:.5},{:.5},{:.5},{:.2},{:.6},{:.6e},{:.6},{:.6},{:.6},{:.6}",
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
        )?;
        minute += config.step_minutes;
    }
    Ok(())
}

/// Reads `x,y` lines (a header line is allowed; blank lines are skipped) and writes
/// `x,y,cct_k,duv`.
///
/// # Errors
/// A line that is not two numbers, or a chromaticity without a CCT, named by its line number.
pub fn cct_lines(input: &mut dyn BufRead, output: &mut dyn Write) -> Result<()> {
    writeln!(output, "x,y,cct_k,duv")?;
    for (n, x, y) in stdin_pairs(input, "x,y")? {
        let (xv, yv) = match (x.parse::<f32>(), y.parse::<f32>()) {
            (Ok(a), Ok(b)) => (a, b),
            _ if n == 1 => continue, // a header line
            _ => bail!(
                "stdin line {n}: x and y must be numbers (CIE 1931 chromaticity), got `{x},{y}`"
            ),
        };
        let c = cct::cct_duv(xv, yv).map_err(|e| {
            ParamError(format!(
                "stdin line {n}: {e} (x in [0, 1], y in (0, 1], CCT {}-{} K)",
                cct::MIN_CCT,
                cct::MAX_CCT
            ))
        })?;
        writeln!(output, "{x},{y},{:.3},{:.7}", c.kelvin, c.duv)?;
    }
    Ok(())
}
