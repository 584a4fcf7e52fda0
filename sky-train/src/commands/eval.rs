//! `sky-train eval`: a neural sky on seed 000's test protocol, Tables 1-2 and Figs. 6-7.

use std::io::Write;
use std::path::PathBuf;

use anyhow::{Context, Result};
use clap::Args;
use sky_core::neural::{NeuralWeights, pretrained};

use crate::args::ParamError;
use crate::output_path;
use crate::sources::{self, ModelKind, SkyParams};

/// `eval`'s arguments.
#[derive(Args)]
pub struct EvalArgs {
    /// The network: a shipped one, or `neural` with `--weights`.
    #[arg(long, value_enum, default_value_t = ModelKind::NeuralPreetham)]
    pub model: ModelKind,
    /// Weight file of `--model neural`.
    #[arg(long, value_name = "FILE")]
    pub weights: Option<PathBuf>,
    /// Folder for the comparison images (created if missing).
    #[arg(long, value_name = "DIR", default_value = "out")]
    pub out: PathBuf,
}

/// Evaluates the network of `args`, writes the tables to `output` and the comparison image
/// into `--out`.
///
/// # Errors
/// A bad model or weight file, a failed write.
pub fn run(args: &EvalArgs, output: &mut dyn Write) -> Result<()> {
    output_path::folder("--out", &args.out)?;
    let weights: NeuralWeights<12> = match (args.model, &args.weights) {
        (ModelKind::NeuralPreetham, None) => pretrained::PREETHAM,
        (ModelKind::NeuralHosek, None) => pretrained::HOSEK,
        (ModelKind::Neural, Some(path)) => super::weight_file("--weights", path)?,
        (ModelKind::Neural, None) => refuse("--model neural needs --weights FILE".into())?,
        (ModelKind::NeuralPreetham | ModelKind::NeuralHosek, Some(_)) => refuse(format!(
            "--weights applies to --model neural only, not --model {}",
            args.model
        ))?,
        (model, _) => refuse(format!(
            "--model {model}: eval takes neural-preetham, neural-hosek or neural --weights FILE"
        ))?,
    };
    let reference = match weights.source_name() {
        "preetham" => ModelKind::Preetham,
        "hosek" => ModelKind::Hosek,
        "aoas" => ModelKind::Aoas,
        other => refuse(format!(
            "--weights: the weights were trained on `{other}`, which eval has no reference for (preetham, hosek, aoas)"
        ))?,
    };
    let network = |p: &SkyParams| -> Result<Box<dyn sources::SkySource>> {
        Ok(Box::new(sources::Neural::new(&weights, args.model, p)?))
    };
    let evaluation = crate::eval::evaluate(reference, &network)?;
    write!(output, "{}", evaluation.report())?;
    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("cannot create --out {}", args.out.display()))?;
    // The skies of seed 000's Figs. 6 (Preetham, θ = 0.48π, t = 4) and 7 (Hosek, θ = 0.3π, t = 2).
    let (figure, zenith, turbidity) = match reference {
        ModelKind::Hosek => ("fig7", 0.3 * 180.0, 2.0),
        _ => ("fig6", 0.48 * 180.0, 4.0),
    };
    let params = SkyParams::sun_and_turbidity(zenith, 90.0, turbidity);
    let path = args.out.join(format!(
        "{figure}_{reference}_reference_network_difference.png"
    ));
    crate::eval::write_comparison(&path, reference, &*network(&params)?, &params, 512)?;
    writeln!(output, "wrote {}", path.display())?;
    Ok(())
}

/// Bad arguments: `message` as a [`ParamError`].
fn refuse<T>(message: String) -> Result<T, ParamError> {
    Err(ParamError(message))
}
