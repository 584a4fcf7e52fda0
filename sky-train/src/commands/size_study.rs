//! `sky-train size-study`: seed 000's 6-12-3 network beside smaller, larger and deeper ones.

use std::io::Write;

use anyhow::Result;
use clap::Args;

use crate::args::{ParamError, irradiance_weight, seconds};
use crate::sources::ModelKind;

/// `size-study`'s arguments.
#[derive(Args)]
pub struct SizeStudyArgs {
    /// The sky model to learn (preetham or hosek).
    #[arg(long, default_value = "preetham")]
    pub model: ModelKind,
    /// Training wall-time budget per network, seconds (1 to 86400).
    #[arg(long, default_value_t = 300.0, value_parser = seconds)]
    pub seconds: f64,
    /// Random seed (initial weights, view jitter).
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Hidden layouts to train, e.g. `6 12 24 48 12,12` (each one of those).
    #[arg(long, num_args = 1.., value_delimiter = ' ', default_values = ["6", "12", "24", "48", "12,12"])]
    pub layouts: Vec<String>,
    /// LM weight of each sky's irradiance residual (0 to 100; 0 = NRMSE only), as for `train`.
    #[arg(long, default_value_t = 1.0, value_parser = irradiance_weight)]
    pub irradiance_weight: f64,
}

/// Trains every layout and writes the Markdown table to `output`.
///
/// # Errors
/// A model other than preetham or hosek, a bad layout, a failed training or write.
pub fn run(args: &SizeStudyArgs, output: &mut dyn Write) -> Result<()> {
    if !matches!(args.model, ModelKind::Preetham | ModelKind::Hosek) {
        return Err(ParamError(format!(
            "--model {}: the size study trains on preetham or hosek",
            args.model
        ))
        .into());
    }
    let layouts = args
        .layouts
        .iter()
        .map(|l| {
            l.split(',')
                .map(|h| h.trim().parse::<usize>())
                .collect::<Result<Vec<_>, _>>()
                .map_err(|_| {
                    ParamError(format!("--layouts `{l}`: expected sizes like 12 or 12,12"))
                })
        })
        .collect::<Result<Vec<_>, _>>()?;
    let rows = crate::study::run(
        args.model,
        &layouts,
        args.seconds,
        args.seed,
        args.irradiance_weight,
        true,
    )?;
    write!(output, "{}", crate::study::table(args.model, &rows))?;
    Ok(())
}
