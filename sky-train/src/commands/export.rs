//! `sky-train export`: a weight file as Rust source for compile-time embedding in sky-core, a
//! sky model's GPU shader (GLSL ES 3.00 or WGSL, sky-gpu), or sky-wasm's module of them all.

use std::io::Write;
use std::path::PathBuf;

use anyhow::Result;
use clap::{Args, ValueEnum};

use super::SkyArgs;
use crate::args::ParamError;
use crate::output_path::{self, Folder};
use crate::sources::{ModelKind, SkyParams};
use crate::{export, image_io};

/// `export`'s arguments.
#[derive(Args)]
pub struct ExportArgs {
    /// f32 and fixed: the weight file (required). glsl and wgsl: `--model` names the shader,
    /// and with `--constants` these arguments name the sky whose parameters it holds.
    #[command(flatten)]
    sky: SkyArgs,
    /// The constant's name (f32 and fixed; e.g. PREETHAM).
    #[arg(long)]
    pub name: Option<String>,
    /// The file to write (atomically).
    #[arg(long, value_name = "FILE")]
    pub out: PathBuf,
    /// What to write: the f32 weights (`NeuralWeights`, for `NeuralSky`), the weights
    /// quantised to Q7.24 (`FixedNeuralWeights`, for `FixedNeuralSky` on parts without an
    /// FPU), a model's shader in GLSL ES 3.00 or WGSL, or the JavaScript module of every
    /// model's shader that sky-wasm ships.
    #[arg(long, value_enum, default_value_t = ExportFormat::F32)]
    pub format: ExportFormat,
    /// glsl and wgsl: write the parameters of the sky that `--sun-zenith`, `--turbidity`,
    /// `--weights`, `--style` or `--bands` name into the shader as constants (a shader for
    /// that sky alone); without it the shader reads them from a uniform array.
    #[arg(long)]
    pub constants: bool,
    /// wgsl without --constants: the uniform array's `@group` (default 0).
    #[arg(long)]
    pub group: Option<u32>,
    /// wgsl without --constants: the uniform array's `@binding` (default 0).
    #[arg(long)]
    pub binding: Option<u32>,
}

/// `export --format`.
#[derive(Clone, Copy, ValueEnum)]
pub enum ExportFormat {
    /// `NeuralWeights<12>` in f32.
    F32,
    /// `FixedNeuralWeights<12>` in Q7.24.
    Fixed,
    /// A model's shader, GLSL ES 3.00 (WebGL2).
    Glsl,
    /// A model's shader, WGSL (WebGPU).
    Wgsl,
    /// Every model's shader in both languages as a JavaScript module (sky-wasm's `shaders.js`).
    Js,
}

/// Writes what `--format` names to `--out`.
///
/// # Errors
/// A missing or inapplicable argument (a [`ParamError`]), an unreadable weight file, weights
/// that do not fit Q7.24, a failed write.
pub fn run(args: &ExportArgs, output: &mut dyn Write) -> Result<()> {
    check_applies(args)?;
    output_path::file("--out", &args.out, Folder::Existing)?;
    let text = match args.format {
        ExportFormat::F32 | ExportFormat::Fixed => {
            let (Some(path), Some(name)) = (&args.sky.weights, &args.name) else {
                return Err(ParamError(
                    "--format f32 and fixed need --weights FILE and --name NAME".into(),
                )
                .into());
            };
            // sky-core's daylight skies are 6-24-3 (f32 only); every other shipped sky 6-12-3.
            let len = std::fs::metadata(path).map_or(0, |m| m.len());
            if matches!(args.format, ExportFormat::F32)
                && len == sky_core::neural::weights::encoded_len(24) as u64
            {
                let weights = export::read_weights::<24>(path)
                    .map_err(|e| ParamError(format!("--weights {e:#}")))?;
                export::pretrained_source(&weights, name, path)?
            } else {
                let weights = super::weight_file("--weights", path)?;
                if matches!(args.format, ExportFormat::F32) {
                    export::pretrained_source(&weights, name, path)?
                } else {
                    export::pretrained_fixed_source(&weights, name, path)?
                }
            }
        }
        ExportFormat::Glsl => shader_source(args, sky_gpu::Language::Glsl)?,
        ExportFormat::Wgsl => shader_source(args, sky_gpu::Language::Wgsl)?,
        ExportFormat::Js => sky_gpu::js_module(),
    };
    image_io::write_text(&args.out, &text)?;
    super::report_written(output, &args.out);
    Ok(())
}

/// Refuses a flag the format does not use (issue 25: they were dropped without a word).
fn check_applies(args: &ExportArgs) -> Result<(), ParamError> {
    let format = args
        .format
        .to_possible_value()
        .map_or_else(String::new, |v| v.get_name().to_owned());
    let (weights, shader, wgsl_uniform, js) = match args.format {
        ExportFormat::F32 | ExportFormat::Fixed => (true, false, false, false),
        ExportFormat::Glsl => (false, true, false, false),
        ExportFormat::Wgsl => (false, true, !args.constants, false),
        ExportFormat::Js => (false, false, false, true),
    };
    let params_given = args.sky.params()? != SkyParams::default();
    let refused = [
        (args.name.is_some() && !weights, "--name", "f32 and fixed"),
        (
            args.sky.model != ModelKind::Preetham && !shader,
            "--model",
            "glsl and wgsl",
        ),
        (args.constants && !shader, "--constants", "glsl and wgsl"),
        (
            args.group.is_some() && !wgsl_uniform,
            "--group",
            "wgsl without --constants",
        ),
        (
            args.binding.is_some() && !wgsl_uniform,
            "--binding",
            "wgsl without --constants",
        ),
        (
            params_given && !shader,
            "--sun-zenith/--sun-azimuth/--turbidity/--style/--bands (the sky's parameters)",
            "glsl and wgsl with --constants",
        ),
        (
            js && args.sky.weights.is_some(),
            "--weights",
            "f32, fixed, glsl and wgsl",
        ),
    ];
    if let Some((_, flag, applies)) = refused.iter().find(|r| r.0) {
        return Err(ParamError(format!(
            "{flag} does not apply to --format {format} (only to {applies})"
        )));
    }
    Ok(())
}

/// `export --format glsl|wgsl`: the shader of `--model`, its parameters a uniform array or,
/// with `--constants`, the named sky's.
fn shader_source(args: &ExportArgs, lang: sky_gpu::Language) -> Result<String> {
    let sky = &args.sky;
    let model = match sky.model {
        ModelKind::Preetham => sky_gpu::Model::Preetham,
        ModelKind::NeuralPreetham | ModelKind::NeuralHosek | ModelKind::Neural => {
            sky_gpu::Model::Neural
        }
        ModelKind::Aoas => sky_gpu::Model::Aoas,
        ModelKind::Sh => sky_gpu::Model::Sh,
        ModelKind::Daylight => sky_gpu::Model::Daylight,
        ModelKind::Hosek | ModelKind::Cie | ModelKind::Perez | ModelKind::Physical => {
            return Err(ParamError(format!(
                "--model {} has no shader (preetham, neural, neural-preetham, neural-hosek, aoas, sh or daylight)",
                sky.model
            ))
            .into());
        }
    };
    let shader = model.shader();
    if !args.constants {
        if sky.params()? != SkyParams::default() || sky.weights.is_some() {
            return Err(ParamError(
                "--sun-zenith, --sun-azimuth, --turbidity, --weights, --style, --bands and --no-ringing-filter name one sky: add --constants to write its parameters into the shader".into(),
            )
            .into());
        }
        return Ok(shader.source(
            lang,
            sky_gpu::Storage::Uniform {
                group: args.group.unwrap_or(0),
                binding: args.binding.unwrap_or(0),
            },
        ));
    }
    let params = sky.source()?.shader_params();
    let (_, params) = params
        .ok_or_else(|| ParamError(format!("--model {} has no shader", sky.model)))?
        .map_err(|e| ParamError(format!("--style: {e}")))?;
    Ok(shader.source(lang, sky_gpu::Storage::Constant(&params)))
}
