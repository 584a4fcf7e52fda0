//! Helpers shared by the integration tests (`mod common;` in each test file that needs them).

use clap::Parser;
use proptest::test_runner::{Config as ProptestConfig, FileFailurePersistence};
use sky_train::cli::{self, Cli};

/// Proptest configuration: `cases` per property; failing cases are saved beside the test file.
#[allow(dead_code)] // not every test file that shares `common` has properties
pub(crate) fn proptest_config(cases: u32) -> ProptestConfig {
    ProptestConfig {
        cases,
        failure_persistence: Some(Box::new(FileFailurePersistence::WithSource(
            "proptest-regressions",
        ))),
        ..ProptestConfig::default()
    }
}

/// Runs a `sky-train` command line in-process (the binary is a thin wrapper over
/// `sky_train::cli::execute`) with `input` on stdin and returns stdout.
#[allow(dead_code)] // not every test file that shares `common` runs the CLI
pub(crate) fn run(args: &[&str], input: &str) -> String {
    let cli = Cli::try_parse_from(std::iter::once("sky-train").chain(args.iter().copied()))
        .unwrap_or_else(|e| panic!("{args:?}: {e}"));
    let mut output = Vec::new();
    cli::execute(cli.command, &mut input.as_bytes(), &mut output)
        .unwrap_or_else(|e| panic!("{args:?}: {e:#}"));
    String::from_utf8(output).expect("UTF-8 output")
}

/// `YYYY-MM-DDTHH:MM:SSZ` as sky-core's UTC time.
#[allow(dead_code)] // not every test file that shares `common` reads times
pub(crate) fn utc(s: &str) -> sky_core::solar::UtcTime {
    let n = |r: std::ops::Range<usize>| s[r].parse::<u32>().expect("digits");
    let year = i32::try_from(n(0..4)).expect("year");
    sky_core::solar::UtcTime::new(
        year,
        n(5..7),
        n(8..10),
        n(11..13),
        n(14..16),
        f64::from(n(17..19)),
    )
    .expect("valid time")
}
