//! Prints, as JSON on stdout, the values the native (host) build of sky-core gives for a set of
//! skies of every model and a set of view directions, and for a 16 × 16 fisheye image of each.
//! The wasm-bindgen tests (`sky-wasm/tests/wasm.rs`, run in node) build the same skies through
//! sky-wasm's API compiled for wasm32 and compare: `scripts/wasm.sh test` runs
//! `cargo run -p sky-wasm --example native_values > native_values.json` and hands the file to
//! their build.
//!
//! Also: the clear-sky daylight of a few days (sky-core's `Daylight` at the controller's sun,
//! for sky-wasm's `DaylightDay`) and Rust's own `Display` text of a thousand `f32`s across the
//! range (for the error messages' numbers, which sky-wasm writes without `core::fmt`).
//!
//! Everything here calls sky-core directly (not sky-wasm's bindings), so the comparison checks
//! the bindings as well as the wasm32 code generation.

use std::fmt::Write as _;

use sky_core::aoas::{AoasSky, DayCycle, Preset, Scattering};
use sky_core::controller::Settings;
use sky_core::daylight::{self, ClearAtmosphere, Daylight};
use sky_core::neural::{NeuralWeights, pretrained};
use sky_core::sh::ShSky;
use sky_core::solar::{Site, UtcTime};
use sky_core::{NeuralSky, PreethamSky, SkyError, Sun, Vec3, geom};
use sky_wasm::projection::{Kind, Projection};

/// The skies compared: which of `sky_wasm::Sky`'s constructors builds each one and its
/// arguments (JSON), and the native sky.
type Case = (String, Box<dyn Fn(&[Vec3], &mut [Vec3])>);

fn preetham(z: f32, a: f32, t: f32) -> Result<Case, SkyError> {
    let sky = PreethamSky::new(Sun::new(z, a)?, t)?;
    let spec = format!(r#"{{"kind":"preetham","args":[{z},{a},{t}]}}"#);
    Ok((spec, Box::new(move |d, o| sky.rgb_batch(d, o))))
}

fn neural(name: &str, w: &NeuralWeights, z: f32, a: f32, t: f32) -> Result<Case, SkyError> {
    let sky = NeuralSky::new(w, Sun::new(z, a)?, t)?;
    let spec = format!(r#"{{"kind":"neural","args":["{name}",{z},{a},{t}]}}"#);
    Ok((spec, Box::new(move |d, o| sky.rgb_batch(d, o))))
}

fn neural_file(path: &str, z: f32, a: f32, t: f32) -> anyhow::Result<Case> {
    let bytes = std::fs::read(path).map_err(|e| anyhow::anyhow!("{path}: {e}"))?;
    let w = NeuralWeights::<12>::decode(&bytes).map_err(|e| anyhow::anyhow!("{path}: {e}"))?;
    let sky = NeuralSky::new(&w, Sun::new(z, a)?, t)?;
    let spec = format!(r#"{{"kind":"neuralFromBytes","args":["{path}",{z},{a},{t}]}}"#);
    Ok((spec, Box::new(move |d, o| sky.rgb_batch(d, o))))
}

fn aoas(preset: Preset, sun: Option<(f32, f32)>) -> Result<Case, SkyError> {
    let mut style = preset.style();
    let spec = match sun {
        Some((z, a)) => {
            style.day_cycle = DayCycle::Sun(Sun::new(z, a)?);
            format!(
                r#"{{"kind":"aoasWithSun","args":["{}",{z},{a}]}}"#,
                preset.name()
            )
        }
        None => format!(r#"{{"kind":"aoas","args":["{}"]}}"#, preset.name()),
    };
    let sky = AoasSky::new(&Scattering::default(), &style)?;
    Ok((spec, Box::new(move |d, o| sky.rgb_batch(d, o))))
}

fn sh(z: f32, a: f32, t: f32, bands: u32) -> Result<Case, SkyError> {
    let sky = ShSky::new(Sun::new(z, a)?, t, bands as usize)?;
    let spec = format!(r#"{{"kind":"sh","args":[{z},{a},{t},{bands}]}}"#);
    Ok((
        spec,
        Box::new(move |d, o| {
            for (o, d) in o.iter_mut().zip(d) {
                *o = sky.radiance(*d);
            }
        }),
    ))
}

/// The daylight sky one direction at a time (`DaylightSky::rgb`): sky-wasm draws it through
/// `DaylightSky::rgb_batch`, so the parity tests compare the wasm32 batch with the host's single
/// direction.
fn daylight(z: f32, a: f32, aod: f32) -> Result<Case, SkyError> {
    let sky = Daylight::new(Sun::new(z, a)?, aod)?.sky();
    let spec = format!(r#"{{"kind":"daylight","args":[{z},{a},{aod}]}}"#);
    Ok((
        spec,
        Box::new(move |d, o| {
            for (o, d) in o.iter_mut().zip(d) {
                *o = sky.rgb(*d);
            }
        }),
    ))
}

fn floats(out: &mut String, values: impl IntoIterator<Item = f32>) {
    out.push('[');
    for (i, v) in values.into_iter().enumerate() {
        if i > 0 {
            out.push(',');
        }
        // Rust prints the shortest decimal that reads back as the same f32.
        let _ = write!(out, "{v}");
    }
    out.push(']');
}

/// The day's series that `sky_wasm::daylight::DaylightDay::at` gives for the same arguments
/// (year, month, day, start, end and step in seconds, latitude, longitude, elevation, optical
/// depth), as a JSON object; NaN (no CCT) as null.
#[allow(clippy::too_many_arguments, clippy::cast_possible_truncation)]
fn daylight_day(
    json: &mut String,
    (year, month, day): (i32, u32, u32),
    (start, end, step): (f64, f64, f64),
    (latitude, longitude, elevation): (f64, f64, f64),
    aod: f32,
) -> anyhow::Result<()> {
    let site = Site::new(latitude, longitude, elevation)?;
    let sun = Settings::default().sun;
    let mut columns: [(&str, Vec<f64>); 9] = [
        ("times", vec![]),
        ("elevationDeg", vec![]),
        ("globalLux", vec![]),
        ("diffuseLux", vec![]),
        ("directLux", vec![]),
        ("x", vec![]),
        ("y", vec![]),
        ("cctK", vec![]),
        ("melanopicEdiLux", vec![]),
    ];
    for k in 0.. {
        let t = start + f64::from(k) * step;
        if t > end {
            break;
        }
        let (hour, minute) = ((t / 3600.0) as u32, (t / 60.0) as u32 % 60);
        let time = UtcTime::new(
            year,
            month,
            day,
            hour,
            minute,
            t - f64::from(hour * 3600 + minute * 60),
        )?;
        let position = sun.position(&time, &site)?;
        // The controller's clear sky at the site: its pressure, the default ozone, the
        // sun's beam refracted.
        let atmosphere = ClearAtmosphere {
            aerosol_optical_depth: aod,
            elevation_m: elevation as f32,
            ozone_du: daylight::OZONE_DU,
        };
        let light = Daylight::refracted(&position, &atmosphere)?.on_day(time.day_of_year());
        let (x, y) = light.chromaticity();
        let row = [
            t,
            f64::from(position.elevation_deg() as f32),
            f64::from(light.global().y),
            f64::from(light.diffuse().y),
            f64::from(light.direct().y),
            f64::from(x),
            f64::from(y),
            light.cct().map_or(f64::NAN, |c| f64::from(c.kelvin)),
            f64::from(light.melanopic_edi()),
        ];
        for ((_, column), v) in columns.iter_mut().zip(row) {
            column.push(v);
        }
    }
    let _ = write!(
        json,
        r#"{{"args":[{year},{month},{day},{start},{end},{step},{latitude},{longitude},{elevation},{aod}]"#
    );
    for (name, column) in &columns {
        let _ = write!(json, r#","{name}":["#);
        for (i, v) in column.iter().enumerate() {
            let sep = if i > 0 { "," } else { "" };
            // f32 columns print as the shortest decimal of their f32 value; times as f64.
            if v.is_nan() {
                let _ = write!(json, "{sep}null");
            } else if *name == "times" {
                let _ = write!(json, "{sep}{v}");
            } else {
                let _ = write!(json, "{sep}{}", *v as f32);
            }
        }
        json.push(']');
    }
    json.push('}');
    Ok(())
}

/// A thousand `f32`s across the range (bit patterns of a xorshift sequence, whole numbers,
/// decimals and the ends) with Rust's `Display` text of each, as `[bits, "text"]`.
fn float_texts(json: &mut String) {
    let mut values = vec![
        0.0f32,
        -0.0,
        1.0,
        9.0,
        2.5,
        0.05,
        0.8,
        0.43,
        1.8,
        0.1,
        86_400.0,
        86_399.999,
        1e-45,
        f32::MIN_POSITIVE,
        f32::MAX,
        f32::MIN,
        1e-7,
        1.2e-7,
        1e21,
        123_456_790.0,
        f32::NAN,
        f32::INFINITY,
        f32::NEG_INFINITY,
        2010.0,
        2110.0,
        0.000_123,
        16_777_216.0,
    ];
    let mut state: u32 = 0x9E37_79B9;
    while values.len() < 1000 {
        state ^= state << 13;
        state ^= state >> 17;
        state ^= state << 5;
        let v = f32::from_bits(state);
        if v.is_finite() {
            values.push(v);
        }
    }
    json.push('[');
    for (i, v) in values.iter().enumerate() {
        let sep = if i > 0 { "," } else { "" };
        let _ = write!(json, r#"{sep}[{},"{v}"]"#, v.to_bits());
    }
    json.push(']');
}

fn main() -> anyhow::Result<()> {
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/..");
    std::env::set_current_dir(root)?;
    let mut cases = vec![
        preetham(0.3, 0.5, 2.5)?,
        preetham(1.2, 4.0, 5.5)?,
        preetham(1.55, 2.0, 3.0)?,
        neural("preetham", &pretrained::PREETHAM, 1.0, 1.0, 3.0)?,
        neural("preetham", &pretrained::PREETHAM, 0.1, 5.0, 5.9)?,
        neural("hosek", &pretrained::HOSEK, 0.6, 2.5, 7.0)?,
        neural_file("sky-core/weights/preetham.skyn", 0.8, 3.0, 4.0)?,
        aoas(Preset::Coral, Some((1.0, 2.0)))?,
        sh(0.5, 1.0, 3.0, 5)?,
        sh(1.4, 4.0, 5.5, 7)?,
        sh(0.9, 2.0, 2.5, 1)?,
        // The daylight sky: day, the day-dusk blend (88°), the dusk-night blend (97°),
        // twilight (100°), and a sun beyond 108° (which draws the 108° sky).
        daylight(0.6, 1.0, 0.43)?,
        daylight(1.536, 4.0, 0.2)?,
        daylight(1.693, 2.5, 0.8)?,
        daylight(1.745, 5.0, 0.05)?,
        daylight(2.5, 0.5, 0.3)?,
    ];
    for preset in Preset::ALL {
        cases.push(aoas(preset, None)?);
    }
    let mut directions = Vec::new();
    for zenith in [0.0f32, 0.2, 0.7, 1.2, 1.5, 1.570_796_4, 2.0] {
        for azimuth in [0.0f32, 1.0, 2.5, 4.0, 5.9] {
            directions.push((zenith, azimuth));
        }
    }
    let dirs: Vec<Vec3> = directions
        .iter()
        .map(|&(z, a)| geom::direction(z, a))
        .collect();
    let fisheye = Projection::new(Kind::Fisheye, 16, 16)?;

    let mut json = String::from("{\"directions\":[");
    for (i, (z, a)) in directions.iter().enumerate() {
        let sep = if i > 0 { "," } else { "" };
        let _ = write!(json, "{sep}[{z},{a}]");
    }
    json.push_str("],\"fisheye\":{\"width\":16,\"height\":16},\"skies\":[");
    for (i, (spec, eval)) in cases.iter().enumerate() {
        if i > 0 {
            json.push(',');
        }
        let _ = write!(json, "{{\"sky\":{spec},\"rgb\":");
        let mut rgb = vec![Vec3::ZERO; dirs.len()];
        eval(&dirs, &mut rgb);
        floats(&mut json, rgb.iter().flat_map(|c| c.to_array()));
        // The fisheye's linear image: sky-core's values at the projection's pixels, 0 elsewhere.
        let mut inside = vec![Vec3::ZERO; fisheye.directions().len()];
        eval(fisheye.directions(), &mut inside);
        let mut image = vec![0.0f32; fisheye.pixel_count() * 3];
        for (c, &p) in inside.iter().zip(fisheye.pixels()) {
            let at = p as usize * 3;
            image[at..at + 3].copy_from_slice(&c.to_array());
        }
        json.push_str(",\"fisheyeLinear\":");
        floats(&mut json, image);
        json.push('}');
    }
    json.push_str("],\"daylight\":[");
    // Vienna at midsummer, Longyearbyen in the polar night (twilight only), Singapore at the
    // equinox from 1:00 UTC in steps of 333.5 s under a hazy sky, Alamosa (2,317 m: its
    // pressure and refraction) on a clean winter day.
    let days = [
        (
            (2026, 6, 21),
            (0.0, 86_399.0, 600.0),
            (48.21, 16.37, 190.0),
            0.43,
        ),
        (
            (2030, 12, 21),
            (0.0, 86_399.0, 900.0),
            (78.22, 15.63, 10.0),
            0.1,
        ),
        (
            (2026, 3, 20),
            (3_600.0, 40_000.0, 333.5),
            (1.35, 103.82, 15.0),
            0.8,
        ),
        (
            (2016, 1, 1),
            (0.0, 86_399.0, 300.0),
            (37.70, -105.92, 2317.0),
            0.05,
        ),
    ];
    for (i, (date, times, site, aod)) in days.into_iter().enumerate() {
        if i > 0 {
            json.push(',');
        }
        daylight_day(&mut json, date, times, site, aod)?;
    }
    json.push_str("],\"floats\":");
    float_texts(&mut json);
    json.push('}');
    println!("{json}");
    Ok(())
}
