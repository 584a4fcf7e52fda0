//! `sky-train export --format glsl|wgsl|js`: the committed shaders (sky-gpu/shaders/) and
//! sky-wasm's module of them (sky-wasm/js/shaders.js) are what the command writes, and
//! `--constants` writes the parameters sky-core computes for the named sky.

mod common;
use common::run;

use std::path::Path;

use sky_core::daylight::Daylight;
use sky_core::neural::pretrained;
use sky_core::{NeuralSky, PreethamSky, Sun};
use sky_gpu::{Language, Model, Storage};

fn root() -> &'static Path {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/.."))
}

fn export(args: &[&str]) -> String {
    let dir = tempfile::tempdir().expect("temp dir");
    let out = dir.path().join("shader.txt");
    let out_str = out.to_str().expect("UTF-8 path");
    let mut full = vec!["export"];
    full.extend_from_slice(args);
    full.extend_from_slice(&["--out", out_str]);
    let said = run(&full, "");
    assert_eq!(said.trim(), format!("wrote {out_str}"));
    std::fs::read_to_string(&out).expect("written")
}

#[test]
fn the_committed_shaders_regenerate() {
    for model in Model::ALL {
        for lang in Language::ALL {
            let ext = lang.extension();
            let written = export(&["--format", ext, "--model", model.name()]);
            assert_eq!(written, model.shader().source(lang, Storage::UNIFORM));
            let file = format!("sky-gpu/shaders/{model}.{ext}");
            let committed = std::fs::read_to_string(root().join(&file)).expect("committed shader");
            assert!(
                written == committed,
                "{file} is not what `sky-train export --format {ext} --model {model}` writes: regenerate it"
            );
        }
    }
    let js = export(&["--format", "js"]);
    let committed =
        std::fs::read_to_string(root().join("sky-wasm/js/shaders.js")).expect("committed module");
    assert!(
        js == committed,
        "sky-wasm/js/shaders.js is not what `sky-train export --format js` writes: regenerate it"
    );
    // Each model's uniform texts are in the module.
    for model in Model::ALL {
        let glsl = model.shader().source(Language::Glsl, Storage::UNIFORM);
        assert!(
            js.contains(&format!("export const {model} = {{")),
            "{model}"
        );
        assert!(
            js.contains(&glsl.replace('\n', "\\n")),
            "{model} GLSL in the module"
        );
    }
}

/// `export --constants` of `model` in `format` for the sky of sun zenith 40°, azimuth 25°,
/// turbidity 4.
fn export_sky(format: &str, model: &str) -> String {
    export(&[
        "--format",
        format,
        "--model",
        model,
        "--constants",
        "--sun-zenith",
        "40",
        "--sun-azimuth",
        "25",
        "--turbidity",
        "4",
    ])
}

#[test]
fn constants_are_the_named_skys_parameters() {
    let sun = Sun::new(40f32.to_radians(), 25f32.to_radians()).expect("valid sun");
    let preetham = PreethamSky::new(sun, 4.0).expect("valid sky");
    let written = export_sky("glsl", "preetham");
    let params = sky_gpu::models::preetham::params(&preetham);
    let want = Model::Preetham
        .shader()
        .source(Language::Glsl, Storage::Constant(&params));
    assert_eq!(written, want);
    assert!(written.contains("const vec4 sky_preetham[7] = vec4[7]("));

    let neural = NeuralSky::new(&pretrained::HOSEK, sun, 4.0).expect("valid sky");
    let written = export_sky("wgsl", "neural-hosek");
    let params = sky_gpu::models::neural::params(&neural);
    let want = Model::Neural
        .shader()
        .source(Language::Wgsl, Storage::Constant(&params));
    assert_eq!(written, want);
    // The folded constant of neuron 0 appears as the literal sky-core computed.
    assert!(written.contains(&format!("{:?}", params[4 * 15 + 3])));

    // The daylight sky, the sun 7 deg below the horizon (two networks share it), an optical
    // depth of 0.2.
    let sun = Sun::new(
        sky_train::sources::radians(97.0),
        sky_train::sources::radians(25.0),
    )
    .expect("valid sun");
    let sky = Daylight::new(sun, 0.2).expect("valid sky").sky();
    let written = export(&[
        "--format",
        "glsl",
        "--model",
        "daylight",
        "--constants",
        "--sun-zenith",
        "97",
        "--sun-azimuth",
        "25",
        "--aod",
        "0.2",
    ]);
    let params = sky_gpu::models::daylight::params(&sky);
    assert_eq!(params[3], 2.0, "two networks");
    let want = Model::Daylight
        .shader()
        .source(Language::Glsl, Storage::Constant(&params));
    assert_eq!(written, want);
}

#[test]
fn bad_combinations_are_usage_errors() {
    let dir = tempfile::tempdir().expect("temp dir");
    let out = dir.path().join("x.glsl");
    let out = out.to_str().expect("UTF-8 path");
    for (args, message) in [
        (
            vec!["--format", "glsl", "--model", "hosek"],
            "--model hosek has no shader",
        ),
        (
            vec![
                "--format",
                "glsl",
                "--model",
                "preetham",
                "--sun-zenith",
                "30",
            ],
            "add --constants",
        ),
        (
            vec![
                "--format",
                "wgsl",
                "--model",
                "aoas",
                "--style",
                "smiley",
                "--constants",
            ],
            "without cloud noise",
        ),
        (
            vec!["--format", "glsl", "--model", "preetham", "--constants"],
            "--sun-zenith",
        ),
        (vec!["--format", "f32"], "--weights FILE and --name NAME"),
        (
            vec![
                "--format",
                "wgsl",
                "--model",
                "daylight",
                "--constants",
                "--sun-zenith",
                "97",
                "--aod",
                "0.9",
            ],
            "--aod 0.9 is outside the valid range [0.05, 0.8] for --model daylight",
        ),
        (
            vec![
                "--format",
                "glsl",
                "--model",
                "preetham",
                "--constants",
                "--sun-zenith",
                "30",
                "--aod",
                "0.2",
            ],
            "--aod does not apply to --model preetham (only to --model physical, daylight)",
        ),
        (
            vec![
                "--format",
                "glsl",
                "--model",
                "daylight",
                "--constants",
                "--sun-zenith",
                "97",
                "--ozone-du",
                "300",
            ],
            "--ozone-du does not apply to --model daylight (only to --model physical)",
        ),
    ] {
        let mut full = vec!["sky-train", "export", "--out", out];
        full.extend_from_slice(&args);
        let cli = <sky_train::cli::Cli as clap::Parser>::try_parse_from(full).expect("parses");
        let err = sky_train::cli::execute(cli.command, &mut "".as_bytes(), &mut Vec::new())
            .expect_err("refused");
        assert!(
            err.is::<sky_train::sources::ParamError>(),
            "{args:?}: exit status 2 needs a ParamError, got {err:#}"
        );
        assert!(format!("{err:#}").contains(message), "{args:?}: {err:#}");
        assert!(!Path::new(out).exists(), "{args:?}: nothing written");
    }
}
