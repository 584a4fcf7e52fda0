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
    /// Sample the physical atmosphere into --data and --site-data first (one precomputed
    /// atmosphere per optical depth 0.05, 0.1, 0.2, 0.4, 0.8 at sea level and at 3,000 m, one
    /// at 400 DU of ozone, and four held-out atmospheres for the tests; about a minute each on
    /// first use, then cached).
    #[arg(long)]
    sample: bool,
    /// Sample only the site's axes into --site-data (with --sample: --data is left as it is).
    #[arg(long, requires = "sample")]
    site_only: bool,
    /// The sampled reference (CSV): written by --sample, read to make the tables.
    #[arg(long, value_name = "FILE.csv", default_value = tables::DATA_PATH)]
    data: PathBuf,
    /// The sampled reference at other pressures and ozone columns (CSV): written by --sample,
    /// read to make the pressure and ozone sensitivities.
    #[arg(long, value_name = "FILE.csv", default_value = tables::SITE_DATA_PATH)]
    site_data: PathBuf,
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
    check_output("--data", &args.data, "csv")?;
    check_output("--out", &args.out, "rs")?;
    if args.sample {
        // Both outputs are checked before the minutes of sampling.
        check_output("--site-data", &args.site_data, "csv")?;
        let dir = cache::CacheDir::new(args.cache_dir.as_deref());
        if !args.site_only {
            let samples = tables::sample(&dir, true)?;
            tables::write_samples(&args.data, &samples)?;
            writeln!(
                output,
                "wrote {} ({} samples)",
                args.data.display(),
                samples.len()
            )?;
        }
        let site = tables::sample_site(&dir, true)?;
        tables::write_site_samples(&args.site_data, &site)?;
        writeln!(
            output,
            "wrote {} ({} samples)",
            args.site_data.display(),
            site.len()
        )?;
    }
    let samples = tables::read_samples(&args.data)?;
    let site = tables::read_site_samples(&args.site_data)?;
    let source = tables::rust_source(&samples, &site, &tables::beam());
    write_atomically(&args.out, |f| Ok(f.write_all(source.as_bytes())?))?;
    super::report_written(output, &args.out);
    Ok(())
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
