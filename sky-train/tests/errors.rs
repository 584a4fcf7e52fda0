//! Bad arguments: a one-line error on stderr naming the argument and its valid range, a
//! non-zero exit status, and nothing written.

use std::process::{Command, Output};

fn sky_train(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_sky-train"))
        .args(args)
        .stdin(std::process::Stdio::null())
        .output()
        .expect("sky-train runs")
}

/// Asserts that `args` fail with status 2 and a single stderr line containing every `needle`.
fn fails(args: &[&str], needles: &[&str]) {
    let out = sky_train(args);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
    assert_eq!(stderr.trim_end().lines().count(), 1, "{args:?}: `{stderr}`");
    for needle in needles {
        assert!(
            stderr.contains(needle),
            "{args:?}: `{stderr}` lacks `{needle}`"
        );
    }
    assert!(out.stdout.is_empty(), "{args:?} wrote to stdout");
}

#[test]
fn bad_sky_parameters_name_the_argument_and_range() {
    fails(
        &["sample", "--sun-zenith", "30", "--turbidity", "7"],
        &["--turbidity", "7", "[2, 6]"],
    );
    fails(
        &["sample", "--sun-zenith", "30", "--turbidity", "nan"],
        &["--turbidity", "[2, 6]"],
    );
    fails(
        &["sample", "--sun-zenith", "95"],
        &["--sun-zenith", "95", "[0, 90]"],
    );
    fails(
        &["sample", "--sun-zenith", "-1"],
        &["--sun-zenith", "[0, 90]"],
    );
    fails(
        &["sample", "--sun-zenith", "inf"],
        &["--sun-zenith", "[0, 90]"],
    );
    fails(
        &["sample", "--sun-zenith", "30", "--sun-azimuth", "inf"],
        &["--sun-azimuth", "finite"],
    );
    fails(&["sample", "--sun-zenith", "abc"], &["--sun-zenith", "abc"]);
    fails(
        &[
            "sample",
            "--model",
            "sh",
            "--sun-zenith",
            "30",
            "--bands",
            "9",
        ],
        &["--bands", "9", "[1, 7]"],
    );
    fails(
        &[
            "sample",
            "--model",
            "sh",
            "--sun-zenith",
            "30",
            "--turbidity",
            "2.2",
        ],
        &["--turbidity", "2.2", "[2.5, 6]", "--model sh"],
    );
    fails(
        &["sample", "--model", "sh", "--sun-zenith", "91"],
        &["--sun-zenith", "[0, 90]"],
    );
    fails(&["sample"], &["--sun-zenith"]);
    fails(
        &["sample", "--sun-zenith", "10", "--model", "nope"],
        &["--model", "preetham"],
    );
}

#[test]
fn bad_image_arguments_name_the_argument_and_range() {
    let dir = tempfile::tempdir().expect("temp dir");
    let out = dir.path().join("x.exr");
    let out = out.to_str().expect("UTF-8 path");
    fails(
        &["render", "--sun-zenith", "30", "--width", "1", "--out", out],
        &["--width", "2..=16384"],
    );
    fails(
        &[
            "render",
            "--sun-zenith",
            "30",
            "--exposure",
            "99",
            "--out",
            out,
        ],
        &["--exposure", "[-30, 30]"],
    );
    fails(
        &[
            "render",
            "--sun-zenith",
            "30",
            "--turbidity",
            "1",
            "--out",
            out,
        ],
        &["--turbidity", "[2, 6]"],
    );
    assert_eq!(
        std::fs::read_dir(dir.path()).expect("dir").count(),
        0,
        "nothing written"
    );
}

#[test]
/// Bad input is exit status 2, like a bad argument (issue 19).
fn bad_sample_input_names_the_line() {
    let mut child = Command::new(env!("CARGO_BIN_EXE_sky-train"))
        .args(["sample", "--sun-zenith", "30"])
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("sky-train runs");
    {
        use std::io::Write;
        let mut stdin = child.stdin.take().expect("stdin");
        stdin
            .write_all(b"view_zenith_deg,view_azimuth_deg\n10,20\n30;40\n")
            .expect("write");
    }
    let out = child.wait_with_output().expect("wait");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("line 3"), "{stderr}");
    assert_eq!(stderr.trim_end().lines().count(), 1, "{stderr}");
}

#[test]
fn neural_model_errors_name_the_argument() {
    fails(
        &["sample", "--sun-zenith", "30", "--model", "neural"],
        &["--weights"],
    );
    fails(
        &["sample", "--sun-zenith", "30", "--weights", "x.skyn"],
        &["--weights", "--model neural"],
    );
    fails(
        &[
            "sample",
            "--sun-zenith",
            "30",
            "--model",
            "neural",
            "--weights",
            "/nonexistent.skyn",
        ],
        &["--weights", "/nonexistent.skyn"],
    );
    let dir = tempfile::tempdir().expect("temp dir");
    let bad = dir.path().join("bad.skyn");
    std::fs::write(&bad, b"SKYN\x01\x00\x06\x0c\x03").expect("write");
    let bad = bad.to_str().expect("UTF-8 path");
    fails(
        &[
            "sample",
            "--sun-zenith",
            "30",
            "--model",
            "neural",
            "--weights",
            bad,
        ],
        &["--weights", "truncated"],
    );
    fails(
        &[
            "sample",
            "--sun-zenith",
            "30",
            "--model",
            "neural-hosek",
            "--turbidity",
            "11",
        ],
        &["--turbidity", "[1, 10]"],
    );
    fails(
        &[
            "sample",
            "--sun-zenith",
            "30",
            "--model",
            "hosek",
            "--turbidity",
            "0.5",
        ],
        &["--turbidity", "[1, 10]"],
    );
}

#[test]
fn bad_aoas_arguments_name_the_argument_and_range() {
    fails(
        &["sample", "--model", "aoas", "--style", "mauve"],
        &["--style", "mauve", "physical", "coral", ".toml"],
    );
    fails(
        &["sample", "--model", "aoas", "--turbidity", "3"],
        &["--turbidity", "--model preetham"],
    );
    fails(
        &[
            "sample",
            "--model",
            "preetham",
            "--sun-zenith",
            "30",
            "--style",
            "coral",
        ],
        &["--style", "--model aoas"],
    );
    fails(
        &["sample", "--model", "aoas", "--sun-zenith", "95"],
        &["--sun-zenith", "95", "[0, 90]", "aoas"],
    );
    fails(
        &["sample", "--model", "aoas", "--sun-azimuth", "10"],
        &["--sun-azimuth", "--sun-zenith"],
    );
    let dir = tempfile::tempdir().expect("temp dir");
    let style = dir.path().join("blurry.toml");
    std::fs::write(
        &style,
        "preset = \"coral\"\n[ambiguity]\nneighbourhood = 0.7\n",
    )
    .expect("write");
    let style = style.to_str().expect("UTF-8 path");
    fails(
        &["sample", "--model", "aoas", "--style", style],
        &[
            "--style",
            "blurry.toml",
            "ambiguity.neighbourhood = 0.7",
            "[0, 0.5]",
        ],
    );
    let typo = dir.path().join("typo.toml");
    std::fs::write(&typo, "[sky_hue]\nred = 1\ngreen = 2\nblu = 3\n").expect("write");
    fails(
        &[
            "sample",
            "--model",
            "aoas",
            "--style",
            typo.to_str().expect("UTF-8 path"),
        ],
        &["--style", "typo.toml", "line 4", "blu"],
    );
    let missing = dir.path().join("missing.toml");
    fails(
        &[
            "sample",
            "--model",
            "aoas",
            "--style",
            missing.to_str().expect("UTF-8 path"),
        ],
        &["--style", "missing.toml", "cannot read"],
    );
    let out = dir.path().join("x.png");
    fails(
        &[
            "render",
            "--model",
            "aoas",
            "--style",
            "heart",
            "--sun-zenith",
            "91",
            "--out",
            out.to_str().expect("UTF-8 path"),
        ],
        &["--sun-zenith", "[0, 90]"],
    );
    assert!(!out.exists(), "nothing written");
}

/// `bench` runs and prints each evaluator's line with its ratio to a peer (on a small grid: the
/// figures are docs/performance.md's, from the full grid on a quiet machine).
#[test]
fn bench_prints_every_evaluator_with_a_ratio() {
    let out = sky_train(&["bench", "--width", "16", "--height", "8", "--runs", "1"]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    for name in [
        "preetham",
        "neural 6-12-3 rgb_batch",
        "daylight rgb_batch",
        "aoas",
        "cct_duv",
    ] {
        let line = stdout
            .lines()
            .find(|l| l.contains(name))
            .unwrap_or_else(|| panic!("no `{name}` line in\n{stdout}"));
        assert!(line.contains("ns/") && line.contains("x vs "), "{line}");
    }
}
