//! The training commands as docs/training.md and the README run them (`train`, `eval`,
//! `export`, `showcase`), in-process with small budgets: each finishes, reports what the pages
//! say it reports, and writes files that read back.

use clap::Parser;
use sky_train::cli::{self, Cli};

fn run(args: &[&str]) -> String {
    let cli = Cli::try_parse_from(std::iter::once("sky-train").chain(args.iter().copied()))
        .expect("valid arguments");
    let mut out = Vec::new();
    cli::execute(cli.command, &mut std::io::empty(), &mut out).expect("the command runs");
    String::from_utf8(out).expect("UTF-8 output")
}

#[test]
fn train_eval_export() {
    let dir = tempfile::tempdir().expect("temp dir");
    let weights = dir.path().join("preetham.skyn");
    let w = weights.to_str().expect("UTF-8 path");
    let d = dir.path().to_str().expect("UTF-8 path");
    let trained = run(&[
        "train",
        "--model",
        "preetham",
        "--max-iterations",
        "3",
        "--sun-zeniths",
        "3",
        "--views",
        "4x4",
        "--out",
        w,
    ]);
    assert!(
        trained.contains("test NRMSE (seed 000 protocol)"),
        "{trained}"
    );
    let read = sky_train::export::read_weights::<12>(&weights).expect("a valid weight file");
    assert_eq!(read.source_name(), "preetham");

    let report = run(&["eval", "--model", "neural", "--weights", w, "--out", d]);
    assert!(report.contains("Table 1: mean NRMSE"), "{report}");
    let figure = dir
        .path()
        .join("fig6_preetham_reference_network_difference.png");
    assert!(std::fs::metadata(&figure).expect("the figure").len() > 1000);

    let rust = dir.path().join("preetham.rs");
    run(&[
        "export",
        "--weights",
        w,
        "--name",
        "PREETHAM",
        "--out",
        rust.to_str().expect("UTF-8"),
    ]);
    let text = std::fs::read_to_string(&rust).expect("the Rust file");
    assert!(
        text.contains("PREETHAM") && text.contains("NeuralWeights"),
        "{text}"
    );
}

#[test]
fn showcase_writes_the_gallery_weights_and_figure() {
    let dir = tempfile::tempdir().expect("temp dir");
    let d = dir.path().to_str().expect("UTF-8 path");
    let out = run(&["showcase", "--out", d, "--seconds", "1"]);
    assert!(out.contains("seed 000 Table 1 NRMSE 0.0145"), "{out}");
    for file in [
        "preetham_sheet.png",
        "aoas_presets.png",
        "neural-preetham.skyn",
        "fig6_preetham_reference_network_difference.png",
    ] {
        assert!(dir.path().join(file).is_file(), "{file} missing: {out}");
    }
    sky_train::export::read_weights::<12>(&dir.path().join("neural-preetham.skyn"))
        .expect("a valid weight file");

    // A one-second run cannot beat the paper; the shipped weights' column beside it, labelled,
    // must. The paper's figures are seed 000's Tables 1-2 (0.0145 NRMSE, 0.257 % irradiance).
    let header = out
        .lines()
        .find(|l| l.contains("paper") && l.contains("this run"))
        .unwrap_or_else(|| panic!("no table header: {out}"));
    let columns: Vec<&str> = header.split_whitespace().collect();
    assert_eq!(columns, ["paper", "this", "run", "shipped"], "{header}");
    for (table, paper) in [("Table 1:", 0.0145), ("Table 2:", 0.00257)] {
        let row = out
            .lines()
            .find(|l| l.starts_with(table))
            .unwrap_or_else(|| panic!("no {table} row: {out}"));
        let figures: Vec<f64> = row
            .split_whitespace()
            .rev()
            .take(3)
            .map(|v| v.parse().expect("a figure"))
            .collect();
        let (shipped, paper_column) = (figures[0], figures[2]);
        assert!((paper_column - paper).abs() < 1e-9, "{row}");
        assert!(
            shipped < paper,
            "{table} shipped {shipped} not below the paper's {paper}"
        );
    }
    assert!(out.contains("shipped: sky-core's PREETHAM"), "{out}");
}
