//! Hostile input, round 3 (issue 25), the command-line half: each case a test named after it,
//! run through the `sky-train` binary as a user would, under the 1 GiB address-space limit of
//! `hostile.rs` (its helpers are copied here).

mod common;

use std::io::{BufRead, BufReader, Read, Write};
use std::process::Stdio;

use common::{command, fails, path, sky_train, succeeds};

/// Asserts `args` fail as bad input (exit status 2), naming every `needle`; returns stderr.
fn refused(args: &[&str], stdin: &str, needles: &[&str]) {
    assert_eq!(fails(args, stdin, needles), 2, "{args:?}");
}

/// The CSV rows of `text` after its header, split into fields.
fn rows(text: &str) -> Vec<Vec<String>> {
    text.lines()
        .skip(1)
        .map(|l| l.split(',').map(str::to_owned).collect())
        .collect()
}

// ---- item 3: the CIE sky's level -------------------------------------------------------

const CIE: [&str; 7] = [
    "--model",
    "cie",
    "--cie-type",
    "12",
    "--sun-zenith",
    "60",
    "--sun-azimuth",
];

/// Issue 25 item 3: `--zenith-luminance 3e38` and `--diffuse-lux 3e38` gave R, G, B NaN with
/// exit 0 (and an EXR of NaN and inf pixels); they are refused, naming the flag, the value as
/// given and the range; at the largest levels allowed every value is finite.
#[test]
fn cie_sky_levels_that_overflow_are_refused() {
    let dir = tempfile::tempdir().expect("temp dir");
    let exr = dir.path().join("sky.exr");
    for (flag, value, range) in [
        ("--zenith-luminance", "3e38", "[0, 1e10]"),
        ("--diffuse-lux", "3e38", "[0, 1e9]"),
        ("--diffuse-lux", "1e39", "[0, 1e9]"),
        ("--zenith-luminance", "1.1e10", "[0, 1e10]"),
    ] {
        let mut args: Vec<&str> = vec!["sample"];
        args.extend(CIE);
        args.extend(["0", flag, value]);
        refused(&args, "0,0\n", &[flag, value, range]);
        let mut render: Vec<&str> = vec!["render"];
        render.extend(CIE);
        render.extend(["0", flag, value, "--width", "64", "--out", path(&exr)]);
        refused(&render, "", &[flag, value]);
        assert!(!exr.exists());
    }
    // The largest levels: a render's every pixel and every sampled value finite, and the
    // horizon (view zenith 90) and the circumsolar peak included.
    for (flag, value) in [("--zenith-luminance", "1e10"), ("--diffuse-lux", "1e9")] {
        let mut args: Vec<&str> = vec!["sample"];
        args.extend(CIE);
        args.extend(["0", flag, value]);
        let out = succeeds(&args, "0,0\n60,0\n90,0\n90,180\n45,90\n");
        for row in rows(&out) {
            for v in &row[2..] {
                let v: f64 = v
                    .parse()
                    .unwrap_or_else(|_| panic!("{flag} {value}: `{v}`"));
                assert!(v.is_finite() && v >= 0.0, "{flag} {value}: {row:?}");
            }
        }
        let mut render: Vec<&str> = vec!["render"];
        render.extend(CIE);
        render.extend(["0", flag, value, "--width", "128", "--out", path(&exr)]);
        succeeds(&render, "");
        let img = sky_train::image_io::read_exr(&exr).expect("EXR");
        let bad = img.pixels.iter().filter(|p| !p.is_finite()).count();
        assert_eq!(bad, 0, "{flag} {value}: {bad} pixels not finite");
        assert!(
            img.pixels.iter().any(|p| p.max_element() > 1e8),
            "{flag} {value}"
        );
    }
}

// ---- item 7: stdout closed or full -----------------------------------------------------

/// Runs `args` with `stdin` fed from a thread, reads one line of stdout and closes it;
/// returns the exit status and stderr.
fn read_one_line_then_close(args: &[&str], stdin: String) -> (std::process::ExitStatus, String) {
    let mut child = command(args, Stdio::piped()).spawn().expect("runs");
    let mut input = child.stdin.take().expect("stdin");
    let feeder = std::thread::spawn(move || {
        // Ends with a broken pipe when the command stops reading: that is expected.
        let _ = input.write_all(stdin.as_bytes());
    });
    let mut stdout = BufReader::new(child.stdout.take().expect("stdout"));
    let mut line = String::new();
    stdout.read_line(&mut line).expect("one line");
    assert!(!line.is_empty(), "{args:?}: no output");
    drop(stdout);
    let mut stderr = String::new();
    child
        .stderr
        .take()
        .expect("stderr")
        .read_to_string(&mut stderr)
        .expect("stderr");
    let status = child.wait().expect("ends");
    feeder.join().expect("feeder");
    (status, stderr)
}

/// The four commands of issue 25 item 7, each with more output than a pipe holds (64 KiB).
fn long_outputs() -> Vec<(Vec<&'static str>, String)> {
    let directions: String = (0..20_000)
        .map(|k| format!("{},{}\n", k % 90, k % 360))
        .collect();
    let chromaticities: String = (0..20_000)
        .map(|k| format!("0.{},0.33\n", 30 + k % 10))
        .collect();
    vec![
        (
            vec![
                "daylight",
                "--model",
                "preetham",
                "--elevations",
                "-18:90:0.011",
            ],
            String::new(),
        ),
        (
            vec![
                "schedule",
                "--lat",
                "48.2",
                "--lon",
                "16.4",
                "--date",
                "2026-06-21",
                "--step",
                "1",
            ],
            String::new(),
        ),
        (
            vec!["sample", "--model", "preetham", "--sun-zenith", "30"],
            directions,
        ),
        (vec!["cct"], chromaticities),
    ]
}

/// Issue 25 item 7: `sky-train daylight … | head -1` said "error: Broken pipe (os error 32)"
/// and exited 1 (daylight, schedule, sample, cct). A reader that goes away ends the program
/// quietly with status 0, ripgrep's convention (coreutils die of SIGPIPE instead, status 141
/// in a shell; both are silent).
#[test]
fn a_closed_stdout_ends_quietly() {
    for (args, stdin) in long_outputs() {
        let (status, stderr) = read_one_line_then_close(&args, stdin);
        assert_eq!(status.code(), Some(0), "{args:?}: {status:?} `{stderr}`");
        assert!(stderr.is_empty(), "{args:?}: `{stderr}`");
    }
}

/// Issue 25 item 7: a full stdout (/dev/full: ENOSPC) is named as stdout's, exit status 1.
#[test]
fn a_full_stdout_is_named() {
    for (args, stdin) in long_outputs() {
        let full = std::fs::OpenOptions::new()
            .write(true)
            .open("/dev/full")
            .expect("/dev/full");
        let mut child = command(&args, Stdio::from(full)).spawn().expect("runs");
        let mut input = child.stdin.take().expect("stdin");
        let feeder = std::thread::spawn(move || {
            let _ = input.write_all(stdin.as_bytes());
        });
        let out = child.wait_with_output().expect("ends");
        feeder.join().expect("feeder");
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{args:?}: `{stderr}`");
        assert!(
            stderr.contains("stdout") && stderr.contains("No space left on device"),
            "{args:?}: `{stderr}`"
        );
        assert_eq!(stderr.trim_end().lines().count(), 1, "{args:?}: `{stderr}`");
    }
}

/// Issue 25 item 7: `locus-table` exited 1 after writing its file because printing "wrote …"
/// failed: with stdout full or closed it writes the file and exits 0.
#[test]
fn locus_table_succeeds_when_only_its_report_fails() {
    let dir = tempfile::tempdir().expect("temp dir");
    let reference = dir.path().join("reference.rs");
    succeeds(&["locus-table", "--out", path(&reference)], "");
    let table = std::fs::read(&reference).expect("table");
    assert!(table.len() > 1000);
    // stdout full.
    let out_full = dir.path().join("full.rs");
    let full = std::fs::OpenOptions::new()
        .write(true)
        .open("/dev/full")
        .expect("/dev/full");
    let out = command(
        &["locus-table", "--out", path(&out_full)],
        Stdio::from(full),
    )
    .output()
    .expect("runs");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "`{stderr}`");
    assert!(
        stderr.contains("wrote") && stderr.contains("stdout"),
        "`{stderr}`"
    );
    assert_eq!(std::fs::read(&out_full).expect("written"), table);
    // stdout closed before the command writes: a pipe whose reader is gone.
    let out_closed = dir.path().join("closed.rs");
    let mut child = command(&["locus-table", "--out", path(&out_closed)], Stdio::piped())
        .spawn()
        .expect("runs");
    drop(child.stdout.take());
    let status = child.wait().expect("ends");
    assert_eq!(status.code(), Some(0));
    assert_eq!(std::fs::read(&out_closed).expect("written"), table);
}

// ---- item 8: charts --------------------------------------------------------------------

/// Issue 25 item 8: `--elevations -18:-17:1 --plot-cct` drew a reversed axis with the data
/// outside it, `5:5:1 --plot-illuminance` an empty chart, and both charts to one path the
/// second over the first, all with exit 0. Each is refused before any work, naming the flag.
#[test]
fn charts_that_would_be_wrong_are_refused() {
    let dir = tempfile::tempdir().expect("temp dir");
    let png = dir.path().join("a.png");
    let other = dir.path().join("./a.png");
    for (elevations, flag, file, needles) in [
        ("-18:-17:1", "--plot-cct", &png, vec!["--plot-cct", "-8"]),
        ("-18:-8.5:0.5", "--plot-cct", &png, vec!["--plot-cct", "-8"]),
        (
            "5:5:1",
            "--plot-illuminance",
            &png,
            vec!["--plot-illuminance", "two"],
        ),
        ("5:5:1", "--plot-cct", &png, vec!["--plot-cct", "two"]),
        ("0:10:1", "--plot-cct", &png, vec![]),
    ] {
        let mut args = vec!["daylight", "--elevations", elevations, flag, path(file)];
        if needles.is_empty() {
            // Both charts to one file, written as two paths.
            args.extend(["--plot-illuminance", path(&other)]);
            refused(&args, "", &["--plot-illuminance", "--plot-cct", "same"]);
        } else {
            refused(&args, "", &needles);
        }
        assert!(!png.exists());
    }
}

/// Issue 25 item 8: a 10:11:0.5 axis was labelled "10 10 10 … 11" (every tick to 0
/// decimals). The labels of a chart's ticks (those plotters places on 10..11 at tenths, on
/// -18..90 at tens) are each their own value. Tests the labelling function the charts use.
#[test]
fn chart_ticks_are_labelled_with_their_values() {
    use sky_train::commands::daylight_plot::tick_label;
    let tenths: Vec<String> = (0..=10)
        .map(|k| tick_label(10.0 + f64::from(k) * 0.1))
        .collect();
    assert_eq!(
        tenths,
        [
            "10", "10.1", "10.2", "10.3", "10.4", "10.5", "10.6", "10.7", "10.8", "10.9", "11"
        ]
    );
    let tens: Vec<String> = (-1..=9).map(|k| tick_label(f64::from(k) * 10.0)).collect();
    assert_eq!(
        tens,
        [
            "-10", "0", "10", "20", "30", "40", "50", "60", "70", "80", "90"
        ]
    );
    assert_eq!(tick_label(-0.0), "0");
    assert_eq!(tick_label(-17.25), "-17.25");
}

// ---- item 9: flags that would be ignored -----------------------------------------------

/// Issue 25 item 9: `fit-aod --cache-dir /nonexistent/x` started minutes of work (fit-aod
/// caches nothing: the flag was ignored); `export --format glsl --group 3`, `--format js
/// --model cie` and `--name` were dropped without a word. Each is refused, naming the flag.
#[test]
fn flags_that_do_not_apply_are_refused() {
    let started = std::time::Instant::now();
    refused(
        &["fit-aod", "--cache-dir", "/nonexistent/x"],
        "",
        &["--cache-dir", "fit-aod"],
    );
    assert!(started.elapsed().as_secs() < 10, "{:?}", started.elapsed());
    let dir = tempfile::tempdir().expect("temp dir");
    let out = dir.path().join("shader.txt");
    let o = path(&out);
    for (args, flag) in [
        (vec!["--format", "glsl", "--group", "3"], "--group"),
        (vec!["--format", "glsl", "--binding", "1"], "--binding"),
        (
            vec![
                "--format",
                "wgsl",
                "--constants",
                "--sun-zenith",
                "30",
                "--group",
                "3",
            ],
            "--group",
        ),
        (vec!["--format", "js", "--model", "cie"], "--model"),
        (vec!["--format", "js", "--group", "3"], "--group"),
        (vec!["--format", "js", "--name", "SKY"], "--name"),
        (vec!["--format", "glsl", "--name", "SKY"], "--name"),
        (vec!["--format", "wgsl", "--name", "SKY"], "--name"),
        (vec!["--format", "js", "--constants"], "--constants"),
        (vec!["--format", "js", "--sun-zenith", "30"], "--sun-zenith"),
    ] {
        let mut a = vec!["export", "--out", o];
        a.extend(&args);
        refused(&a, "", &[flag]);
        assert!(!out.exists(), "{args:?}");
    }
    // What does apply still works: --group and --binding of a WGSL uniform array.
    succeeds(
        &[
            "export",
            "--out",
            o,
            "--format",
            "wgsl",
            "--group",
            "3",
            "--binding",
            "5",
        ],
        "",
    );
    let wgsl = std::fs::read_to_string(&out).expect("shader");
    assert!(
        wgsl.contains("@group(3)") && wgsl.contains("@binding(5)"),
        "{wgsl}"
    );
}

// ---- item 10 (parts): the horizon, CCT far from the locus ------------------------------

/// Issue 25 item 10: view zenith exactly 90 gave Y = 0 although the model is finite at the
/// horizon (the CIE and Perez skies: f32 cos(π/2) is −4.4e-8, "below the horizon"). At 90
/// the luminance is the horizon's: within 0.1 % of 89.999's, and not 0; at 90.01 it is 0.
#[test]
fn view_zenith_90_is_the_horizon() {
    for sky in [
        vec!["--model", "cie", "--cie-type", "12", "--sun-zenith", "60"],
        vec!["--model", "cie", "--cie-type", "1", "--sun-zenith", "30"],
        vec![
            "--model",
            "perez",
            "--sun-zenith",
            "50",
            "--ghi",
            "500",
            "--dhi",
            "200",
        ],
    ] {
        let mut args = vec!["sample"];
        args.extend(&sky);
        let out = succeeds(&args, "89.999,30\n90,30\n90.01,30\n");
        let y: Vec<f64> = rows(&out)
            .iter()
            .map(|r| r[2].parse().expect("Y"))
            .collect();
        assert!(y[0] > 0.0 && y[1] > 0.0, "{sky:?}: {y:?}");
        assert!((y[1] / y[0] - 1.0).abs() < 1e-3, "{sky:?}: {y:?}");
        assert_eq!(y[2], 0.0, "{sky:?}: {y:?}");
    }
}

/// Issue 25 item 10: `cct` gave CCTs for chromaticities far off the Planckian locus ((0.6,
/// 0.6) → 2,428 K; (1, 1) → 1,896 K) where `daylight` leaves |Duv| > 0.05 empty. One rule
/// now: empty beyond 0.05. Reference: D65's chromaticity (0.31272, 0.32903) has CCT 6504 K
/// (CIE 015:2018, Table T.3; the nominal 6500 K scaled by the revised c2, 1.4388/1.4380) and
/// Duv +0.0032 (ANSI C78.377's sign: above the locus).
#[test]
fn cct_is_empty_far_from_the_planckian_locus() {
    let out = succeeds(&["cct"], "x,y\n0.6,0.6\n1,1\n0.31272,0.32903\n");
    let r = rows(&out);
    for far in [&r[0], &r[1]] {
        assert_eq!(far[2..], ["", ""], "{far:?}");
    }
    let d65: f64 = r[2][2].parse().expect("D65 CCT");
    let duv: f64 = r[2][3].parse().expect("D65 Duv");
    assert!((d65 - 6504.0).abs() < 5.0, "{d65}");
    assert!((duv - 0.0032).abs() < 3e-4, "{duv}");
    // The help says the rule.
    let help = succeeds(&["cct", "--help"], "");
    assert!(help.contains("0.05"), "{help}");
}

// ---- item 11 (parts): messages ---------------------------------------------------------

/// The sun at local noon on the equator's date line, for `--time`.
const PLACE: [&str; 4] = ["--lat", "0", "--lon", "180"];

/// Issue 25 item 11: a leap second said "second = 60 is outside [0, 60]"; it is read as the
/// next day's first instant (POSIX time); a second of 61 names the range [0, 60); year 3000
/// said "expected RFC 3339" and names the supported years.
#[test]
fn time_messages_name_the_field_and_its_range() {
    let sample = |time: &str| {
        let mut a = vec!["sample", "--model", "preetham", "--time", time];
        a.extend(PLACE);
        a.iter().map(|s| (*s).to_owned()).collect::<Vec<String>>()
    };
    let run = |time: &str| {
        let a = sample(time);
        let a: Vec<&str> = a.iter().map(String::as_str).collect();
        succeeds(&a, "0,0\n45,90\n")
    };
    assert_eq!(
        run("2016-12-31T23:59:60Z"),
        run("2017-01-01T00:00:00Z"),
        "the leap second is the next day's first instant"
    );
    assert_eq!(
        run("2016-12-31T22:59:60-01:00"),
        run("2017-01-01T00:00:00Z")
    );
    for (time, needles) in [
        (
            "2026-06-21T12:00:60Z",
            vec!["second = 60", "[0, 60)", "23:59:60"],
        ),
        ("2026-06-21T23:59:61Z", vec!["second = 61", "[0, 60)"]),
        ("3000-01-01T00:00:00Z", vec!["year = 3000", "2999"]),
    ] {
        let a = sample(time);
        let a: Vec<&str> = a.iter().map(String::as_str).collect();
        let out = sky_train(&a, "0,0\n");
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{time}: {stderr}");
        assert!(!stderr.contains("expected RFC 3339"), "{time}: {stderr}");
        for n in needles {
            assert!(stderr.contains(n), "{time}: `{stderr}` lacks `{n}`");
        }
    }
}

/// Issue 25 item 11: `--diffuse-lux 1e39` was echoed as "inf" with a 39-digit range, and
/// other values as 31 digits. Values and ranges are printed compactly, as the user typed them.
#[test]
fn values_and_ranges_are_printed_compactly() {
    for (args, needles) in [
        (
            vec![
                "sample",
                "--model",
                "preetham",
                "--sun-zenith",
                "40",
                "--turbidity",
                "1e30",
            ],
            vec!["--turbidity 1e30", "[2, 6]"],
        ),
        (
            vec![
                "daylight",
                "--model",
                "preetham",
                "--elevations",
                "0:1:1",
                "--turbidity",
                "1e30",
            ],
            vec!["--turbidity 1e30", "[2, 6]"],
        ),
        (
            vec![
                "sample",
                "--model",
                "cie",
                "--cie-type",
                "3",
                "--sun-zenith",
                "40",
                "--diffuse-lux",
                "1e39",
            ],
            vec!["1e39", "[0, 1e9]"],
        ),
    ] {
        let out = sky_train(&args, "0,0\n");
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(
            !stderr.contains("000000") && !stderr.contains("inf"),
            "{args:?}: {stderr}"
        );
        for n in needles {
            assert!(stderr.contains(n), "{args:?}: `{stderr}` lacks `{n}`");
        }
    }
}

/// The subcommands, from `sky-train --help` (and `captures`' own).
fn subcommands() -> Vec<Vec<String>> {
    let list = |args: &[&str]| -> Vec<String> {
        let help = succeeds(args, "");
        help.lines()
            .skip_while(|l| !l.starts_with("Commands:"))
            .skip(1)
            .take_while(|l| l.starts_with("  "))
            .filter_map(|l| l.split_whitespace().next().map(str::to_owned))
            .filter(|c| c != "help")
            .collect()
    };
    let mut out: Vec<Vec<String>> = vec![vec![]];
    for c in list(&["--help"]) {
        out.push(vec![c.clone()]);
        if c == "captures" {
            for s in list(&["captures", "--help"]) {
                out.push(vec![c.clone(), s]);
            }
        }
    }
    out
}

/// Issue 25 item 11: rustdoc's link syntax (`[`RECORD_AOD_550`]`) showed in `spectrum
/// --help`. No --help of any subcommand shows it (a `[` followed by a backtick, or `](`).
#[test]
fn no_help_shows_rustdoc_link_syntax() {
    let commands = subcommands();
    assert!(commands.len() > 20, "{commands:?}");
    for c in commands {
        let mut args: Vec<&str> = c.iter().map(String::as_str).collect();
        args.push("--help");
        let help = succeeds(&args, "");
        for l in help.lines() {
            assert!(
                !l.contains("[`") && !l.contains("`]") && !l.contains("](Self::"),
                "{args:?}: `{l}`"
            );
        }
    }
}

// ---- item 12: limits checked before the work -------------------------------------------

/// Issue 25 item 12: `gallery --width 2` (or 3) was accepted, then failed after writing 24
/// files. It is refused before anything is written; width 4 works.
#[test]
fn gallery_width_too_small_is_refused_before_writing() {
    let dir = tempfile::tempdir().expect("temp dir");
    for w in ["2", "3"] {
        let out = dir.path().join(format!("g{w}"));
        refused(
            &["gallery", "--out", path(&out), "--width", w],
            "",
            &["--width", "4"],
        );
        let written = std::fs::read_dir(&out).map_or(0, Iterator::count);
        assert_eq!(written, 0, "--width {w}: {written} files written");
    }
    let out = dir.path().join("g4");
    succeeds(&["gallery", "--out", path(&out), "--width", "4"], "");
    assert_eq!(std::fs::read_dir(&out).map_or(0, Iterator::count), 26);
}

/// Issue 25 item 12: `captures interpolate --step 1s` wrote 12,602 files for 8 captures. A
/// cap (--max-frames, default 1000) refuses it before anything is rendered, naming the flags
/// and how many frames it would write; raising the cap (or a longer step) is accepted.
#[test]
fn interpolate_refuses_more_frames_than_the_cap() {
    let dir = tempfile::tempdir().expect("temp dir");
    let caps = dir.path().join("caps");
    succeeds(
        &[
            "captures",
            "synthesize",
            "--out",
            path(&caps),
            "--width",
            "64",
            "--frames",
            "8",
            "--start",
            "08:00",
        ],
        "",
    );
    // Weights trained on them (briefly: only their file matters here).
    let weights = dir.path().join("sky.weights");
    succeeds(
        &[
            "captures",
            "train",
            "--input",
            path(&caps),
            "--no-cross-validation",
            "--max-iterations",
            "2",
            "--samples",
            "64",
            "--out",
            path(&weights),
        ],
        "",
    );
    let out = dir.path().join("frames");
    let args = |step: &'static str, cap: Option<&'static str>| {
        let mut a = vec![
            "captures".to_owned(),
            "interpolate".into(),
            "--input".into(),
            path(&caps).into(),
            "--weights".into(),
            path(&weights).into(),
            "--out".into(),
            path(&out).into(),
            "--step".into(),
            step.into(),
        ];
        if let Some(c) = cap {
            a.extend(["--max-frames".into(), c.into()]);
        }
        a
    };
    let run = |a: Vec<String>| sky_train(&a.iter().map(String::as_str).collect::<Vec<_>>(), "");
    // 8 captures 15 minutes apart: 105 minutes, 6301 frames at 1 s.
    let a = args("1s", None);
    refused(
        &a.iter().map(String::as_str).collect::<Vec<_>>(),
        "",
        &["--step", "6301 frames", "--max-frames 1000"],
    );
    assert_eq!(std::fs::read_dir(&out).map_or(0, Iterator::count), 0);
    let a = args("1min", Some("50"));
    refused(
        &a.iter().map(String::as_str).collect::<Vec<_>>(),
        "",
        &["106 frames", "--max-frames 50"],
    );
    let done = run(args("1min", Some("106")));
    assert!(
        done.status.success(),
        "{}",
        String::from_utf8_lossy(&done.stderr)
    );
    let frames = std::fs::read_dir(&out)
        .expect("frames")
        .filter_map(Result::ok)
        .filter(|e| e.file_name().to_string_lossy().ends_with(".exr"))
        .count();
    assert_eq!(frames, 106);
}

// ---- item 6: daylight-tables --data ----------------------------------------------------

/// Issue 25 item 6: bad data files (empty, header only, a byte-order mark, NaN) exited 1
/// (failed work) where they are bad input (2), and a value of 1e308 was accepted (a table
/// entry of 709.2 instead of −9.58). Each is refused with status 2, naming the file and line;
/// the shipped file is accepted.
#[test]
fn daylight_tables_data_is_range_checked() {
    let shipped = concat!(env!("CARGO_MANIFEST_DIR"), "/data/daylight_diffuse.csv");
    // The site's samples as shipped (the default path is relative to the repository's root).
    let site = concat!(env!("CARGO_MANIFEST_DIR"), "/data/daylight_site.csv");
    let good = std::fs::read_to_string(shipped).expect("shipped data");
    let dir = tempfile::tempdir().expect("temp dir");
    let data = dir.path().join("d.csv");
    let out = dir.path().join("t.rs");
    let header = good.lines().next().expect("header");
    let mut lines: Vec<String> = good.lines().map(str::to_owned).collect();
    let row = |lines: &mut Vec<String>, n: usize, field: usize, v: &str| {
        let mut f: Vec<String> = lines[n - 1].split(',').map(str::to_owned).collect();
        f[field] = v.to_owned();
        lines[n - 1] = f.join(",");
    };
    let mut huge = lines.clone();
    row(&mut huge, 5, 3, "1e308");
    let mut nan = lines.clone();
    row(&mut nan, 7, 2, "NaN");
    let mut negative = lines.clone();
    row(&mut negative, 9, 5, "-1");
    let cases: Vec<(String, Vec<&str>)> = vec![
        (String::new(), vec!["empty"]),
        (format!("{header}\n"), vec!["line 1"]),
        (format!("\u{feff}{good}"), vec!["line 1", "header"]),
        (nan.join("\n") + "\n", vec!["line 7"]),
        (
            huge.join("\n") + "\n",
            vec!["line 5", "y_lux", "1e308", "200000"],
        ),
        (
            negative.join("\n") + "\n",
            vec!["line 9", "melanopic_edi_lux"],
        ),
    ];
    for (text, needles) in cases {
        std::fs::write(&data, &text).expect("data");
        let mut n = vec![path(&data)];
        n.extend(needles);
        refused(
            &[
                "daylight-tables",
                "--data",
                path(&data),
                "--site-data",
                site,
                "--out",
                path(&out),
            ],
            "",
            &n,
        );
        assert!(!out.exists());
    }
    lines.push(String::new());
    std::fs::write(&data, lines.join("\n")).expect("data");
    succeeds(
        &[
            "daylight-tables",
            "--data",
            path(&data),
            "--site-data",
            site,
            "--out",
            path(&out),
        ],
        "",
    );
    assert!(out.exists());
}

// ---- item 13: numbers ------------------------------------------------------------------

/// Whether `field` is written by the CSV rule (sky_train::csv_output): the shortest decimal
/// that reads back as the same f32 (checked here by parsing it as f32 and trying every
/// shorter precision), or empty.
fn shortest_f32(field: &str) -> bool {
    if field.is_empty() {
        return true;
    }
    let Ok(v) = field.parse::<f32>() else {
        return false;
    };
    // No shorter mantissa reads back as v.
    let digits = field
        .trim_start_matches('-')
        .split(['e', 'E'])
        .next()
        .unwrap_or("")
        .chars()
        .filter(char::is_ascii_digit)
        .collect::<String>();
    let significant = digits.trim_start_matches('0').trim_end_matches('0').len();
    (1..significant).all(|p| format!("{:.*e}", p - 1, v).parse::<f32>() != Ok(v))
}

/// Issue 25 item 13: elevations printed as `0.30000000000000004` and `melanopic_edi_lux`
/// as `0.000000` for 9.7e-10 lux. One rule for every CSV column: the shortest decimal that
/// reads back as the same f32. Checked on every numeric column of daylight, sample and cct.
#[test]
fn every_csv_number_is_the_shortest_f32() {
    let daylight = succeeds(
        &[
            "daylight",
            "--model",
            "preetham",
            "--elevations",
            "-18:1:0.1",
        ],
        "",
    );
    let r = rows(&daylight);
    let elevations: Vec<&str> = r.iter().map(|r| r[0].as_str()).collect();
    assert_eq!(elevations[..4], ["-18", "-17.9", "-17.8", "-17.7"]);
    assert!(
        elevations.contains(&"0.3") && elevations.contains(&"0"),
        "{elevations:?}"
    );
    let lowest: f64 = r[0][1].parse().expect("global_lux");
    assert!(lowest > 0.0, "{lowest}");
    let sample = succeeds(
        &["sample", "--model", "preetham", "--sun-zenith", "30"],
        "0,0\n45,90\n89.5,180\n",
    );
    let cct = succeeds(&["cct"], "0.31272,0.32903\n0.4,0.39\n");
    let schedule = succeeds(
        &[
            "schedule",
            "--lat",
            "48.2",
            "--lon",
            "16.4",
            "--date",
            "2026-06-21",
            "--step",
            "7",
        ],
        "",
    );
    for (name, text, from) in [
        ("daylight", &daylight, 0),
        ("sample", &sample, 2),
        ("cct", &cct, 2),
        ("schedule", &schedule, 1),
    ] {
        for row in rows(text) {
            for f in &row[from..] {
                assert!(shortest_f32(f), "{name}: `{f}` in {row:?}");
            }
        }
    }
}
