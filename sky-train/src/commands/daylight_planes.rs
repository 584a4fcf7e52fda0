//! `sky-train daylight-planes`: sky-core's table of the sky's light on vertical planes from the
//! physical atmosphere ([`crate::daylight_planes`]): `--sample` reruns the slow step (the
//! reference at every optical depth, sun-elevation and azimuth node, into `--data`), then the
//! table is written from `--data`.

use std::io::Write;
use std::path::PathBuf;

use anyhow::Result;
use clap::Args;

use super::daylight_tables::{Steps, regenerate};
use crate::daylight_planes as planes;

/// `daylight-planes`' arguments.
#[derive(Args)]
pub struct DaylightPlanesArgs {
    /// Sample the physical atmosphere into --data first (one precomputed atmosphere per
    /// optical depth 0.05, 0.1, 0.2, 0.4, 0.8, cached, then about 45 ms per sun position).
    #[arg(long)]
    sample: bool,
    /// The sampled reference (CSV): written by --sample, read to make the table.
    #[arg(long, value_name = "FILE.csv", default_value = planes::DATA_PATH)]
    data: PathBuf,
    /// The Rust file to write (sky-core's `daylight/plane_tables.rs`).
    #[arg(long, value_name = "FILE.rs", default_value = planes::TABLES_PATH)]
    out: PathBuf,
    /// Folder of precomputed atmospheres (default $SKY_TRAIN_CACHE_DIR, else
    /// $XDG_CACHE_HOME/sky-train, else ~/.cache/sky-train).
    #[arg(long, value_name = "DIR")]
    cache_dir: Option<PathBuf>,
}

/// Samples (with `--sample`) and writes the table, reporting on `output`.
///
/// # Errors
/// Bad paths as a [`crate::args::ParamError`]; a data file that is not the sampled grid; a
/// failed write.
pub fn run(args: &DaylightPlanesArgs, output: &mut dyn Write) -> Result<()> {
    let steps = Steps {
        sample: planes::sample,
        write: planes::write_samples,
        read: planes::read_samples,
        source: planes::rust_source,
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
