//! `sky-train export`: a weight file as Rust source for compile-time embedding in sky-core.

use std::io::Write;
use std::path::PathBuf;

use anyhow::Result;
use clap::{Args, ValueEnum};

use crate::{export, image_io};

/// `export`'s arguments.
#[derive(Args)]
pub struct ExportArgs {
    /// The weight file.
    #[arg(long, value_name = "FILE")]
    pub weights: PathBuf,
    /// The constant's name (e.g. PREETHAM).
    #[arg(long)]
    pub name: String,
    /// The Rust file to write (atomically).
    #[arg(long, value_name = "FILE")]
    pub out: PathBuf,
    /// What to write: the f32 weights (`NeuralWeights`, for `NeuralSky`) or the weights
    /// quantised to Q7.24 (`FixedNeuralWeights`, for `FixedNeuralSky` on parts without an FPU).
    #[arg(long, value_enum, default_value_t = ExportFormat::F32)]
    pub format: ExportFormat,
}

/// `export --format`.
#[derive(Clone, Copy, ValueEnum)]
pub enum ExportFormat {
    /// `NeuralWeights<12>` in f32.
    F32,
    /// `FixedNeuralWeights<12>` in Q7.24.
    Fixed,
}

/// Writes the Rust source of `--weights` to `--out`.
///
/// # Errors
/// An unreadable weight file, weights that do not fit Q7.24, a failed write.
pub fn run(args: &ExportArgs, output: &mut dyn Write) -> Result<()> {
    let weights = export::read_weights::<12>(&args.weights)?;
    let text = match args.format {
        ExportFormat::F32 => export::pretrained_source(&weights, &args.name, &args.weights),
        ExportFormat::Fixed => {
            export::pretrained_fixed_source(&weights, &args.name, &args.weights)?
        }
    };
    image_io::write_text(&args.out, &text)?;
    writeln!(output, "wrote {}", args.out.display())?;
    Ok(())
}
