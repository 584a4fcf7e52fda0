//! `--style PRESET|FILE`: an AOAS style by preset name, or from a TOML file.
//!
//! A style file may name a `preset` to start from (default `physical`); every table it has then
//! replaces that part of the preset. Angles are in degrees, directions are
//! `[zenith_deg, azimuth_deg]` as everywhere on the command line:
//!
//! ```toml
//! preset = "yellow"
//!
//! [scattering]            # O'Neil's parameters; any subset
//! kr = 0.0025
//! km = 0.0010
//! sun_intensity = 20.0
//! mie_g = 0.99            # forward scattering for g > 0 (O'Neil writes -0.99)
//! wavelengths = [0.650, 0.570, 0.475]   # um
//! samples = 8
//! viewer = [0.0, 0.0, 0.0]              # skydome space, atmosphere thicknesses
//!
//! [ambiguity]             # eqs. 5-6
//! neighbourhood = 0.05    # l_pt, relative to the fragment's distance, 0 to 0.5
//! seed = 7
//!
//! [cloud_noise]           # eqs. 7-8
//! size = 0.1
//! strength = 0.8          # default 1: eq. 8 as written
//!
//! [sky_hue]               # Rayleigh constants per channel, 0 to 100
//! red = 16.0
//! green = 13.0
//! blue = 2.5
//!
//! [day_cycle]             # a time of day ...
//! time_of_day = 17.5      # hours, 6 to 18
//! noon_elevation = 60.0   # degrees (default 60)
//! # ... or a sun direction: sun_zenith = 80.0, sun_azimuth = 180.0
//!
//! [[clouds]]              # one table per point or polyline
//! points = [[60.0, 90.0], [55.0, 100.0], [58.0, 110.0]]
//! radius = 1.0            # degrees
//! fade = 2.0              # degrees
//! ```

use std::path::Path;

use serde::Deserialize;
use sky_core::aoas::{
    Ambiguity, AoasSky, CloudNoise, CloudShapes, DayCycle, Preset, Scattering, Style,
};
use sky_core::geom::{self, Sun};
use sky_core::{SkyError, Vec3};

use crate::args::{ParamError, describe, radians};

/// The largest style file read, bytes (a style with a thousand cloud polylines is smaller).
pub const MAX_STYLE_BYTES: u64 = 1 << 20;

/// The noon elevation of a `time_of_day` without one, in degrees (the presets' value).
const DEFAULT_NOON_ELEVATION_DEG: f64 = 60.0;

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct StyleFile {
    preset: Option<String>,
    scattering: Option<ScatteringTable>,
    ambiguity: Option<AmbiguityTable>,
    cloud_noise: Option<CloudNoiseTable>,
    sky_hue: Option<SkyHueTable>,
    day_cycle: Option<DayCycleTable>,
    clouds: Option<Vec<CloudTable>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ScatteringTable {
    kr: Option<f64>,
    km: Option<f64>,
    sun_intensity: Option<f64>,
    mie_g: Option<f64>,
    wavelengths: Option<[f64; 3]>,
    samples: Option<u32>,
    viewer: Option<[f64; 3]>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct AmbiguityTable {
    neighbourhood: f64,
    #[serde(default)]
    seed: u32,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct CloudNoiseTable {
    size: f64,
    strength: Option<f64>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct SkyHueTable {
    red: f64,
    green: f64,
    blue: f64,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct DayCycleTable {
    time_of_day: Option<f64>,
    noon_elevation: Option<f64>,
    sun_zenith: Option<f64>,
    sun_azimuth: Option<f64>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct CloudTable {
    points: Vec<[f64; 2]>,
    radius: f64,
    fade: f64,
}

#[allow(clippy::cast_possible_truncation)] // rounding to sky-core's f32 is the point
fn f32_of(x: f64) -> f32 {
    x as f32
}

/// The scattering parameters and style that `--style` names: a preset (see
/// [`Preset::name`]) or a TOML file as described in the module docs.
///
/// Every value is checked (the result makes a valid [`AoasSky`]).
///
/// # Errors
/// A one-line [`ParamError`] that starts with `--style` and names the preset list, the file's
/// line, or the key and its valid range.
pub fn load(spec: &str) -> Result<(Scattering, Style), ParamError> {
    if let Some(preset) = Preset::from_name(spec) {
        return Ok((Scattering::default(), preset.style()));
    }
    let path = Path::new(spec);
    let is_toml = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("toml"));
    if !is_toml && !path.is_file() {
        let names: Vec<&str> = Preset::ALL.iter().map(|p| p.name()).collect();
        return Err(ParamError(format!(
            "--style `{spec}` is neither a preset ({}) nor a .toml style file",
            names.join(", ")
        )));
    }
    let text = crate::image_io::read_text(path, MAX_STYLE_BYTES)
        .map_err(|e| ParamError(format!("--style {spec}: {:#}", e)))?;
    parse(spec, &text)
}

/// [`load`] for the TOML `text` of the file `spec`.
///
/// # Errors
/// As [`load`].
pub fn parse(spec: &str, text: &str) -> Result<(Scattering, Style), ParamError> {
    let fail = |msg: String| ParamError(format!("--style {spec}: {msg}"));
    let file: StyleFile = toml::from_str(text).map_err(|e| {
        let line = e.span().map_or(0, |s| {
            let before = &text.as_bytes()[..s.start.min(text.len())];
            1 + before.iter().filter(|b| **b == b'\n').count()
        });
        // toml's message may span lines; the first carries the reason.
        let reason = e.message().lines().next().unwrap_or("invalid TOML").trim();
        fail(format!("line {line}: {reason}"))
    })?;
    let sky_error = |e: SkyError| fail(describe(e, str::to_owned, " = "));
    let mut style = match &file.preset {
        None => Style::default(),
        Some(name) => Preset::from_name(name)
            .ok_or_else(|| fail(format!("preset = \"{name}\" is not a preset")))?
            .style(),
    };
    let mut scattering = Scattering::default();
    if let Some(t) = file.scattering {
        let s = &mut scattering;
        let set = |dst: &mut f32, v: Option<f64>| {
            if let Some(v) = v {
                *dst = f32_of(v);
            }
        };
        set(&mut s.kr, t.kr);
        set(&mut s.km, t.km);
        set(&mut s.sun_intensity, t.sun_intensity);
        set(&mut s.mie_g, t.mie_g);
        if let Some(w) = t.wavelengths {
            s.wavelengths = w.map(f32_of);
        }
        if let Some(n) = t.samples {
            s.samples = n;
        }
        if let Some(v) = t.viewer {
            s.viewer = Vec3::from_array(v.map(f32_of));
        }
    }
    if let Some(a) = file.ambiguity {
        style.ambiguity = Some(Ambiguity {
            neighbourhood: f32_of(a.neighbourhood),
            seed: a.seed,
        });
    }
    if let Some(n) = file.cloud_noise {
        style.cloud_noise = Some(CloudNoise {
            size: f32_of(n.size),
            strength: f32_of(n.strength.unwrap_or(1.0)),
        });
    }
    if let Some(h) = file.sky_hue {
        style.sky_hue = Some(Vec3::new(f32_of(h.red), f32_of(h.green), f32_of(h.blue)));
    }
    if let Some(d) = file.day_cycle {
        style.day_cycle = day_cycle(&d).map_err(fail)?;
        style.day_cycle.sun().map_err(sky_error)?;
    }
    if let Some(clouds) = file.clouds {
        let mut shapes = CloudShapes::new();
        for (i, c) in clouds.iter().enumerate() {
            let points: Vec<Vec3> = c
                .points
                .iter()
                .map(|[z, a]| geom::direction(radians(*z), radians(*a)))
                .collect();
            shapes
                .push_polyline(&points, radians(c.radius), radians(c.fade))
                .map_err(|e| {
                    let at = format!("clouds[{i}].");
                    fail(describe(e, |p| p.replacen("clouds.", &at, 1), " = "))
                })?;
        }
        style.cloud_shapes = shapes;
    }
    // Every value in range, named by its key.
    AoasSky::new(&scattering, &style).map_err(sky_error)?;
    Ok((scattering, style))
}

/// The `[day_cycle]` table: a time of day, or a sun direction.
fn day_cycle(d: &DayCycleTable) -> Result<DayCycle, String> {
    match (d.time_of_day, d.sun_zenith) {
        (Some(hours), None) => {
            if d.sun_azimuth.is_some() {
                return Err("day_cycle: sun_azimuth goes with sun_zenith, not time_of_day".into());
            }
            Ok(DayCycle::TimeOfDay {
                hours: f32_of(hours),
                noon_elevation: radians(d.noon_elevation.unwrap_or(DEFAULT_NOON_ELEVATION_DEG)),
            })
        }
        (None, Some(zenith)) => {
            if d.noon_elevation.is_some() {
                return Err(
                    "day_cycle: noon_elevation goes with time_of_day, not sun_zenith".into(),
                );
            }
            if !(0.0..=90.0).contains(&zenith) {
                return Err(format!(
                    "day_cycle.sun_zenith = {zenith} deg is outside the valid range [0, 90] deg"
                ));
            }
            let azimuth = d.sun_azimuth.unwrap_or(0.0);
            Sun::new(radians(zenith), radians(azimuth))
                .map(DayCycle::Sun)
                .map_err(|_| "day_cycle.sun_azimuth must be a finite number".into())
        }
        _ => Err("day_cycle needs either time_of_day (hours) or sun_zenith (degrees)".into()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn err(text: &str) -> String {
        parse("s.toml", text).expect_err(text).0
    }

    #[test]
    fn presets_by_name() {
        for p in Preset::ALL {
            let (scattering, style) = load(p.name()).expect("a preset");
            assert_eq!(scattering, Scattering::default());
            assert_eq!(style, p.style());
        }
        let e = load("mauve").expect_err("not a preset").0;
        assert!(e.contains("--style `mauve`") && e.contains("coral"), "{e}");
    }

    #[test]
    fn a_file_overrides_its_preset() {
        let (scattering, style) = parse(
            "s.toml",
            r#"
            preset = "coral"
            [scattering]
            samples = 12
            kr = 0.003
            [ambiguity]
            neighbourhood = 0.1
            seed = 3
            [day_cycle]
            sun_zenith = 80
            sun_azimuth = 45
            [[clouds]]
            points = [[40, 90], [45, 100]]
            radius = 1
            fade = 2
            [[clouds]]
            points = [[30, 10]]
            radius = 3
            fade = 2.5
            "#,
        )
        .expect("valid");
        assert_eq!(scattering.samples, 12);
        assert!((scattering.kr - 0.003).abs() < 1e-9);
        assert_eq!(style.sky_hue, Preset::Coral.style().sky_hue);
        assert_eq!(
            style.ambiguity,
            Some(Ambiguity {
                neighbourhood: 0.1,
                seed: 3
            })
        );
        assert_eq!(style.cloud_shapes.len(), 2);
        let sun = style.day_cycle.sun().expect("valid sun");
        assert!((sun.zenith().to_degrees() - 80.0).abs() < 1e-4);
    }

    #[test]
    fn errors_name_the_key_and_range() {
        let cases = [
            (
                "[ambiguity]\nneighbourhood = 0.7",
                "ambiguity.neighbourhood = 0.7 is outside the valid range [0, 0.5]",
            ),
            (
                "[cloud_noise]\nsize = 0",
                "cloud_noise.size = 0 is outside the valid range [0.01, 10]",
            ),
            (
                "[sky_hue]\nred = 1\ngreen = 2\nblue = 200",
                "sky_hue.blue = 200 is outside the valid range [0, 100]",
            ),
            (
                "[day_cycle]\ntime_of_day = 20",
                "day_cycle.time_of_day = 20 h is outside the valid range [6, 18] h",
            ),
            (
                "[day_cycle]\nsun_zenith = 95",
                "day_cycle.sun_zenith = 95 deg is outside the valid range [0, 90] deg",
            ),
            (
                "[day_cycle]\nnoon_elevation = 30",
                "day_cycle needs either time_of_day",
            ),
            (
                "[[clouds]]\npoints = [[10, 10]]\nradius = 100\nfade = 1",
                "clouds[0].radius = 100 deg is outside the valid range [0, 90] deg",
            ),
            (
                "[[clouds]]\npoints = []\nradius = 1\nfade = 1",
                "clouds[0].points (count) = 0",
            ),
            ("preset = \"mauve\"", "preset = \"mauve\" is not a preset"),
            ("[scattering]\nsamples = -3", "line 2"),
            ("colour = 3", "line 1: unknown field `colour`"),
            ("[ambiguity]\nneighbourhood = \"lots\"", "line 2"),
        ];
        for (text, want) in cases {
            let e = err(text);
            assert!(e.starts_with("--style s.toml: "), "{e}");
            assert!(e.contains(want), "`{text}`: `{e}` lacks `{want}`");
            assert_eq!(e.lines().count(), 1, "{e}");
        }
        // Too many cloud segments: the capacity, not a panic.
        let mut text = String::new();
        for _ in 0..=CloudShapes::CAPACITY {
            text += "[[clouds]]\npoints = [[10, 10]]\nradius = 1\nfade = 1\n";
        }
        let e = err(&text);
        assert!(
            e.contains("cloud segments") && e.contains("at most 64"),
            "{e}"
        );
    }
}
