//! `sky-train bench`: ns/direction of every evaluator and ns/call of CCT, with ratios against
//! the peers.

use std::io::Write;

use anyhow::Result;
use clap::Args;

use crate::bench;

/// `bench`'s arguments.
#[derive(Args)]
pub struct BenchArgs {
    /// Grid width (directions per row).
    #[arg(long, default_value_t = 1024, value_parser = clap::value_parser!(u32).range(1..=16384))]
    width: u32,
    /// Grid height (rows over the upper hemisphere).
    #[arg(long, default_value_t = 512, value_parser = clap::value_parser!(u32).range(1..=16384))]
    height: u32,
    /// Timed runs per evaluator (the median is reported).
    #[arg(long, default_value_t = 15, value_parser = clap::value_parser!(u32).range(1..=1000))]
    runs: u32,
    /// Also time the physical atmosphere: its precomputation (not cached; tens of seconds),
    /// the sky of one sun position and the radiance per direction.
    #[arg(long)]
    physical: bool,
}

/// Runs the benchmarks and writes their tables to `output`.
///
/// # Errors
/// A model that cannot be built, a failed write.
pub fn run(args: &BenchArgs, output: &mut dyn Write) -> Result<()> {
    let dirs = bench::hemisphere_directions(args.width, args.height);
    let results = bench::run(&dirs, args.runs as usize)?;
    write!(
        output,
        "{}",
        bench::report(&results, args.width, args.height)
    )?;
    let sh = bench::sh_reconstruction(args.runs as usize)?;
    write!(output, "{}", bench::sh_report(&sh))?;
    let cct = bench::cct(args.runs as usize)?;
    write!(output, "{}", bench::cct_report(&cct))?;
    if args.physical {
        write!(
            output,
            "{}",
            bench::physical(&dirs, args.runs as usize, &results)?
        )?;
    }
    Ok(())
}
