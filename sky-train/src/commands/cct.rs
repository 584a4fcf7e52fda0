//! `sky-train cct`: correlated colour temperature and Duv of chromaticities read from stdin.

use std::io::{BufRead, BufWriter, Write};

use anyhow::Result;

/// Reads `x,y` lines from `input` and writes `x,y,cct_k,duv` to `output`
/// ([`crate::controller::cct_lines`]).
///
/// # Errors
/// A bad line (named by its number), a failed write.
pub fn run(input: &mut dyn BufRead, output: &mut dyn Write) -> Result<()> {
    let mut out = BufWriter::new(output);
    crate::controller::cct_lines(input, &mut out)?;
    out.flush()?;
    Ok(())
}
