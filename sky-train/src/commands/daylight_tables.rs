//! `sky-train daylight-tables`: sky-core's daylight tables from the physical atmosphere
//! ([`crate::daylight_tables`]): `--sample` reruns the slow step (the reference at every
//! optical depth and sun-angle node, into `--data`), then the tables are written from `--data`.

use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::Result;
use clap::Args;

use crate::args::check_output;
use crate::daylight_tables as tables;
use crate::image_io::write_atomically;
use crate::physical::cache;

/// `daylight-tables`' arguments.
#[derive(Args)]
pub struct DaylightTablesArgs {
    /// Sample the physical atmosphere into --data first (one precomputed atmosphere per
    /// optical depth 0.05, 0.1, 0.2, 0.4, 0.8; about a minute each on first use, then cached).
    #[arg(long)]
    sample: bool,
    /// The sampled reference (CSV): written by --sample, read to make the tables.
    #[arg(long, value_name = "FILE.csv", default_value = tables::DATA_PATH)]
    data: PathBuf,
    /// The Rust file to write (sky-core's `daylight/tables.rs`).
    #[arg(long, value_name = "FILE.rs", default_value = tables::TABLES_PATH)]
    out: PathBuf,
    /// Folder of precomputed atmospheres (default $SKY_TRAIN_CACHE_DIR, else
    /// $XDG_CACHE_HOME/sky-train, else ~/.cache/sky-train).
    #[arg(long, value_name = "DIR")]
    cache_dir: Option<PathBuf>,
}

/// Samples (with `--sample`) and writes the tables, reporting on `output`.
///
/// # Errors
/// Bad paths as a [`crate::args::ParamError`]; a data file that is not the sampled grid; a failed write.
pub fn run(args: &DaylightTablesArgs, output: &mut dyn Write) -> Result<()> {
    let steps = Steps {
        sample: tables::sample,
        write: tables::write_samples,
        read: tables::read_samples,
        source: |samples| tables::rust_source(samples, &tables::beam()),
    };
    let paths = (args.data.as_path(), args.out.as_path());
    regenerate(
        &steps,
        args.sample,
        paths,
        args.cache_dir.as_deref(),
        output,
    )
}

/// The two steps of a table distilled from the reference ([`crate::sampled_grid`]).
pub(super) struct Steps<S> {
    /// The slow step: the reference over the grid.
    pub(super) sample: fn(&cache::CacheDir, bool) -> Result<Vec<S>>,
    /// The samples' file.
    pub(super) write: fn(&Path, &[S]) -> Result<()>,
    /// The samples from their file, checked.
    pub(super) read: fn(&Path) -> Result<Vec<S>>,
    /// The Rust source of the table.
    pub(super) source: fn(&[S]) -> String,
}

/// With `sample`, samples the reference into `data` (atmospheres cached in `cache_dir`), then
/// writes the table from `data` to `out`, reporting on `output`.
pub(super) fn regenerate<S>(
    steps: &Steps<S>,
    sample: bool,
    (data, out): (&Path, &Path),
    cache_dir: Option<&Path>,
    output: &mut dyn Write,
) -> Result<()> {
    check_output("--data", data, "csv")?;
    check_output("--out", out, "rs")?;
    if sample {
        let dir = cache::CacheDir::new(cache_dir);
        let samples = (steps.sample)(&dir, true)?;
        (steps.write)(data, &samples)?;
        writeln!(
            output,
            "wrote {} ({} samples)",
            data.display(),
            samples.len()
        )?;
    }
    let samples = (steps.read)(data)?;
    let source = (steps.source)(&samples);
    write_atomically(out, |f| Ok(f.write_all(source.as_bytes())?))?;
    super::report_written(output, out);
    Ok(())
}
