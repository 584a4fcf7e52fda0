//! Prints, as JSON on stdout, the values the native (host) build of sky-core gives for a set of
//! skies of every model and a set of view directions, and for a 16 × 16 fisheye image of each.
//! The wasm-bindgen tests (`sky-wasm/tests/wasm.rs`, run in node) build the same skies through
//! sky-wasm's API compiled for wasm32 and compare: `scripts/wasm.sh test` runs
//! `cargo run -p sky-wasm --example native_values > native_values.json` and hands the file to
//! their build.
//!
//! Everything here calls sky-core directly (not sky-wasm's bindings), so the comparison checks
//! the bindings as well as the wasm32 code generation.

use std::fmt::Write as _;

use sky_core::aoas::{AoasSky, DayCycle, Preset, Scattering};
use sky_core::neural::{NeuralWeights, pretrained};
use sky_core::sh::ShSky;
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
    json.push_str("]}");
    println!("{json}");
    Ok(())
}
