//! The optional sidecar manifest of a capture sequence, `captures.toml` beside the frames:
//!
//! ```toml
//! latitude = 48.21          # degrees north; with longitude, the sun's zenith comes from the times
//! longitude = 16.37         # degrees east
//! elevation = 190           # metres (optional, 0 when absent)
//! mask = "mask.png"         # sky mask (optional): white = sky, black = not sky, the frames' size
//!
//! [[frame]]
//! file = "sky_0600.exr"
//! time = "2026-06-21T06:00:00Z"   # RFC 3339, `Z` or a UTC offset like +02:00 (optional)
//! exposure = 0.84                 # camera units per unit of radiance (optional, 1 when absent)
//! ```
//!
//! Frames the manifest lists are the sequence, in the manifest's order; without a manifest every
//! `.exr` file of the folder is a frame, in file-name order.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};
use serde::Deserialize;

/// The manifest's file name.
pub const MANIFEST: &str = "captures.toml";

/// The largest manifest read, bytes: about 10,000 frames (a frame's entry is about 100
/// bytes); a manifest is read whole before it is parsed.
pub const MAX_MANIFEST_BYTES: u64 = 1 << 20;

/// A parsed manifest.
#[derive(Debug, Clone, Default, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Manifest {
    /// Latitude of the site, degrees north.
    pub latitude: Option<f64>,
    /// Longitude of the site, degrees east.
    pub longitude: Option<f64>,
    /// Elevation of the site, metres.
    pub elevation: Option<f64>,
    /// The sky mask image (PNG), relative to the folder.
    pub mask: Option<PathBuf>,
    /// The frames, in time order.
    #[serde(default, rename = "frame")]
    pub frames: Vec<FrameEntry>,
}

/// One frame of the manifest.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FrameEntry {
    /// The OpenEXR file, relative to the folder.
    pub file: PathBuf,
    /// The capture time (RFC 3339: `Z` for UTC, or a UTC offset such as `+02:00`).
    pub time: Option<String>,
    /// Camera units per unit of radiance: pixel values are divided by it.
    pub exposure: Option<f64>,
}

impl Manifest {
    /// The manifest of `dir`, or `None` when it has none.
    ///
    /// # Errors
    /// When the manifest cannot be read or parsed, or a value is out of range (the message names
    /// the file and the key).
    pub fn read(dir: &Path) -> Result<Option<Self>> {
        let path = dir.join(MANIFEST);
        if !path.exists() {
            return Ok(None);
        }
        let text = crate::image_io::read_text(&path, MAX_MANIFEST_BYTES)?;
        Self::parse(&text, &path).map(Some)
    }

    /// The manifest in `text`, read from `path` (named in errors), checked as [`Manifest::read`]
    /// checks it.
    ///
    /// # Errors
    /// As [`Manifest::read`].
    pub fn parse(text: &str, path: &Path) -> Result<Self> {
        let manifest: Self = toml::from_str(text)
            .map_err(|e| anyhow::anyhow!("{}: not a valid manifest: {e}", path.display()))?;
        manifest.check(path)?;
        Ok(manifest)
    }

    fn check(&self, path: &Path) -> Result<()> {
        let p = path.display();
        match (self.latitude, self.longitude) {
            (Some(lat), Some(lon)) => {
                if !(-90.0..=90.0).contains(&lat) {
                    bail!("{p}: latitude {lat} is outside [-90, 90] degrees");
                }
                if !(-180.0..=180.0).contains(&lon) {
                    bail!("{p}: longitude {lon} is outside [-180, 180] degrees");
                }
            }
            (None, None) => {}
            _ => bail!("{p}: latitude and longitude go together (one of them is missing)"),
        }
        for f in &self.frames {
            if let Some(e) = f.exposure
                && !(e.is_finite() && e > 0.0)
            {
                bail!(
                    "{p}: frame {}: exposure {e} is not a positive number",
                    f.file.display()
                );
            }
            if let Some(t) = &f.time {
                UnixTime::parse(t).with_context(|| format!("{p}: frame {}", f.file.display()))?;
            }
        }
        let timed = self.frames.iter().filter(|f| f.time.is_some()).count();
        if timed != 0 && timed != self.frames.len() {
            bail!("{p}: either every frame has a time or none does");
        }
        Ok(())
    }
}

/// A UTC instant as seconds since 1970-01-01T00:00:00Z (proleptic Gregorian, no leap seconds).
#[derive(Debug, Clone, Copy, PartialEq, PartialOrd)]
pub struct UnixTime(pub f64);

impl UnixTime {
    /// Parses RFC 3339, `YYYY-MM-DDTHH:MM:SS[.fff]` followed by `Z` (UTC) or a UTC offset
    /// `±HH:MM` (a camera's local time: `2026-06-21T08:00:00+02:00` is 06:00 UTC), years
    /// 1 to 2999 (sky-core's [`sky_core::solar::UtcTime`]). A leap second, `23:59:60`, is read
    /// as the first instant of the next day (POSIX time's reading: no leap seconds counted).
    ///
    /// # Errors
    /// When `s` is not of that form or a field is out of range.
    pub fn parse(s: &str) -> Result<Self> {
        let bad = || {
            anyhow::anyhow!(
                "time `{s}`: expected RFC 3339, YYYY-MM-DDTHH:MM:SS followed by Z or ±HH:MM"
            )
        };
        let s = s.trim();
        let (body, offset_seconds) = match s.strip_suffix(['Z', 'z']) {
            Some(body) => (body, 0.0),
            None => {
                // `±HH:MM` at the end, after the seconds.
                let split = s.len().checked_sub(6).ok_or_else(bad)?;
                let (body, offset) = (s.get(..split).ok_or_else(bad)?, &s[split..]);
                let sign = match offset.as_bytes()[0] {
                    b'+' => 1.0,
                    b'-' => -1.0,
                    _ => return Err(bad()),
                };
                let (oh, om) = offset[1..].split_once(':').ok_or_else(bad)?;
                let (Ok(oh), Ok(om)) = (oh.parse::<u32>(), om.parse::<u32>()) else {
                    return Err(bad());
                };
                if oh > 23 || om > 59 || offset[1..].len() != 5 {
                    return Err(bad());
                }
                (body, sign * f64::from(oh * 3600 + om * 60))
            }
        };
        let (date, time) = body.split_once(['T', ' ']).ok_or_else(bad)?;
        let (y, m, d) = crate::args::date_fields(date).ok_or_else(bad)?;
        let mut hms = time.split(':');
        let (Some(h), Some(mi), Some(sec), None) = (hms.next(), hms.next(), hms.next(), hms.next())
        else {
            return Err(bad());
        };
        let (Ok(h), Ok(mi), Ok(sec)) = (h.parse::<u32>(), mi.parse::<u32>(), sec.parse::<f64>())
        else {
            return Err(bad());
        };
        // A leap second, 23:59:60.x (RFC 3339 allows it at the end of a day): no leap seconds
        // are counted, so it is read as the next day's first second, as POSIX time reads it.
        #[allow(clippy::cast_possible_truncation)] // whole minutes of an offset below a day
        let utc_minute =
            (i64::from(h * 60 + mi) - (offset_seconds / 60.0) as i64).rem_euclid(24 * 60);
        let leap = utc_minute == 24 * 60 - 1 && (60.0..61.0).contains(&sec);
        let checked = if leap { 59.0 } else { sec };
        if !(0.0..60.0).contains(&checked) {
            bail!(
                "time `{s}`: second = {sec} is outside the valid range [0, 60) (60 only in the leap second 23:59:60 UTC)"
            );
        }
        sky_core::solar::UtcTime::new(y, m, d, h, mi, checked).map_err(|e| {
            let year = matches!(
                e,
                sky_core::SkyError::OutOfRange {
                    parameter: "year",
                    ..
                }
            );
            let what = crate::args::describe(e, str::to_owned, " = ");
            if year {
                anyhow::anyhow!("time `{s}`: {what} (the supported years)")
            } else {
                anyhow::anyhow!("time `{s}`: {what}")
            }
        })?;
        Ok(Self(
            Self::from_civil(y, m, d, h, mi, sec).0 - offset_seconds,
        ))
    }

    /// The instant `y-m-d h:mi:sec` UTC.
    #[must_use]
    pub fn from_civil(y: i32, m: u32, d: u32, h: u32, mi: u32, sec: f64) -> Self {
        // Days from civil (H. Hinnant's algorithm).
        let y = i64::from(y) - i64::from(m <= 2);
        let era = y.div_euclid(400);
        let yoe = y - era * 400;
        let mp = (i64::from(m) + 9) % 12;
        let doy = (153 * mp + 2) / 5 + i64::from(d) - 1;
        let doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
        let days = era * 146_097 + doe - 719_468;
        #[allow(clippy::cast_precision_loss)] // |days| < 2^31
        let seconds = days as f64 * 86_400.0;
        Self(seconds + f64::from(h * 3600 + mi * 60) + sec)
    }

    /// The calendar fields (year, month, day, hour, minute, second).
    #[must_use]
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    pub fn to_civil(self) -> (i32, u32, u32, u32, u32, f64) {
        let days = (self.0 / 86_400.0).floor();
        let rest = self.0 - days * 86_400.0;
        let z = days as i64 + 719_468;
        let era = z.div_euclid(146_097);
        let doe = z - era * 146_097;
        let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
        let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
        let mp = (5 * doy + 2) / 153;
        let d = (doy - (153 * mp + 2) / 5 + 1) as u32;
        let m = if mp < 10 { mp + 3 } else { mp - 9 } as u32;
        let y = (yoe + era * 400 + i64::from(m <= 2)) as i32;
        let h = (rest / 3600.0).floor();
        let mi = ((rest - h * 3600.0) / 60.0).floor();
        let sec = (rest - h * 3600.0 - mi * 60.0).clamp(0.0, 59.999_999);
        (y, m, d, h as u32, mi as u32, sec)
    }

    /// RFC 3339 with `Z`, to the second.
    #[must_use]
    pub fn rfc3339(self) -> String {
        let (y, m, d, h, mi, s) = self.to_civil();
        format!(
            "{y:04}-{m:02}-{d:02}T{h:02}:{mi:02}:{:02}Z",
            s.round().min(59.0)
        )
    }

    /// The sun's position at this instant at `site` (NREL SPA, `sky_core::solar`).
    ///
    /// # Errors
    /// Outside the years SPA accepts.
    pub fn sun_position(
        self,
        site: &sky_core::solar::Site,
    ) -> Result<sky_core::solar::SunPosition> {
        let (y, m, d, h, mi, s) = self.to_civil();
        let t = sky_core::solar::UtcTime::new(y, m, d, h, mi, s)
            .map_err(|e| anyhow::anyhow!("{}: {e}", self.rfc3339()))?;
        sky_core::solar::SunPosition::new(&t, site)
            .map_err(|e| anyhow::anyhow!("{}: {e}", self.rfc3339()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unix_time_round_trips_and_matches_known_instants() {
        // 2000-01-01T12:00:00Z is 946728000 s after the epoch (J2000.0 in UTC).
        let t = UnixTime::parse("2000-01-01T12:00:00Z").expect("valid");
        assert!((t.0 - 946_728_000.0).abs() < 1e-6);
        let t = UnixTime::parse("2026-06-21T23:59:30Z").expect("valid");
        assert_eq!(UnixTime(t.0 + 45.0).rfc3339(), "2026-06-22T00:00:15Z");
        assert!(UnixTime::parse("2026-06-21T06:00:00").is_err());
        assert!(UnixTime::parse("2026-02-30T06:00:00Z").is_err());
    }

    #[test]
    fn utc_offsets_are_local_times() {
        let utc = UnixTime::parse("2026-06-21T06:00:00Z").expect("valid");
        for local in [
            "2026-06-21T08:00:00+02:00",
            "2026-06-21T00:30:00-05:30",
            "2026-06-21T06:00:00+00:00",
            "2026-06-21T06:00:00z",
        ] {
            assert_eq!(UnixTime::parse(local).expect(local), utc, "{local}");
        }
        // Across midnight, backwards.
        let t = UnixTime::parse("2026-01-01T01:00:00+03:00").expect("valid");
        assert_eq!(t.rfc3339(), "2025-12-31T22:00:00Z");
        for bad in [
            "2026-06-21T08:00:00+2:00",
            "2026-06-21T08:00:00+24:00",
            "2026-06-21T08:00:00+02:60",
            "2026-06-21T08:00:00*02:00",
            "+02:00",
        ] {
            let e = UnixTime::parse(bad).expect_err(bad).to_string();
            assert!(e.contains(bad) && e.contains("RFC 3339"), "{e}");
        }
    }
}
