//! `sky-train showcase`, the main job: the gallery, then a Preetham neural sky trained from
//! scratch and compared with seed 000's Tables 1-2.

use std::io::Write;
use std::path::PathBuf;

use anyhow::Result;
use clap::Args;

use super::gallery::{self, GalleryArgs};
use super::train::milestone_line;
use sky_core::neural::{NeuralWeights, pretrained};

use crate::args::seconds;
use crate::export;
use crate::sources::{self, ModelKind, SkyParams};
use crate::train::{self, TrainConfig};

/// `showcase`'s arguments.
#[derive(Args)]
pub struct ShowcaseArgs {
    /// Output folder (created if missing).
    #[arg(long, value_name = "DIR", default_value = "out")]
    out: PathBuf,
    /// Training budget in wall seconds (1 to 86400).
    #[arg(long, default_value_t = 60.0, value_parser = seconds)]
    seconds: f64,
}

/// Runs the showcase into `--out`, reporting on `output`.
///
/// # Errors
/// A folder that cannot be created, a failed training or write.
pub fn run(args: &ShowcaseArgs, output: &mut dyn Write) -> Result<()> {
    crate::output_path::folder("--out", &args.out)?;
    gallery::run(
        &GalleryArgs {
            out: args.out.clone(),
            width: 512,
        },
        output,
    )?;
    let model = ModelKind::Preetham;
    let mut config = TrainConfig::new(model);
    config.max_seconds = args.seconds;
    config.milestone = train::Milestone::paper(model)?;
    writeln!(
        output,
        "\ntraining a 6-12-3 neural sky on {model} from scratch (Levenberg-Marquardt, {} s budget)...",
        args.seconds
    )?;
    let sampling = std::time::Instant::now();
    let set = train::dataset::DataSet::training(model, &config.sampling)?;
    let sampling = sampling.elapsed().as_secs_f64();
    let validation = train::validation_set(model)?;
    let trained = train::train(&config, &set, validation.as_slice())?;
    writeln!(
        output,
        "{} iterations in {:.1} s; validation NRMSE {:.5}",
        trained.iterations, trained.seconds, trained.validation_nrmse,
    )?;
    writeln!(output, "{}", milestone_line(&config, &trained, sampling))?;
    let weights = export::to_weights::<12>(&trained, model, 1)?;
    let path = args.out.join("neural-preetham.skyn");
    export::write_weights(&path, &weights)?;
    writeln!(output, "wrote {}", path.display())?;
    let network = network_of(&weights);
    let this_run = crate::eval::evaluate(model, &network)?;
    // The shipped weights beside this run's: a short run is a demonstration of the trainer,
    // the shipped network the product of its long run (docs/training.md).
    let shipped = crate::eval::evaluate(model, &network_of(&pretrained::PREETHAM))?;
    write!(
        output,
        "{}",
        crate::eval::report(model, &[("this run", &this_run), ("shipped", &shipped)])
    )?;
    writeln!(
        output,
        "(this run: {:.0} s of training from scratch; shipped: sky-core's PREETHAM, 630 \
         iterations of the same trainer, `train --seed 3`, docs/training.md)",
        trained.seconds
    )?;
    let params = SkyParams::sun_and_turbidity(0.48 * 180.0, 90.0, 4.0);
    let path = args
        .out
        .join("fig6_preetham_reference_network_difference.png");
    crate::eval::write_comparison(&path, model, &*network(&params)?, &params, 512)?;
    writeln!(output, "wrote {}", path.display())?;
    Ok(())
}

/// The neural sky of `weights` as the evaluation's source.
fn network_of(
    weights: &NeuralWeights<12>,
) -> impl Fn(&SkyParams) -> Result<Box<dyn sources::SkySource>> + '_ {
    move |p| {
        Ok(Box::new(sources::Neural::new(
            weights,
            ModelKind::Neural,
            p,
        )?))
    }
}
