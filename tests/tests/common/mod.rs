//! Helpers shared by the integration tests (`mod common;` in each test file that needs them).

use clap::Parser;
use sky_train::cli::{self, Cli};

/// Runs a `sky-train` command line in-process (the binary is a thin wrapper over
/// `sky_train::cli::execute`) with `input` on stdin and returns stdout.
pub(crate) fn run(args: &[&str], input: &str) -> String {
    let cli = Cli::try_parse_from(std::iter::once("sky-train").chain(args.iter().copied()))
        .unwrap_or_else(|e| panic!("{args:?}: {e}"));
    let mut output = Vec::new();
    cli::execute(cli.command, &mut input.as_bytes(), &mut output)
        .unwrap_or_else(|e| panic!("{args:?}: {e:#}"));
    String::from_utf8(output).expect("UTF-8 output")
}
