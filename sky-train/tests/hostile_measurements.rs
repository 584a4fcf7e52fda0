//! Hostile measurements (issue 25 items 10 and 11, the measurement parts; issue 24 item 3):
//! each case a test named after it, run through the `sky-train` binary as a user would, under
//! a 1 GiB address-space limit (`prlimit --as`). The spawn and assertion helpers are those of
//! `hostile.rs`.

mod common;

use std::path::Path;

use common::{failure, path, sky_train, strs, succeeds};

/// Asserts that `args` fail with an exit status (not a signal) and one stderr line holding
/// every `needle` and none of `absent`; returns the status.
fn fails(args: &[&str], stdin: &str, needles: &[&str], absent: &[&str]) -> i32 {
    let (code, stderr) = failure(args, &sky_train(args, stdin), needles);
    for word in absent {
        assert!(!stderr.contains(word), "{args:?}: `{stderr}` has `{word}`");
    }
    code
}

/// `schedule --measurements` of `text` (written to a file in `dir`) at Boulder.
fn schedule_args(dir: &Path, name: &str, text: &str) -> Vec<String> {
    let file = dir.join(name);
    std::fs::write(&file, text).expect("write measurements");
    [
        "schedule",
        "--lat",
        "40.0",
        "--lon",
        "-105.25",
        "--measurements",
    ]
    .iter()
    .map(|s| (*s).to_owned())
    .chain([path(&file).to_owned()])
    .collect()
}

/// `sample --model perez` with the sun 30° from the zenith and `flags`, one view.
fn sample_perez(flags: &[&str]) -> Vec<String> {
    ["sample", "--model", "perez", "--sun-zenith", "30"]
        .iter()
        .chain(flags)
        .map(|s| (*s).to_owned())
        .collect()
}

/// The field `column` of every data row of a CSV output.
fn column<'a>(csv: &'a str, column: &str) -> Vec<&'a str> {
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().expect("header").split(',').collect();
    let i = header
        .iter()
        .position(|h| *h == column)
        .unwrap_or_else(|| panic!("no {column} in {header:?}"));
    lines.map(|l| l.split(',').nth(i).expect("field")).collect()
}

/// Item 10: `sample --model perez` and `schedule` follow one rule for negative readings: a
/// thermal offset down to −20 W/m² (−2200 lx) is 0 in both, below it both refuse. Today's
/// binary: schedule refuses −5, sample takes −50 and −2000 lx.
#[test]
fn negative_readings_follow_one_rule_in_sample_and_schedule() {
    let dir = tempfile::tempdir().expect("tempdir");
    let a = schedule_args(
        dir.path(),
        "offset.csv",
        "utc,ghi_wm2\n2026-06-21T06:00:00Z,-5\n2026-06-21T18:00:00Z,420\n",
    );
    let out = succeeds(&strs(&a), "");
    let ghi: f64 = column(&out, "ghi_wm2")[0].parse().expect("a number");
    assert!(ghi == 0.0, "{out}");
    succeeds(&strs(&sample_perez(&["--ghi", "-5"])), "0,0\n");
    succeeds(&strs(&sample_perez(&["--global-lux", "-1"])), "0,0\n");
    for [flag, value, limit] in [
        ["--ghi", "-50", "-20 W/m²"],
        ["--global-lux", "-3000", "-2200 lx"],
    ] {
        let code = fails(
            &strs(&sample_perez(&[flag, value])),
            "0,0\n",
            &[flag, value, limit],
            &[],
        );
        assert_eq!(code, 2);
    }
    let a = schedule_args(
        dir.path(),
        "fault.csv",
        "utc,ghi_wm2\n2026-06-21T06:00:00Z,-50\n",
    );
    let code = fails(
        &strs(&a),
        "",
        &["fault.csv line 2", "ghi_wm2", "-50", "-20"],
        &[],
    );
    assert_eq!(code, 2);
}

/// Item 10: `--dhi -1` with a daylight `--ghi` is refused quoting −1, the value given (today's
/// binary quotes the clamped 0).
#[test]
fn a_refused_diffuse_is_quoted_as_given() {
    let code = fails(
        &strs(&sample_perez(&["--ghi", "800", "--dhi", "-1"])),
        "0,0\n",
        &["--dhi -1"],
        &["--dhi 0 "],
    );
    assert_eq!(code, 2);
}

/// Item 10: a diffuse of 0 with a global above 0 is used at night and at a thermal-offset
/// level (a shaded sensor's offset), documented in sky-core's `Measurement`; today's binary
/// refuses both.
#[test]
fn a_zero_diffuse_at_night_or_dawn_is_used() {
    let dir = tempfile::tempdir().expect("tempdir");
    let a = schedule_args(
        dir.path(),
        "night.csv",
        "utc,ghi_wm2,dhi_wm2\n2026-06-21T08:00:00Z,0.3,0\n2026-06-21T18:00:00Z,420,90\n",
    );
    let out = succeeds(&strs(&a), "");
    assert!(!out.contains("NaN") && !out.contains("inf"), "{out}");
    succeeds(&strs(&sample_perez(&["--ghi", "5", "--dhi", "0"])), "0,0\n");
}

/// Item 10: a column named twice is refused, naming it (today's binary takes one of them).
#[test]
fn a_duplicate_column_is_refused() {
    let dir = tempfile::tempdir().expect("tempdir");
    let a = schedule_args(
        dir.path(),
        "twice.csv",
        "utc,ghi_wm2,GHI_WM2\n2026-06-21T18:00:00Z,420,500\n",
    );
    let code = fails(&strs(&a), "", &["twice.csv line 1", "ghi_wm2 twice"], &[]);
    assert_eq!(code, 2);
}

/// Item 10: at night (the clear sky below 100 lx) the clear-sky index is left empty; today's
/// binary writes 1.6e8-like ratios of a sensor's noise over the twilight.
#[test]
fn the_clear_sky_index_is_empty_at_night() {
    let dir = tempfile::tempdir().expect("tempdir");
    // Boulder, 21 June: 08:00 UTC is 02:00 local (night), 18:00 UTC midday.
    let a = schedule_args(
        dir.path(),
        "night.csv",
        "utc,ghi_wm2,dhi_wm2\n2026-06-21T08:00:00Z,0.3,0.3\n2026-06-21T18:00:00Z,420,90\n",
    );
    let out = succeeds(&strs(&a), "");
    let index = column(&out, "clear_sky_index");
    assert_eq!(index[0], "", "{out}");
    let day: f64 = index[1].parse().expect("a number by day");
    assert!(day > 0.0 && day < 2.0, "{out}");
}

/// Item 11: a folder given as the measurement file is named as such, not as stdin.
#[test]
fn a_folder_of_measurements_is_named() {
    let dir = tempfile::tempdir().expect("tempdir");
    let code = fails(
        &[
            "schedule",
            "--lat",
            "40",
            "--lon",
            "-105",
            "--measurements",
            path(dir.path()),
        ],
        "",
        &[path(dir.path()), "is a folder"],
        &["stdin"],
    );
    assert_eq!(code, 2);
}

/// Item 11: `--ghi 1e-40` alone (below f32's normal range, counted as 0) is a black sky, not a
/// refused `--dhi` the user never gave.
#[test]
fn a_tiny_global_alone_does_not_blame_the_diffuse() {
    succeeds(&strs(&sample_perez(&["--ghi", "1e-40"])), "0,0\n");
}

/// Item 11: a reading refused by its range is named by the file's line number (5, after a
/// comment and a blank line), not by its data row (1).
#[test]
fn range_errors_name_the_file_line() {
    let dir = tempfile::tempdir().expect("tempdir");
    let a = schedule_args(
        dir.path(),
        "range.csv",
        "# station A\nutc,ghi_wm2\n\n2026-06-21T18:00:00Z,4000\n",
    );
    let code = fails(&strs(&a), "", &["range.csv line 4", "4000"], &["data row"]);
    assert_eq!(code, 2);
    let a = schedule_args(
        dir.path(),
        "range5.csv",
        "# station A\nutc,ghi_wm2\n\n2026-06-21T17:00:00Z,400\n2026-06-21T18:00:00Z,4000\n",
    );
    fails(&strs(&a), "", &["range5.csv line 5"], &["data row"]);
}

/// Item 11: `--time` at night names `--time` and the sun below the horizon, not a
/// `--sun-zenith` the user never gave.
#[test]
fn a_night_time_names_the_time() {
    let code = fails(
        &[
            "sample",
            "--model",
            "perez",
            "--ghi",
            "100",
            "--time",
            "2026-06-21T08:00:00Z",
            "--lat",
            "40",
            "--lon",
            "-105",
        ],
        "0,0\n",
        &["--time", "below the horizon"],
        &["--sun-zenith"],
    );
    assert_eq!(code, 2);
}

/// Item 11: a file of 70 MB of blank lines is named by the 64 MiB limit, not as empty.
#[test]
fn a_long_file_of_blank_lines_names_the_limit() {
    let dir = tempfile::tempdir().expect("tempdir");
    let file = dir.path().join("blank.csv");
    std::fs::write(&file, vec![b'\n'; 70_000_000]).expect("write");
    let code = fails(
        &[
            "schedule",
            "--lat",
            "40",
            "--lon",
            "-105",
            "--measurements",
            path(&file),
        ],
        "",
        &["blank.csv", "more than 64 MiB"],
        &["empty"],
    );
    assert_eq!(code, 2);
}
