//! `sky-train train`: a neural sky trained on a model (seed 000 §III), and its weight file.

use std::io::Write;
use std::path::PathBuf;

use anyhow::Result;
use clap::Args;

use crate::args::{ParamError, irradiance_weight, non_negative, seconds};
use crate::export;
use crate::output_path::{self, Folder};
use crate::sources::ModelKind;
use crate::train::{self, TrainConfig};

/// `train`'s arguments.
#[derive(Args)]
pub struct TrainArgs {
    /// The sky model to learn.
    #[arg(long, value_enum, default_value_t = ModelKind::Preetham)]
    pub model: ModelKind,
    /// Hidden layer sizes, comma-separated (1 to 255 each; `12` is the paper's network).
    #[arg(long, value_delimiter = ',', default_value = "12", value_parser = clap::value_parser!(u16).range(1..=255))]
    pub hidden: Vec<u16>,
    /// The optimiser.
    #[arg(long, value_enum, default_value_t = train::Optimizer::Lm)]
    pub optimizer: train::Optimizer,
    /// Random seed.
    #[arg(long, default_value_t = 1)]
    pub seed: u32,
    /// Wall-time budget in seconds (1 to 86400).
    #[arg(long, default_value_t = 60.0, value_parser = seconds)]
    pub max_seconds: f64,
    /// Iteration budget (LM steps or backprop epochs, 1 to 1000000).
    #[arg(long, default_value_t = 400, value_parser = clap::value_parser!(u32).range(1..=1_000_000))]
    pub max_iterations: u32,
    /// Stop once the validation NRMSE reaches this (0 = train to the budget or convergence).
    #[arg(long, default_value_t = 0.0, value_parser = non_negative)]
    pub target_nrmse: f64,
    /// Checkpoint file: resumed from when it exists, rewritten after every iteration.
    #[arg(long, value_name = "FILE")]
    pub checkpoint: Option<PathBuf>,
    /// Start from a 6-12-3 weight file (its network and its input/output scaling) instead of
    /// random weights: continues an earlier training on new samples or budgets.
    #[arg(long, value_name = "FILE")]
    pub init_weights: Option<PathBuf>,
    /// Weight file to write (single hidden layer only). Written atomically.
    #[arg(long, value_name = "FILE")]
    pub out: Option<PathBuf>,
    /// Training turbidities, comma-separated (default: the model's range in steps of 1, as in
    /// seed 000 §III-D).
    #[arg(long, value_delimiter = ',', value_name = "T,T,...")]
    pub turbidities: Option<Vec<f64>>,
    /// Training sun zeniths, uniform over [0, 90] deg inclusive (2 to 1000).
    #[arg(long, default_value_t = 20, value_parser = clap::value_parser!(u16).range(2..=1000))]
    pub sun_zeniths: u16,
    /// LM weight of each sky's irradiance residual (0 to 100; 0 = NRMSE only).
    #[arg(long, default_value_t = 1.0, value_parser = irradiance_weight)]
    pub irradiance_weight: f64,
    /// View strata per training sky: zenith x azimuth (each 1 to 1000).
    #[arg(long, default_value = "10x20", value_parser = strata)]
    pub views: (usize, usize),
}

fn strata(s: &str) -> Result<(usize, usize), String> {
    let parse = |v: &str| {
        v.trim()
            .parse::<usize>()
            .ok()
            .filter(|n| (1..=1000).contains(n))
    };
    match s.split_once('x').map(|(a, b)| (parse(a), parse(b))) {
        Some((Some(a), Some(b))) => Ok((a, b)),
        _ => Err("expected ZxA with each in [1, 1000], e.g. 10x20".into()),
    }
}

/// The training `args` ask for, checked: a model with skies to learn, turbidities in its
/// range, a network the optimiser can train and `--out` can hold, a checkpoint and initial
/// weights of that network, output files that can be written.
fn config(args: &TrainArgs) -> Result<TrainConfig> {
    if matches!(
        args.model,
        ModelKind::Neural | ModelKind::Cie | ModelKind::Perez
    ) {
        return Err(ParamError(format!(
            "--model {}: train learns preetham, hosek, neural-preetham, neural-hosek, aoas, sh or physical (cie and perez need a measurement, neural a weight file)",
            args.model
        ))
        .into());
    }
    let mut config = TrainConfig::new(args.model);
    config.hidden = args.hidden.iter().map(|&h| usize::from(h)).collect();
    config.optimizer = args.optimizer;
    config.check()?;
    if config.hidden != [12] {
        let layout: Vec<String> = args.hidden.iter().map(ToString::to_string).collect();
        let layout = layout.join(",");
        for (flag, given) in [
            ("--out", args.out.is_some()),
            ("--init-weights", args.init_weights.is_some()),
        ] {
            if given {
                return Err(ParamError(format!(
                    "{flag} holds a 6-12-3 network (the weight file's shape), and --hidden {layout} trains another: leave out {flag}, or train --hidden 12"
                ))
                .into());
            }
        }
    }
    if let Some(path) = &args.out {
        output_path::file("--out", path, Folder::Existing)?;
    }
    if let Some(path) = &args.checkpoint {
        output_path::file("--checkpoint", path, Folder::Existing)?;
        let mut sizes = vec![6];
        sizes.extend(&config.hidden);
        sizes.push(3);
        train::checkpoint::resume(path, &sizes)?;
    }
    config.seed = u64::from(args.seed);
    config.sampling.seed = u64::from(args.seed);
    if let Some(t) = &args.turbidities {
        let (lo, hi) = args.model.turbidity_range();
        if let Some(bad) = t.iter().find(|t| !(lo..=hi).contains(*t)) {
            return Err(ParamError(format!(
                "--turbidities {bad} is outside the valid range [{lo}, {hi}] for --model {}",
                args.model
            ))
            .into());
        }
        config.sampling.turbidities.clone_from(t);
    }
    config.sampling.sun_zeniths = usize::from(args.sun_zeniths);
    config.irradiance_weight = args.irradiance_weight;
    (config.sampling.view_zeniths, config.sampling.view_azimuths) = args.views;
    config.max_seconds = args.max_seconds;
    config.max_iterations = args.max_iterations as usize;
    config.target_nrmse = args.target_nrmse;
    config.checkpoint.clone_from(&args.checkpoint);
    if let Some(path) = &args.init_weights {
        let weights = super::weight_file("--init-weights", path)?;
        config.init = Some(
            export::from_weights(&weights)
                .map_err(|e| ParamError(format!("--init-weights {}: {e:#}", path.display())))?,
        );
    } else {
        // Timed from scratch only.
        config.milestone = train::Milestone::paper(args.model)?;
    }
    Ok(config)
}

/// Trains as `args` say, reports the validation and test NRMSE on `output`, and writes the
/// weight file of `--out`. Every argument, the output files and the network's size are checked
/// before the training set is sampled.
///
/// # Errors
/// Bad parameters, input files or output paths as a [`ParamError`], a failed training or
/// write.
pub fn run(args: &TrainArgs, output: &mut dyn Write) -> Result<()> {
    let config = config(args)?;
    let started = std::time::Instant::now();
    let set = train::dataset::DataSet::training(args.model, &config.sampling)?;
    let sampling = started.elapsed().as_secs_f64();
    let validation = train::validation_set(args.model)?;
    let trained = train::train(&config, &set, validation.as_slice())?;
    let wall = started.elapsed().as_secs_f64();
    writeln!(
        output,
        "trained {:?} on {} ({} examples) with {:?}: {} iterations, {:.1} s training, {:.1} s wall in all",
        trained.net.sizes,
        args.model,
        trained.examples,
        args.optimizer,
        trained.iterations,
        trained.seconds,
        wall
    )?;
    writeln!(output, "validation NRMSE {:.5}", trained.validation_nrmse)?;
    if config.milestone.is_some() {
        writeln!(output, "{}", milestone_line(&config, &trained, sampling))?;
    }
    let test = train::dataset::paper_test_set(args.model)?;
    writeln!(
        output,
        "test NRMSE (seed 000 protocol) {:.5}",
        trained.mean_nrmse(&test)
    )?;
    if let Some(path) = &args.out {
        // A 6-12-3 network: checked before training.
        let weights = export::to_weights::<12>(&trained, args.model, args.seed)?;
        export::write_weights(path, &weights)?;
        writeln!(output, "wrote {}", path.display())?;
    }
    Ok(())
}

/// When training reached seed 000's Table 1 NRMSE on its test protocol (the paper: 291 s),
/// counted from scratch: `sampling` seconds of making the training set, then training.
pub(super) fn milestone_line(
    config: &TrainConfig,
    trained: &train::Trained,
    sampling: f64,
) -> String {
    let Some(m) = &config.milestone else {
        return String::new();
    };
    let when = trained.milestone.map_or_else(
        || "not reached".to_string(),
        |(s, i)| {
            format!(
                "reached after {:.1} s wall from scratch ({sampling:.1} s sampling, {s:.1} s and {i} iterations training)",
                sampling + s
            )
        },
    );
    format!(
        "seed 000 Table 1 NRMSE {} on its test protocol ({} images; the paper trained 291 s): {when}",
        m.nrmse,
        m.images.len()
    )
}
