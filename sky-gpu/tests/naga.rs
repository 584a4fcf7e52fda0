//! Every generated shader parses and validates with naga (pinned in Cargo.lock): the WGSL
//! as written, the GLSL functions inside a GLSL 4.50 fragment shader (naga's GLSL front end
//! reads Vulkan GLSL, 440-460, whose uniforms live in blocks; the functions are the text the
//! ES 3.00 shader holds, and the browser tests compile that as ES 3.00 in WebGL2), with the
//! parameters as uniforms and as the constants of one sky.

use naga::valid::{Capabilities, ValidationFlags, Validator};
use sky_core::aoas::{AoasSky, Preset, Scattering};
use sky_core::daylight::Daylight;
use sky_core::neural::pretrained;
use sky_core::sh::ShSky;
use sky_core::{NeuralSky, PreethamSky, Sun};
use sky_gpu::models::{aoas, daylight, neural, preetham, sh};
use sky_gpu::{Language, Model, Shader, Storage};

fn validate(module: &naga::Module, what: &str) {
    Validator::new(ValidationFlags::all(), Capabilities::empty())
        .validate(module)
        .unwrap_or_else(|e| panic!("{what}: naga validation failed: {e:?}"));
}

fn check_wgsl(text: &str, what: &str) {
    let entry = "\n@fragment\nfn fs_main(@location(0) dir: vec3<f32>) -> @location(0) vec4<f32> {\n    return vec4<f32>(sky_radiance(dir), 1.0);\n}\n";
    let full = format!("{text}{entry}");
    let module = naga::front::wgsl::parse_str(&full)
        .unwrap_or_else(|e| panic!("{what}: WGSL does not parse:\n{}", e.emit_to_string(&full)));
    validate(&module, what);
    assert!(
        module
            .functions
            .iter()
            .any(|(_, f)| f.name.as_deref() == Some("sky_radiance")),
        "{what}: no sky_radiance"
    );
}

fn check_glsl(declarations: &str, functions: &str, what: &str) {
    let full = format!(
        "#version 450\n{declarations}\n{functions}\nlayout(location = 0) in vec3 v_dir;\nlayout(location = 0) out vec4 o_color;\nvoid main() {{\n    o_color = vec4(sky_radiance(v_dir), 1.0);\n}}\n"
    );
    let options = naga::front::glsl::Options::from(naga::ShaderStage::Fragment);
    let module = naga::front::glsl::Frontend::default()
        .parse(&options, &full)
        .unwrap_or_else(|e| panic!("{what}: GLSL does not parse: {e:?}\n{full}"));
    validate(&module, what);
}

/// Each model's shader and one sky's parameters.
fn skies() -> Vec<(Shader, Vec<f32>)> {
    let sun = Sun::new(0.9, 2.0).expect("valid sun");
    let preetham = PreethamSky::new(sun, 3.0).expect("valid sky");
    let neural = NeuralSky::new(&pretrained::HOSEK, sun, 4.0).expect("valid sky");
    let aoas = AoasSky::new(&Scattering::default(), &Preset::Coral.style()).expect("valid sky");
    let sh = ShSky::new(sun, 3.0, 5).expect("valid sky");
    // The sun 7° below the horizon: inside the dusk-to-night blend, two networks.
    let dusk = Daylight::clear(Sun::new(97f32.to_radians(), 2.0).expect("valid sun")).sky();
    vec![
        (
            Model::Preetham.shader(),
            preetham::params(&preetham).to_vec(),
        ),
        (Model::Neural.shader(), neural::params(&neural)),
        (
            Model::Aoas.shader(),
            aoas::params(&aoas).expect("no pattern").to_vec(),
        ),
        (Model::Sh.shader(), sh::params(&sh).to_vec()),
        (Model::Daylight.shader(), daylight::params(&dusk)),
    ]
}

#[test]
fn every_wgsl_shader_validates() {
    for (shader, params) in skies() {
        assert_eq!(params.len(), 4 * shader.params_len, "{}", shader.model);
        for (storage, kind) in [
            (Storage::UNIFORM, "uniform"),
            (
                Storage::Uniform {
                    group: 2,
                    binding: 5,
                },
                "uniform at 2, 5",
            ),
            (Storage::Constant(&params), "constants"),
        ] {
            let text = shader.source(Language::Wgsl, storage);
            check_wgsl(&text, &format!("{} WGSL ({kind})", shader.model));
        }
    }
}

#[test]
fn every_glsl_shader_validates() {
    for (shader, params) in skies() {
        let name = shader.model.params_name();
        let functions = shader.functions_source(Language::Glsl);
        // The uniform array in a block (Vulkan GLSL has no free uniforms), same name and type.
        let block = format!(
            "layout(std140, set = 0, binding = 0) uniform SkyParams {{\n    vec4 {name}[{}];\n}};\n",
            shader.params_len
        );
        assert!(
            shader
                .source(Language::Glsl, Storage::UNIFORM)
                .contains(&format!(
                    "uniform vec4 {name}[{}];\n\n{functions}",
                    shader.params_len
                )),
            "{}: the full text is the declaration and these functions",
            shader.model
        );
        check_glsl(
            &block,
            &functions,
            &format!("{} GLSL (uniform block)", shader.model),
        );
        let constants = shader.declaration(Language::Glsl, Storage::Constant(&params));
        check_glsl(
            &constants,
            &functions,
            &format!("{} GLSL (constants)", shader.model),
        );
    }
}

#[test]
fn a_six_hidden_neuron_network_validates_too() {
    let shader = neural::shader(6);
    assert_eq!(shader.params_len, 15);
    check_wgsl(
        &shader.source(Language::Wgsl, Storage::UNIFORM),
        "neural 6-6-3 WGSL",
    );
}

#[test]
fn the_checks_reject_a_broken_shader() {
    // The same checks on a shader with a type error (a vec3 returned as a float) must fail.
    let shader = Model::Preetham.shader();
    let broken = |lang| {
        shader
            .source(lang, Storage::UNIFORM)
            .replace("-> vec3<f32> {", "-> f32 {")
            .replace("vec3 sky_radiance(", "float sky_radiance(")
    };
    let wgsl = broken(Language::Wgsl);
    assert!(std::panic::catch_unwind(|| check_wgsl(&wgsl, "broken WGSL")).is_err());
    let glsl = broken(Language::Glsl).replace("uniform vec4 sky_preetham[7];", "");
    let block =
        "layout(std140, set = 0, binding = 0) uniform SkyParams { vec4 sky_preetham[7]; };\n";
    assert!(std::panic::catch_unwind(|| check_glsl(block, &glsl, "broken GLSL")).is_err());
}
