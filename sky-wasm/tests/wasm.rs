//! sky-wasm compiled for wasm32 and run in node by `wasm-bindgen-test-runner`
//! (`scripts/wasm.sh test`, profile wasm-release with simd128, as the shipped .wasm):
//!
//! * parity: every model (Preetham, the neural sky with both shipped weight sets and from a weight
//!   file's bytes, every AOAS preset and one with its sun moved, SH, the daylight sky by day, in
//!   its networks' blends, in twilight and past astronomical twilight, through its batch path
//!   against the native one-direction path) gives the values of the native build of sky-core
//!   to 1e-6 relative, per direction through `Sky::rgb` and for a whole
//!   fisheye image through `Renderer::render_linear`;
//! * errors: sky-core's errors become `JsError`s (JavaScript `Error`s) carrying sky-core's
//!   message, and so do sky-wasm's own (unknown names, an output array of the wrong length);
//! * images: the 8-bit renderings are not blank and respond to exposure and to the sun;
//! * daylight: `DaylightDay` gives native sky-core's daylight series at the site (its pressure,
//!   the refracted beam), and refuses bad input with a message naming the parameter and its
//!   range;
//! * numbers: the error messages' numbers, written without `core::fmt`, are Rust's `Display`
//!   text of the same `f32`s.
//!
//! The native values are the JSON of `cargo run -p sky-wasm --example native_values`, an
//! independent host build of the same sky-core code, embedded at compile time from the file that
//! `SKY_NATIVE_VALUES` names. These tests call the Rust API directly; the JavaScript glue
//! (exported names, thrown exceptions, typed-array conversions) of the shipped module is tested
//! from JavaScript in `tests/node/`.
#![cfg(target_arch = "wasm32")]

use serde::Deserialize;
use sky_core::aoas::{AoasSky, DayCycle, Preset, Scattering};
use sky_core::daylight::Daylight;
use sky_core::neural::{NeuralWeights, pretrained};
use sky_core::sh::ShSky;
use sky_core::{NeuralSky, PreethamSky, SkyError, Sun};
use sky_wasm::daylight::DaylightDay;
use sky_wasm::number::f32_text;
use sky_wasm::{Renderer, Sky, aoas_presets};
use wasm_bindgen::{JsCast, JsError, JsValue};
use wasm_bindgen_test::{console_log, wasm_bindgen_test};

const NATIVE_VALUES: &str = include_str!(env!("SKY_NATIVE_VALUES"));

/// The weight files the native values name, by their path from the repository's root.
const WEIGHT_FILES: &[(&str, &[u8])] = &[(
    "sky-core/weights/preetham.skyn",
    include_bytes!("../../sky-core/weights/preetham.skyn"),
)];

const RELATIVE_BOUND: f32 = 1e-6;

#[derive(Deserialize)]
struct Native {
    /// (zenith, azimuth) in radians.
    directions: Vec<[f32; 2]>,
    fisheye: Size,
    skies: Vec<NativeSky>,
    daylight: Vec<NativeDay>,
    /// `f32` bit patterns and Rust's `Display` text of each.
    floats: Vec<(u32, String)>,
}

/// One day's daylight series; CCT `None` where sky-core has none (NaN in sky-wasm).
#[derive(Deserialize)]
#[serde(rename_all = "camelCase")]
struct NativeDay {
    /// Year, month, day, start, end, step (s), latitude, longitude, elevation, optical depth.
    args: (i32, u32, u32, f64, f64, f64, f64, f64, f64, f32),
    times: Vec<f64>,
    elevation_deg: Vec<f32>,
    global_lux: Vec<f32>,
    diffuse_lux: Vec<f32>,
    direct_lux: Vec<f32>,
    x: Vec<f32>,
    y: Vec<f32>,
    cct_k: Vec<Option<f32>>,
    melanopic_edi_lux: Vec<f32>,
}

#[derive(Deserialize)]
struct Size {
    width: u32,
    height: u32,
}

#[derive(Deserialize)]
#[serde(rename_all = "camelCase")]
struct NativeSky {
    sky: Spec,
    /// RGB per direction, flattened.
    rgb: Vec<f32>,
    /// The fisheye's linear RGB image, flattened; 0 outside the disc.
    fisheye_linear: Vec<f32>,
}

/// A `Sky` constructor and its arguments.
#[derive(Deserialize, Debug)]
#[serde(tag = "kind", content = "args", rename_all = "camelCase")]
enum Spec {
    Preetham(f32, f32, f32),
    Neural(String, f32, f32, f32),
    NeuralFromBytes(String, f32, f32, f32),
    Aoas([String; 1]),
    AoasWithSun(String, f32, f32),
    Sh(f32, f32, f32, u32),
    Daylight(f32, f32, f32),
}

fn native() -> Native {
    serde_json::from_str(NATIVE_VALUES).expect("SKY_NATIVE_VALUES is the example's JSON")
}

fn weight_file(path: &str) -> &'static [u8] {
    WEIGHT_FILES
        .iter()
        .find_map(|&(p, bytes)| (p == path).then_some(bytes))
        .unwrap_or_else(|| panic!("no weight file {path} in the test"))
}

/// The message of the JavaScript `Error` that `e` is.
fn message(e: JsError) -> String {
    let error: js_sys::Error = JsValue::from(e)
        .dyn_into()
        .expect("a JsError is a JavaScript Error");
    error.message().into()
}

/// The message of the error in `r`, which must be one.
fn error<T>(r: Result<T, JsError>) -> String {
    match r {
        Ok(_) => panic!("expected an error"),
        Err(e) => message(e),
    }
}

fn ok<T>(r: Result<T, JsError>) -> T {
    r.unwrap_or_else(|e| panic!("unexpected error: {}", message(e)))
}

fn build(spec: &Spec) -> Sky {
    ok(match spec {
        Spec::Preetham(z, a, t) => Sky::preetham(*z, *a, *t),
        Spec::Neural(weights, z, a, t) => Sky::neural(weights, *z, *a, *t),
        Spec::NeuralFromBytes(file, z, a, t) => {
            Sky::neural_from_bytes(weight_file(file), *z, *a, *t)
        }
        Spec::Aoas([preset]) => Sky::aoas(preset),
        Spec::AoasWithSun(preset, z, a) => Sky::aoas_with_sun(preset, *z, *a),
        Spec::Sh(z, a, t, bands) => Sky::sh(*z, *a, *t, *bands),
        Spec::Daylight(z, a, aod) => Sky::daylight(*z, *a, *aod),
    })
}

/// Largest |got − want| / |want| over the values; infinite where they differ and `want` is 0 or
/// `got` is not finite.
fn worst_relative(got: &[f32], want: &[f32]) -> f32 {
    assert_eq!(got.len(), want.len());
    got.iter()
        .zip(want)
        .map(|(&g, &w)| {
            if g == w {
                0.0
            } else if w == 0.0 || !g.is_finite() {
                f32::INFINITY
            } else {
                (g - w).abs() / w.abs()
            }
        })
        .fold(0.0, f32::max)
}

/// Checks every native sky that `select` picks, per direction and as a fisheye image, and returns
/// how many there were.
fn check_parity(select: impl Fn(&Spec) -> bool) -> usize {
    let native = native();
    let Size { width, height } = native.fisheye;
    let mut checked = 0;
    for case in native.skies.iter().filter(|c| select(&c.sky)) {
        let sky = build(&case.sky);
        let rgb: Vec<f32> = native
            .directions
            .iter()
            .flat_map(|&[z, a]| sky.rgb(z, a))
            .collect();
        let worst = worst_relative(&rgb, &case.rgb);
        let mut renderer = ok(Renderer::fisheye(width, height));
        let image = js_sys::Float32Array::new_with_length(width * height * 3);
        ok(renderer.render_linear(&sky, &image));
        let worst_image = worst_relative(&image.to_vec(), &case.fisheye_linear);
        console_log!(
            "{:?}: {} values, worst relative difference {worst}; {width}x{height} fisheye, {worst_image}",
            case.sky,
            rgb.len()
        );
        assert!(
            worst <= RELATIVE_BOUND,
            "{:?}: worst relative difference {worst} per direction",
            case.sky
        );
        assert!(
            worst_image <= RELATIVE_BOUND,
            "{:?}: worst relative difference {worst_image} in the fisheye image",
            case.sky
        );
        checked += 1;
    }
    checked
}

#[wasm_bindgen_test]
fn preetham_matches_native() {
    assert!(check_parity(|s| matches!(s, Spec::Preetham(..))) > 0);
}

#[wasm_bindgen_test]
fn neural_with_both_shipped_weight_sets_matches_native() {
    for weights in ["preetham", "hosek"] {
        let n = check_parity(|s| matches!(s, Spec::Neural(w, ..) if w == weights));
        assert!(n > 0, "no native values for the {weights} weights");
    }
}

#[wasm_bindgen_test]
fn neural_from_weight_file_bytes_matches_native() {
    assert!(check_parity(|s| matches!(s, Spec::NeuralFromBytes(..))) > 0);
}

#[wasm_bindgen_test]
fn every_aoas_preset_matches_native() {
    for preset in aoas_presets() {
        let n = check_parity(|s| matches!(s, Spec::Aoas([p]) if *p == preset));
        assert!(n > 0, "no native values for the AOAS preset {preset}");
    }
    assert!(check_parity(|s| matches!(s, Spec::AoasWithSun(..))) > 0);
}

#[wasm_bindgen_test]
fn sh_matches_native() {
    assert!(check_parity(|s| matches!(s, Spec::Sh(..))) > 0);
}

#[wasm_bindgen_test]
fn daylight_sky_matches_native() {
    assert!(check_parity(|s| matches!(s, Spec::Daylight(..))) >= 4);
}

#[wasm_bindgen_test]
fn sky_core_errors_carry_its_message() {
    let core = |e: SkyError| e.to_string();
    let sun = Sun::new(0.5, 0.0).expect("a valid sun");
    let low = Sun::new(2.0, 0.0).expect("a sun below the horizon is a valid Sun");
    let cases = [
        (
            Sky::preetham(0.5, 0.0, 9.0).map(drop),
            PreethamSky::new(sun, 9.0).map(drop),
            "turbidity = 9 is outside the valid range [2, 6]",
        ),
        (
            Sky::preetham(2.0, 0.0, 3.0).map(drop),
            PreethamSky::new(low, 3.0).map(drop),
            "the sun is below the horizon (zenith 2 rad > pi/2), where this model is undefined",
        ),
        (
            Sky::preetham(0.5, f32::NAN, 3.0).map(drop),
            Sun::new(0.5, f32::NAN).map(drop),
            "sun azimuth [rad] must be a finite number",
        ),
        (
            Sky::neural("hosek", 0.5, 0.0, 11.0).map(drop),
            NeuralSky::new(&pretrained::HOSEK, sun, 11.0).map(drop),
            "turbidity = 11 is outside the valid range [1, 10]",
        ),
        (
            Sky::sh(0.5, 0.0, 2.0, 5).map(drop),
            ShSky::new(sun, 2.0, 5).map(drop),
            "turbidity = 2 is outside the valid range [2.5, 6]",
        ),
        (
            Sky::sh(0.5, 0.0, 3.0, 8).map(drop),
            ShSky::new(sun, 3.0, 8).map(drop),
            "SH bands = 8 is outside the valid range [1, 7]",
        ),
        (
            Sky::daylight(0.5, 0.0, 0.9).map(drop),
            Daylight::new(sun, 0.9).map(drop),
            "aerosol optical depth = 0.9 is outside the valid range [0.05, 0.8]",
        ),
        (
            Sky::daylight(3.5, 0.0, 0.43).map(drop),
            Sun::new(3.5, 0.0).map(drop),
            "sun zenith [rad] = 3.5 is outside the valid range [0, 3.1415927]",
        ),
        (
            Sky::sh(2.0, 0.0, 3.0, 5).map(drop),
            ShSky::new(low, 3.0, 5).map(drop),
            "the sun is below the horizon (zenith 2 rad > pi/2), where this model is undefined",
        ),
    ];
    for (wasm, native, text) in cases {
        let native = core(native.expect_err(text));
        assert_eq!(native, text);
        assert_eq!(error(wasm), native);
    }
    let mut style = Preset::Coral.style();
    style.day_cycle = DayCycle::Sun(Sun::new(1.8, 0.0).expect("a valid Sun"));
    let native = core(
        AoasSky::new(&Scattering::default(), &style)
            .map(drop)
            .expect_err("a sun below the horizon"),
    );
    assert!(native.starts_with("the sun is below the horizon (zenith 1.8 rad"));
    assert_eq!(error(Sky::aoas_with_sun("coral", 1.8, 0.0)), native);
    assert_eq!(
        error(Renderer::fisheye(0, 16)),
        "image width [px] = 0 is outside the valid range [1, 4096]"
    );
}

#[wasm_bindgen_test]
fn bad_weight_bytes_carry_the_decoders_message() {
    let bytes = weight_file("sky-core/weights/preetham.skyn");
    let truncated = &bytes[..100];
    let mut corrupt = bytes.to_vec();
    corrupt[200] ^= 1;
    for bad in [truncated, &corrupt[..]] {
        let want = NeuralWeights::<12>::decode(bad)
            .expect_err("bad weight bytes")
            .to_string();
        assert_eq!(error(Sky::neural_from_bytes(bad, 0.5, 0.0, 3.0)), want);
    }
    assert!(
        error(Sky::neural_from_bytes(truncated, 0.5, 0.0, 3.0))
            .starts_with("weight file truncated")
    );
    assert!(
        error(Sky::neural_from_bytes(&corrupt, 0.5, 0.0, 3.0))
            .starts_with("weight file checksum mismatch")
    );
}

#[wasm_bindgen_test]
fn unknown_names_are_errors_naming_the_choices() {
    assert_eq!(
        error(Sky::neural("perez", 0.5, 0.0, 3.0)),
        r#"weights = "perez" is not a shipped neural sky ("preetham" or "hosek")"#
    );
    let presets = aoas_presets().join(", ");
    assert_eq!(
        error(Sky::aoas("mauve")),
        format!(r#"preset = "mauve" is not an AOAS style preset (one of: {presets})"#)
    );
    assert!(presets.starts_with("physical, sunrise"), "{presets}");
    assert!(error(Sky::aoas_with_sun("mauve", 0.5, 0.0)).starts_with(r#"preset = "mauve""#));
}

#[wasm_bindgen_test]
fn rendering_into_an_array_of_the_wrong_length_fails() {
    let sky = ok(Sky::preetham(0.5, 0.0, 3.0));
    let mut r = ok(Renderer::fisheye(8, 4));
    let short = js_sys::Uint8ClampedArray::new_with_length(8 * 4 * 3);
    assert_eq!(
        error(r.render_srgb(&sky, &short, 1.0)),
        "out has length 96, but a 8x4 image needs 128 (4 per pixel)"
    );
    assert_eq!(
        error(r.render_difference_srgb(&sky, &sky, &short, 1.0)),
        "out has length 96, but a 8x4 image needs 128 (4 per pixel)"
    );
    assert_eq!(
        error(r.render_linear(&sky, &js_sys::Float32Array::new_with_length(5))),
        "out has length 5, but a 8x4 image needs 96 (3 per pixel)"
    );
    let fits = js_sys::Uint8ClampedArray::new_with_length(16 * 16 * 4);
    assert_eq!(
        error(ok(Renderer::sphere(16)).render_srgb(&sky, &fits, 1.0)),
        "the sphere is lit by a spherical-harmonics sky: build it with Sky.sh"
    );
}

/// RGBA of pixel (`i`, `j`) of a `width`-wide image.
fn pixel(rgba: &[u8], width: usize, i: usize, j: usize) -> [u8; 4] {
    let at = (j * width + i) * 4;
    rgba[at..at + 4].try_into().expect("4 bytes")
}

fn render_srgb(r: &mut Renderer, sky: &Sky, exposure: f32) -> Vec<u8> {
    let out = js_sys::Uint8ClampedArray::new_with_length(r.width() * r.height() * 4);
    ok(r.render_srgb(sky, &out, exposure));
    out.to_vec()
}

#[wasm_bindgen_test]
fn the_fisheye_is_opaque_sky_inside_the_disc_and_responds_to_exposure() {
    let sky = ok(Sky::preetham(0.5, 0.0, 3.0));
    let e = sky.auto_exposure();
    assert!(
        e > 0.0 && e < 1e-3,
        "a daylight sky in cd/m² needs a small exposure, got {e}"
    );
    let mut r = ok(Renderer::fisheye(64, 64));
    let dim = render_srgb(&mut r, &sky, e);
    let bright = render_srgb(&mut r, &sky, 4.0 * e);
    assert_eq!(pixel(&dim, 64, 0, 0), [0; 4], "corner outside the disc");
    let [cr, cg, cb, ca] = pixel(&dim, 64, 32, 32);
    assert_eq!(ca, 255);
    assert!(cb > cr && cr > 0, "zenith {cr},{cg},{cb}");
    let sum = |img: &[u8]| img.iter().map(|&v| u64::from(v)).sum::<u64>();
    assert!(
        sum(&bright) > sum(&dim),
        "two stops more exposure is brighter"
    );
    // The difference of a sky with itself is black, however strongly exposed.
    let diff = js_sys::Uint8ClampedArray::new_with_length(64 * 64 * 4);
    ok(r.render_difference_srgb(&sky, &sky, &diff, 1e6));
    assert!(diff.to_vec().chunks(4).all(|px| px[..3] == [0, 0, 0]));
}

#[wasm_bindgen_test]
fn the_daylight_sky_in_twilight_is_dim_but_draws_under_its_own_exposure() {
    let day = ok(Sky::daylight(40f32.to_radians(), 0.0, 0.43));
    let mut r = ok(Renderer::fisheye(64, 64));
    for depression in [6.0f32, 12.0] {
        let dusk = ok(Sky::daylight((90.0 + depression).to_radians(), 0.0, 0.43));
        let e = dusk.auto_exposure();
        assert!(
            e > 1e3 * day.auto_exposure(),
            "{depression}° down: exposure {e} vs the day's {}",
            day.auto_exposure()
        );
        let rgba = render_srgb(&mut r, &dusk, e);
        let [cr, cg, cb, ca] = pixel(&rgba, 64, 32, 32);
        assert_eq!(ca, 255);
        assert!(
            cb > cr && cb > 32,
            "{depression}° down: zenith {cr},{cg},{cb}"
        );
    }
}

#[wasm_bindgen_test]
fn the_panorama_is_opaque_and_lighter_towards_the_sun() {
    // The sun low in the east (azimuth 0: the left edge of the panorama).
    let sky = ok(Sky::preetham(1.2, 0.0, 3.0));
    let mut r = ok(Renderer::panorama(64, 16));
    let rgba = render_srgb(&mut r, &sky, sky.auto_exposure());
    assert!(rgba.chunks(4).all(|px| px[3] == 255), "every pixel opaque");
    let lum = |i| {
        pixel(&rgba, 64, i, 8)[..3]
            .iter()
            .map(|&v| u32::from(v))
            .sum::<u32>()
    };
    assert!(
        lum(0) > lum(32),
        "towards the sun {} vs away {}",
        lum(0),
        lum(32)
    );
}

#[wasm_bindgen_test]
fn the_sphere_lit_by_the_sh_sky_is_brighter_on_the_suns_side() {
    // The sun in the east (azimuth 0), 60° from the zenith; the sphere is seen from the south,
    // east to the right.
    let sky = ok(Sky::sh(60f32.to_radians(), 0.0, 3.0, 5));
    let mut r = ok(Renderer::sphere(64));
    let rgba = render_srgb(&mut r, &sky, sky.auto_exposure());
    let lum = |i, j| {
        pixel(&rgba, 64, i, j)[..3]
            .iter()
            .map(|&v| u32::from(v))
            .sum::<u32>()
    };
    assert!(
        lum(56, 32) > lum(8, 32) + 30,
        "east {} vs west {}",
        lum(56, 32),
        lum(8, 32)
    );
    assert!(
        lum(32, 8) > lum(32, 56),
        "top {} vs bottom {}",
        lum(32, 8),
        lum(32, 56)
    );
    assert_eq!(pixel(&rgba, 64, 0, 0)[3], 0, "corner off the sphere");
}

fn daylight_day(
    args: (i32, u32, u32, f64, f64, f64, f64, f64, f64, f32),
) -> Result<DaylightDay, JsError> {
    let (year, month, day, start, end, step, lat, lon, elevation, aod) = args;
    DaylightDay::at(year, month, day, start, end, step, lat, lon, elevation, aod)
}

#[wasm_bindgen_test]
fn daylight_days_match_native() {
    let native = native();
    assert!(native.daylight.len() >= 4);
    for want in &native.daylight {
        let got = ok(daylight_day(want.args));
        assert_eq!(got.times(), want.times, "{:?}: times", want.args);
        let cct: Vec<f32> = want.cct_k.iter().map(|c| c.unwrap_or(f32::NAN)).collect();
        let got_cct = got.cct_k();
        assert!(
            got_cct
                .iter()
                .zip(&cct)
                .all(|(g, w)| g.is_nan() == w.is_nan()),
            "{:?}: CCT defined at other samples",
            want.args
        );
        let columns = [
            ("elevationDeg", got.elevation_deg(), &want.elevation_deg),
            ("globalLux", got.global_lux(), &want.global_lux),
            ("diffuseLux", got.diffuse_lux(), &want.diffuse_lux),
            ("directLux", got.direct_lux(), &want.direct_lux),
            ("x", got.x(), &want.x),
            ("y", got.y(), &want.y),
            (
                "melanopicEdiLux",
                got.melanopic_edi_lux(),
                &want.melanopic_edi_lux,
            ),
        ];
        let defined = |v: &[f32]| {
            v.iter()
                .copied()
                .filter(|c| !c.is_nan())
                .collect::<Vec<_>>()
        };
        let worst_cct = worst_relative(&defined(&got_cct), &defined(&cct));
        console_log!(
            "daylight {:?}: {} samples, CCT worst relative difference {worst_cct}",
            want.args,
            want.times.len()
        );
        assert!(
            worst_cct <= RELATIVE_BOUND,
            "{:?}: CCT {worst_cct}",
            want.args
        );
        for (name, got, want_column) in columns {
            // The direct light is exactly 0 below the horizon on both sides.
            let worst = worst_relative(&got, want_column);
            assert!(
                worst <= RELATIVE_BOUND,
                "{:?}: {name} worst relative difference {worst}",
                want.args
            );
        }
    }
}

#[wasm_bindgen_test]
fn daylight_bad_input_names_the_parameter_and_its_range() {
    let vienna = (2026, 6, 21, 0.0, 86_399.0, 600.0, 48.21, 16.37, 190.0, 0.43);
    let sun = Sun::new(0.5, 0.0).expect("a valid sun");
    assert_eq!(
        error(daylight_day((
            vienna.0, vienna.1, vienna.2, 0.0, 100.0, 10.0, 48.21, 16.37, 190.0, 0.9
        ))),
        Daylight::new(sun, 0.9)
            .expect_err("optical depth 0.9")
            .to_string()
    );
    assert_eq!(
        error(daylight_day((
            2026,
            6,
            21,
            0.0,
            100.0,
            10.0,
            48.21,
            16.37,
            190.0,
            f32::NAN
        ))),
        "aerosol optical depth = NaN is outside the valid range [0.05, 0.8]"
    );
    let cases = [
        (
            (2026, 6, 21, -1.0, 100.0, 10.0, 48.21, 16.37, 190.0, 0.43),
            "start [s after 0:00 UTC] = -1 is outside the valid range [0, 86399]",
        ),
        (
            (2026, 6, 21, 500.0, 100.0, 10.0, 48.21, 16.37, 190.0, 0.43),
            "end [s after 0:00 UTC] = 100 is outside the valid range [500, 86399]",
        ),
        (
            (2026, 6, 21, 0.0, 86_400.0, 10.0, 48.21, 16.37, 190.0, 0.43),
            "end [s after 0:00 UTC] = 86400 is outside the valid range [0, 86399]",
        ),
        (
            (2026, 6, 21, 0.0, 100.0, 0.0, 48.21, 16.37, 190.0, 0.43),
            "step [s] = 0 is outside the valid range [1, 86400]",
        ),
        (
            (2026, 6, 21, 0.0, 100.0, 10.0, 48.21, 16.37, 6000.0, 0.43),
            "site elevation [m] = 6000 is outside the valid range [-500, 5000]",
        ),
        (
            (2026, 6, 21, 0.0, 100.0, f64::NAN, 48.21, 16.37, 190.0, 0.43),
            "step [s] = NaN is outside the valid range [1, 86400]",
        ),
        (
            (2026, 6, 21, 0.0, 100.0, 10.0, 95.0, 16.37, 190.0, 0.43),
            "",
        ),
        (
            (2026, 2, 30, 0.0, 100.0, 10.0, 48.21, 16.37, 190.0, 0.43),
            "day = 30 is outside the valid range [1, 28]",
        ),
        (
            (1950, 6, 21, 0.0, 100.0, 10.0, 48.21, 16.37, 190.0, 0.43),
            "year (fast sun position, Grena 2012) = 1950 is outside the valid range [2000, 2110]",
        ),
    ];
    for (args, text) in cases {
        let got = error(daylight_day(args));
        if text.is_empty() {
            let native = sky_core::solar::Site::new(args.6, args.7, args.8)
                .expect_err("latitude 95")
                .to_string();
            assert_eq!(got, native);
            assert!(got.starts_with("latitude"), "{got}");
        } else {
            assert_eq!(got, text, "{args:?}");
        }
    }
    assert!(ok(daylight_day(vienna)).times().len() == 144);
}

#[wasm_bindgen_test]
fn error_numbers_are_rusts_display_text() {
    let native = native();
    assert!(native.floats.len() >= 1000);
    let wrong: Vec<_> = native
        .floats
        .iter()
        .filter_map(|(bits, text)| {
            let got = f32_text(f32::from_bits(*bits));
            (got != *text).then(|| format!("{bits:#010x}: {got} vs Rust's {text}"))
        })
        .collect();
    assert!(
        wrong.is_empty(),
        "{} of {} differ: {:?}",
        wrong.len(),
        native.floats.len(),
        &wrong[..wrong.len().min(10)]
    );
}
