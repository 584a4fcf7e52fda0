//! `sky-train fuzz-weights`: sky-core's weight-file decoder against mutated files.

use std::io::Write;

use anyhow::Result;
use clap::Args;

use crate::args::seconds;

/// `fuzz-weights`' arguments.
#[derive(Args)]
pub struct FuzzArgs {
    /// How long to fuzz, in seconds (1 to 86400).
    #[arg(long, default_value_t = 10.0, value_parser = seconds)]
    pub seconds: f64,
    /// Random seed of the mutations.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
}

/// Fuzzes for `--seconds` and reports the inputs tried.
///
/// # Errors
/// A decoder that accepted a file it cannot round-trip, a failed write.
pub fn run(args: &FuzzArgs, output: &mut dyn Write) -> Result<()> {
    let stats =
        crate::fuzz::fuzz_weights(std::time::Duration::from_secs_f64(args.seconds), args.seed)?;
    writeln!(
        output,
        "fuzz-weights: {} inputs, {} accepted, no panic, every accepted file round-trips",
        stats.inputs, stats.accepted
    )?;
    Ok(())
}
