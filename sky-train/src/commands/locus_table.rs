//! `sky-train locus-table`: the Planckian locus as sky-core's table of cubic pieces
//! (`sky-core/src/cct/locus.rs`), from [`crate::planckian::locus_table_source`].

use std::io::Write;
use std::path::PathBuf;

use anyhow::Result;
use clap::Args;

use crate::{image_io, planckian};

/// `locus-table`'s arguments.
#[derive(Args)]
pub struct LocusTableArgs {
    /// The Rust file to write (atomically): sky-core's is `sky-core/src/cct/locus.rs`.
    #[arg(long, value_name = "FILE")]
    out: PathBuf,
}

/// Writes the table's Rust source to `--out`.
///
/// # Errors
/// An `--out` that cannot be written (a [`crate::args::ParamError`]), a failed write.
pub fn run(args: &LocusTableArgs, output: &mut dyn Write) -> Result<()> {
    crate::output_path::file("--out", &args.out, crate::output_path::Folder::Existing)?;
    image_io::write_text(&args.out, &planckian::locus_table_source())?;
    super::report_written(output, &args.out);
    Ok(())
}
