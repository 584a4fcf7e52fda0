//! Hostile input (issue 19): each case a test named after it, run through the `sky-train`
//! binary as a user would, under a 1 GiB address-space limit (`prlimit --as`) so that an
//! allocation beyond what a command states it needs fails the test instead of the machine.

mod common;

use std::path::Path;
use std::process::Command;

use common::{fails, path, sky_train, spawn, strs, succeeds};

/// A synthesized capture sequence of `frames` frames `width` wide in `dir`.
fn synthesize(dir: &Path, width: usize, frames: usize) {
    succeeds(
        &[
            "captures",
            "synthesize",
            "--out",
            path(dir),
            "--width",
            &width.to_string(),
            "--frames",
            &frames.to_string(),
            "--start",
            "08:00",
        ],
        "",
    );
}

/// `captures train` on `caps` without cross-validation, for `iterations` and `samples` per
/// frame.
fn captures_train<'a>(caps: &'a str, iterations: &'a str, samples: &'a str) -> Vec<&'a str> {
    vec![
        "captures",
        "train",
        "--input",
        caps,
        "--no-cross-validation",
        "--max-iterations",
        iterations,
        "--samples",
        samples,
    ]
}

/// Where the value of the OpenEXR header attribute `name` of type `ty` starts in `bytes`.
fn attribute(bytes: &[u8], name: &str, ty: &str) -> Option<usize> {
    let key = format!("{name}\0{ty}\0");
    let at = bytes.windows(key.len()).position(|w| w == key.as_bytes())?;
    Some(at + key.len() + 4) // after the value's size
}

/// Patches an OpenEXR file's `dataWindow` and `displayWindow` to claim `width` × `height`,
/// and its `chunkCount` (when present) to match, as a consistent hostile header would.
fn claim_size(file: &Path, width: i32, height: i32) {
    let mut bytes = std::fs::read(file).expect("frame");
    for name in ["dataWindow", "displayWindow"] {
        let at = attribute(&bytes, name, "box2i").expect("window");
        for (k, v) in [0, 0, width - 1, height - 1].into_iter().enumerate() {
            bytes[at + 4 * k..at + 4 * k + 4].copy_from_slice(&i32::to_le_bytes(v));
        }
    }
    let int =
        |at: usize| i32::from_le_bytes([bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]]);
    let chunks = match attribute(&bytes, "tiles", "tiledesc") {
        // One level of tiles (the frames' writer uses no mip levels).
        Some(at) => {
            let (tx, ty) = (int(at), int(at + 4));
            ((width + tx - 1) / tx) * ((height + ty - 1) / ty)
        }
        None => {
            let compression =
                attribute(&bytes, "compression", "compression").map_or(0, |at| bytes[at]);
            // Scan lines per chunk of each compression method (OpenEXR file layout: none,
            // RLE, ZIPS, ZIP, PIZ, PXR24, B44, B44A, DWAA, DWAB).
            let lines = [1, 1, 1, 16, 32, 16, 32, 32, 32, 256][usize::from(compression.min(9))];
            (height + lines - 1) / lines
        }
    };
    if let Some(at) = attribute(&bytes, "chunkCount", "int") {
        bytes[at..at + 4].copy_from_slice(&i32::to_le_bytes(chunks));
    }
    std::fs::write(file, bytes).expect("patched");
}

/// Case 1: a frame whose header claims 65536 × 32768 or 16384 × 8192 pixels is refused from its
/// header, naming the file and the limit, by every command that reads captures.
#[test]
fn exr_header_claiming_a_huge_frame_is_refused_before_allocating() {
    let dir = tempfile::tempdir().expect("temp dir");
    let caps = dir.path().join("caps");
    synthesize(&caps, 64, 4);
    let weights = dir.path().join("sky.weights");
    let mut train = captures_train(path(&caps), "2", "64");
    train.extend(["--out", path(&weights)]);
    succeeds(&train, "");
    let mut frames: Vec<_> = std::fs::read_dir(&caps)
        .expect("folder")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e == "exr"))
        .collect();
    frames.sort();
    let name = frames[0]
        .file_name()
        .and_then(|n| n.to_str())
        .expect("name");
    for (w, h) in [(65536, 32768), (16384, 8192)] {
        for frame in &frames {
            claim_size(frame, w, h);
        }
        let claim = format!("{w}x{h}");
        for args in [
            vec![
                "captures",
                "train",
                "--input",
                path(&caps),
                "--no-cross-validation",
            ],
            vec![
                "captures",
                "interpolate",
                "--input",
                path(&caps),
                "--weights",
                path(&weights),
                "--out",
                path(&dir.path().join("gaps")),
            ],
            vec![
                "captures",
                "strip",
                "--input",
                path(&caps),
                "--weights",
                path(&weights),
                "--out",
                path(&dir.path().join("s.png")),
            ],
        ] {
            fails(&args, "", &[name, &claim, "8192x4096"]);
        }
    }
    assert!(!dir.path().join("gaps").exists() && !dir.path().join("s.png").exists());
}

/// The strip `captures strip` writes: (width, height, luminance per pixel) of the sRGB PNG.
fn read_strip(file: &Path) -> (usize, usize, Vec<f32>) {
    let decoder = png::Decoder::new(std::io::BufReader::new(
        std::fs::File::open(file).expect("strip"),
    ));
    let mut reader = decoder.read_info().expect("a PNG");
    let mut buf = vec![0; reader.output_buffer_size().expect("size")];
    let info = reader.next_frame(&mut buf).expect("decodes");
    let luminance = buf[..info.buffer_size()]
        .chunks(3)
        .map(|p| 0.2126 * f32::from(p[0]) + 0.7152 * f32::from(p[1]) + 0.0722 * f32::from(p[2]))
        .collect();
    (info.width as usize, info.height as usize, luminance)
}

/// The column of the brightest pixel (summed over its rows) of the `tw` × `th` cell at `x0`,
/// `y0` of a strip.
fn brightest_column(strip: &(usize, usize, Vec<f32>), x0: usize, y0: usize, tw: usize) -> usize {
    let th = tw / 4;
    (0..tw)
        .map(|x| {
            let sum: f32 = (0..th).map(|y| strip.2[(y0 + y) * strip.0 + x0 + x]).sum();
            (x, sum)
        })
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .map_or(0, |(x, _)| x)
}

/// Case 2: `captures strip` at its default thumbnail width (128) of captures narrower than
/// that, and of captures between one and two times as wide: no panic, and each network
/// thumbnail shows the whole panorama, turned like the capture above it: its brightest column
/// (the sky around the sun) lies within 3 of 128 columns of the capture's (8 before the fix at
/// 240 pixels wide, where it showed the first 128 columns of 240).
#[test]
fn strip_thumbnails_wider_than_the_captures() {
    for width in [64, 240] {
        let dir = tempfile::tempdir().expect("temp dir");
        let caps = dir.path().join("caps");
        synthesize(&caps, width, 4);
        let weights = dir.path().join("sky.weights");
        let mut train = captures_train(path(&caps), "40", "1024");
        train.extend(["--out", path(&weights)]);
        succeeds(&train, "");
        let out = dir.path().join("s.png");
        succeeds(
            &[
                "captures",
                "strip",
                "--input",
                path(&caps),
                "--weights",
                path(&weights),
                "--out",
                path(&out),
                "--captures",
                "2",
                "--between",
                "0",
            ],
            "",
        );
        let strip = read_strip(&out);
        let (tw, gap) = (128, 4);
        assert_eq!((strip.0, strip.1), (2 * tw + gap, 2 * (tw / 4) + gap));
        for cell in 0..2 {
            let x0 = cell * (tw + gap);
            let capture = brightest_column(&strip, x0, 0, tw);
            let network = brightest_column(&strip, x0, tw / 4 + gap, tw);
            let apart = capture
                .abs_diff(network)
                .min(tw - capture.abs_diff(network));
            assert!(
                apart <= 3,
                "captures {width} wide, cell {cell}: brightest columns {capture} (capture) and {network} (network)"
            );
        }
    }
}

/// Sets the manifest exposure of the first frame (`first_only`) or of every frame.
fn set_exposure(caps: &Path, exposure: &str, first_only: bool) {
    let manifest = caps.join("captures.toml");
    let text = std::fs::read_to_string(&manifest).expect("manifest");
    let mut done = false;
    let lines: Vec<String> = text
        .lines()
        .map(|l| {
            if l.starts_with("exposure = ") && !(first_only && done) {
                done = true;
                format!("exposure = {exposure}")
            } else {
                l.to_string()
            }
        })
        .collect();
    std::fs::write(&manifest, lines.join("\n")).expect("manifest written");
}

/// Case 3: a training that diverges (radiance beyond f32 from a manifest exposure of 1e-40, one
/// frame 1e17 times brighter than the others, a checkpoint with huge parameters) exits non-zero
/// and leaves the good weight file in place.
#[test]
fn diverged_training_keeps_the_good_weights() {
    let dir = tempfile::tempdir().expect("temp dir");
    let caps = dir.path().join("caps");
    synthesize(&caps, 64, 4);
    let train = captures_train(path(&caps), "10", "256");
    succeeds(&train, "");
    let weights = caps.join("sky.weights");
    let good = std::fs::read(&weights).expect("weights");
    set_exposure(&caps, "1e-40", false);
    fails(&train, "", &["sky_0800.exr", "exposure 1e-40", "f32"]);
    assert_eq!(std::fs::read(&weights).expect("weights"), good);
    for exposure in ["1e-20", "1e-36"] {
        set_exposure(&caps, "2e-3", false);
        set_exposure(&caps, exposure, true);
        fails(&train, "", &["diverged", "NRMSE"]);
        assert_eq!(
            std::fs::read(&weights).expect("weights"),
            good,
            "{exposure}"
        );
    }

    // `train` from a checkpoint of huge parameters.
    let out = dir.path().join("sky.skyn");
    let small = [
        "--turbidities",
        "2,4",
        "--sun-zeniths",
        "3",
        "--views",
        "4x8",
        "--max-iterations",
        "2",
        "--out",
        path(&out),
    ];
    let mut args = vec!["train"];
    args.extend(small);
    succeeds(&args, "");
    let good = std::fs::read(&out).expect("weights");
    let checkpoint = dir.path().join("run.ckpt");
    args.extend(["--checkpoint", path(&checkpoint)]);
    for (value, needle) in [("1e300", "1e300"), ("1e30", "diverged")] {
        let params = vec![value; 123].join("\n");
        std::fs::write(
            &checkpoint,
            format!("sky-train checkpoint 2\nsizes 6 12 3\niteration 0\nlambda none\n{params}\n"),
        )
        .expect("checkpoint");
        fails(&args, "", &[needle]);
        assert_eq!(std::fs::read(&out).expect("weights"), good, "{value}");
    }
}

/// The shipped Preetham weight file with its 32-byte source name replaced by `name` (NUL
/// padded) and its checksum made valid again.
fn weights_named(name: &[u8]) -> Vec<u8> {
    use sky_core::neural::{NeuralWeights, pretrained, weights};
    let mut bytes = vec![0; NeuralWeights::<12>::ENCODED_LEN];
    pretrained::PREETHAM.encode(&mut bytes).expect("encodes");
    bytes[88..120].fill(0);
    bytes[88..88 + name.len()].copy_from_slice(name);
    let n = bytes.len();
    let crc = weights::crc32(&bytes[..n - 4]);
    bytes[n - 4..].copy_from_slice(&crc.to_le_bytes());
    bytes
}

/// Case 7: `export` writes no code it was not meant to: a `--name` that is not an upper-case
/// identifier is refused; a source name with a quote stays inside its byte string; a file
/// name with a newline stays inside its comment; a source name with control characters (a
/// terminal escape sequence) is refused by the decoder, and no command prints it.
#[test]
fn generated_source_escapes_names() {
    let dir = tempfile::tempdir().expect("temp dir");
    let out = dir.path().join("w.rs");
    let good = dir.path().join("preetham.skyn");
    std::fs::write(&good, weights_named(b"preetham")).expect("weights");
    let export = |weights: &Path, name: &str| {
        vec![
            "export".to_string(),
            "--weights".into(),
            path(weights).into(),
            "--name".into(),
            name.into(),
            "--out".into(),
            path(&out).into(),
        ]
    };
    for name in ["X\"; panic!(); //", "lower", "1X", "", "A B", "É"] {
        let args = export(&good, name);
        let code = fails(&strs(&args), "", &["--name"]);
        assert_eq!(code, 2, "{name}");
        assert!(!out.exists(), "{name}");
    }

    let quoted = dir.path().join("quoted.skyn");
    let payload = b"\";}fn injected(){}//";
    std::fs::write(&quoted, weights_named(payload)).expect("weights");
    succeeds(&strs(&export(&quoted, "QUOTED")), "");
    let text = std::fs::read_to_string(&out).expect("generated");
    let expected = format!(
        "    source: *b\"\\\";}}fn injected(){{}}//{}\",",
        "\\0".repeat(32 - payload.len())
    );
    assert!(text.lines().any(|l| l == expected), "{text}");

    let odd = dir.path().join("w\nfn injected() {}\n.skyn");
    std::fs::write(&odd, weights_named(b"preetham")).expect("weights");
    succeeds(&strs(&export(&odd, "ODD")), "");
    let text = std::fs::read_to_string(&out).expect("generated");
    assert!(!text.lines().any(|l| l.starts_with("fn ")), "{text}");
    std::fs::remove_file(&out).expect("removed");

    let escape = dir.path().join("escape.skyn");
    std::fs::write(&escape, weights_named(b"\x1b[2J\x1b]0;owned\x07")).expect("weights");
    for args in [
        export(&escape, "ESCAPE"),
        [
            "sample",
            "--model",
            "neural",
            "--sun-zenith",
            "30",
            "--weights",
        ]
        .map(String::from)
        .into_iter()
        .chain([path(&escape).to_string()])
        .collect(),
    ] {
        let run = sky_train(&strs(&args), "0,0\n");
        assert!(!run.status.success(), "{args:?}");
        assert!(
            !run.stderr.contains(&0x1b) && !run.stdout.contains(&0x1b),
            "{args:?}: {}",
            String::from_utf8_lossy(&run.stderr)
        );
        assert!(
            String::from_utf8_lossy(&run.stderr).contains("source model"),
            "{args:?}"
        );
    }
    assert!(!out.exists());
}

/// Case 5 (`cct`, `sample`): the first stdin line is a header only when it names the columns; otherwise it is
/// data like any other line (`NaN,0`, `inf,0`, `0.31.27,0.3290` are errors naming line 1, exit
/// status 2), and a UTF-8 byte-order mark before it is dropped.
#[test]
fn first_stdin_line_is_data_unless_it_names_the_columns() {
    let commands: [(&[&str], &str, &str); 2] = [
        (&["cct"], "x,y", "0.3127,0.3290"),
        (
            &["sample", "--sun-zenith", "30"],
            "view_zenith_deg,view_azimuth_deg",
            "10,20",
        ),
    ];
    for (args, header, good) in commands {
        for bad in ["NaN,0", "inf,0", "0.31.27,0.3290", "-inf,1e999"] {
            let code = fails(args, &format!("{bad}\n{good}\n"), &["stdin line 1", header]);
            assert_eq!(code, 2, "{args:?} {bad}");
            let code = fails(args, &format!("{good}\n{bad}\n"), &["stdin line 2", header]);
            assert_eq!(code, 2, "{args:?} {bad}");
        }
        let rows = |stdin: &str| succeeds(args, stdin).lines().count() - 1;
        assert_eq!(rows(&format!("\u{feff}{good}\n{good}\n")), 2, "{args:?}");
        assert_eq!(rows(&format!("{header}\n{good}\n")), 1, "{args:?}");
        assert_eq!(rows(&format!("\u{feff}{header}\n{good}\n")), 1, "{args:?}");
    }
}

/// `sample`'s CSV rows: view zenith, azimuth, Y, x, y, R, G, B.
fn sample_rows(args: &[&str], directions: &str) -> Vec<[f64; 8]> {
    succeeds(args, directions)
        .lines()
        .skip(1)
        .map(|l| {
            let v: Vec<f64> = l.split(',').map(|f| f.parse().expect("a number")).collect();
            v.try_into().expect("8 columns")
        })
        .collect()
}

/// Case 8: the SH sky keeps its contract: radiance non-negative in every direction (also at 5
/// bands without the ringing filter, whose series dips below zero above the horizon), black
/// below the horizon as `render` shows it, and the columns consistent (Y = 0 with the D65
/// chromaticity of black, x and y inside [0, 1]).
#[test]
fn sh_outputs_are_non_negative_and_black_below_the_horizon() {
    let mut directions = String::new();
    for zenith in (0..=180).step_by(5) {
        for azimuth in (0..360).step_by(10) {
            directions.push_str(&format!("{zenith},{azimuth}\n"));
        }
    }
    for sun in ["10", "60", "85", "90"] {
        for extra in [
            &[][..],
            &["--no-ringing-filter", "--bands", "5"],
            &["--no-ringing-filter"],
        ] {
            let mut args = vec!["sample", "--model", "sh", "--sun-zenith", sun];
            args.extend(extra);
            for row in sample_rows(&args, &directions) {
                let [zenith, _, lum, x, y, r, g, b] = row;
                assert!(
                    [lum, r, g, b].iter().all(|v| *v >= 0.0),
                    "{args:?}: negative radiance {row:?}"
                );
                assert!(
                    (0.0..=1.0).contains(&x) && (0.0..=1.0).contains(&y),
                    "{args:?}: {row:?}"
                );
                if zenith > 90.0 {
                    assert!(
                        lum == 0.0 && r == 0.0 && g == 0.0 && b == 0.0,
                        "{args:?}: {row:?}"
                    );
                }
            }
        }
    }
}

/// Case 4: budgets are kept: `train --hidden 255 --max-seconds 1 --max-iterations 1` stops on
/// its clock (the random starts' race included; 183 s and 1 GB before) within the 1 GiB
/// address space, and a network whose Levenberg-Marquardt normal equations cannot fit
/// (`--hidden 255,255`: 67,833 parameters, a 37 GB matrix) is refused before training, exit 2.
#[test]
fn training_budgets_are_kept() {
    let started = std::time::Instant::now();
    let out = succeeds(
        &[
            "train",
            "--hidden",
            "255",
            "--max-seconds",
            "1",
            "--max-iterations",
            "1",
        ],
        "",
    );
    let seconds = started.elapsed().as_secs_f64();
    // Sampling, the validation and test images and one block of Jacobian rows past the clock
    // take a few seconds more on this 2-core machine; 60 s leaves room for a loaded one.
    assert!(seconds < 60.0, "{seconds} s: {out}");
    let code = fails(
        &["train", "--hidden", "255,255"],
        "",
        &["--hidden 255,255", "67833", "3000"],
    );
    assert_eq!(code, 2);
}

/// Case 6: every output path and option is checked before the work starts: a `--out` in a
/// folder that does not exist or under a plain file, a file name of the wrong type, or a
/// `--hidden` layout the weight file cannot hold is refused with exit status 2 before any
/// sampling, training, fitting or precomputation (before, `train --out /nonexistent/x.skyn`
/// trained its whole budget and then failed with status 1). That the work did not start shows
/// in what it would have left: no checkpoint, no cache folder, no output folder.
#[test]
fn outputs_are_checked_before_the_work_starts() {
    let dir = tempfile::tempdir().expect("temp dir");
    let t = path(dir.path());
    std::fs::write(dir.path().join("plain"), "not a folder").expect("file");
    synthesize(&dir.path().join("caps"), 64, 4);
    let w = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../sky-core/weights/preetham.skyn"
    );
    // Training that leaves a checkpoint after its first iteration.
    let train = format!("train --checkpoint {t}/ck --max-iterations 1");
    let captures = format!("--input {t}/caps");
    let physical = format!("--model physical --sun-zenith 30 --cache-dir {t}/cache");
    let daylight = "daylight --elevations 0:10:5";
    // Each command line (paths without spaces) and what its one error line names.
    let cases = [
        (
            format!("{train} --out {t}/missing/x.skyn"),
            "--out|does not exist",
        ),
        (
            format!("{train} --out {t}/plain/x"),
            "--out|is not a folder",
        ),
        (format!("{train} --out {t}"), "--out|is a folder"),
        (
            format!("{train} --hidden 6 --out {t}/f.skyn"),
            "--hidden 6|--out",
        ),
        (
            format!("{train} --hidden 6 --init-weights {w}"),
            "--hidden 6|--init-weights",
        ),
        (
            format!("train --checkpoint {t}/plain/x"),
            "--checkpoint|is not a folder",
        ),
        (
            format!("captures train {captures} --max-iterations 1 --out {t}/missing/x"),
            "--out|does not exist",
        ),
        (
            format!("captures train --input {t}/missing"),
            "--input|not a folder",
        ),
        (
            format!("captures interpolate --weights {w} {captures} --out {t}/plain/x"),
            "--out|is not a folder",
        ),
        (
            format!("captures interpolate --weights {w} {captures} --out {t}/i --width 17"),
            "--width 17",
        ),
        (
            format!("captures strip --weights {w} {captures} --out {t}/s.jpg"),
            "--out|.png",
        ),
        (
            format!("captures synthesize --width 16 --out {t}/plain/x"),
            "--out|is not a folder",
        ),
        (format!("render {physical} --out {t}/r.jpg"), "--out|.png"),
        (
            format!("render {physical} --out {t}/missing/x.exr"),
            "--out|does not exist",
        ),
        (
            format!("sample --model physical --sun-zenith 30 --cache-dir {t}/plain/x"),
            "--cache-dir|is not a folder",
        ),
        (
            format!("fit-sh --model preetham --out {t}/plain/x.rs"),
            "--out|is not a folder",
        ),
        (
            format!("fit-sh --model preetham --out {t}/t.rs --report {t}/plain/x"),
            "--report|is not a folder",
        ),
        (
            format!("export --format glsl --out {t}/missing/x.glsl"),
            "--out|does not exist",
        ),
        (
            format!("gallery --out {t}/plain/x"),
            "--out|is not a folder",
        ),
        (
            format!("locus-table --out {t}/missing/x.rs"),
            "--out|does not exist",
        ),
        (
            format!("showcase --out {t}/plain/x"),
            "--out|is not a folder",
        ),
        (
            format!("eval --model neural-preetham --out {t}/plain/x"),
            "--out|is not a folder",
        ),
        (
            format!("{daylight} --plot-cct {t}/missing/x.png"),
            "--plot-cct|does not exist",
        ),
        (
            format!("{daylight} --plot-illuminance {t}/a.svg"),
            "--plot-illuminance|.png",
        ),
    ];
    // Every case is run, and every one that is not refused at once is reported.
    let mut wrong = Vec::new();
    for (line, needles) in &cases {
        let args: Vec<&str> = line.split(' ').collect();
        let out = sky_train(&args, "");
        let stderr = String::from_utf8_lossy(&out.stderr);
        let refused = out.status.code() == Some(2)
            && stderr.trim_end().lines().count() == 1
            && needles.split('|').all(|n| stderr.contains(n));
        if !refused {
            wrong.push(format!(
                "{args:?}: {:?} `{}`",
                out.status,
                stderr.trim_end()
            ));
        }
        for left in ["ck", "cache", "missing", "i", "f.skyn"] {
            if dir.path().join(left).exists() {
                wrong.push(format!("{args:?}: the work started (left {left})"));
                let p = dir.path().join(left);
                let _ = std::fs::remove_dir_all(&p).or_else(|_| std::fs::remove_file(&p));
            }
        }
    }
    assert!(
        wrong.is_empty(),
        "not refused at once:\n{}",
        wrong.join("\n")
    );
}

/// Case 9: errors that say what was checked, and exit statuses that say whose fault it was:
/// 2 for every bad argument or bad input file, 1 only when the work itself fails (here: stdout
/// is a full disk). `--model neural` names its weight file's own sun-zenith domain (20-60 deg
/// here; [0, 180] before), an end a refused value sits on is printed open, a bound of "above 0"
/// is not printed as 1.1754944e-38, no message mixes degrees and radians, and `train --model
/// sh` trains with its defaults (it failed on its own default turbidities).
#[test]
fn errors_name_what_was_checked_and_exit_statuses_say_whose_fault() {
    use sky_core::neural::NeuralWeights;
    let dir = tempfile::tempdir().expect("temp dir");
    let t = path(dir.path());
    let shipped = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../sky-core/weights/preetham.skyn"
    );
    let mut narrow =
        NeuralWeights::<12>::decode(&std::fs::read(shipped).expect("weights")).expect("decodes");
    narrow.sun_zenith_range = (20f32.to_radians(), 60f32.to_radians());
    let bytes = sky_train::export::encode(&narrow).expect("encodes");
    std::fs::write(dir.path().join("narrow.skyn"), bytes).expect("written");
    std::fs::write(dir.path().join("garbage"), "garbage").expect("written");
    std::fs::create_dir(dir.path().join("caps")).expect("folder");
    std::fs::write(dir.path().join("caps/captures.toml"), "not toml [[[").expect("written");
    std::fs::write(dir.path().join("m.csv"), "utc,global_lux\nnope,5\n").expect("written");
    let g = format!("{t}/garbage");
    let schedule = "schedule --lat 48 --lon 16";
    // Command line, stdin, exit status, what the one error line names.
    let cases = [
        // Bad arguments.
        (
            format!("sample --model neural --weights {t}/narrow.skyn --sun-zenith 70"),
            "",
            2,
            "--sun-zenith 70 deg|[20, 60] deg",
        ),
        (
            "sample --sun-zenith 30 --turbidity 7".into(),
            "",
            2,
            "--turbidity 7|[2, 6]",
        ),
        ("render --width 0 --out x.png".into(), "", 2, "--width"),
        ("size-study --model cie".into(), "", 2, "--model cie"),
        (
            "spectrum --sun-zenith 120".into(),
            "",
            2,
            "--sun-zenith 120 deg|[0, 108] deg",
        ),
        ("eval --model neural".into(), "", 2, "--weights"),
        ("fit-sh --model sh".into(), "", 2, "--model sh"),
        (
            "fit-sh --model preetham --turbidity-min 1".into(),
            "",
            2,
            "--turbidity-min 1|[2, 6]",
        ),
        ("train --model cie".into(), "", 2, "--model cie"),
        ("train --model neural".into(), "", 2, "--model neural"),
        ("train --target-nrmse nan".into(), "", 2, "--target-nrmse"),
        (
            format!("{schedule} --date 2026-06-21 --step 0"),
            "",
            2,
            "--step",
        ),
        ("bench --no-such-flag".into(), "", 2, "--no-such-flag"),
        (
            "captures synthesize --out x --min-elevation 80".into(),
            "",
            2,
            "--min-elevation 80",
        ),
        // Bad input on stdin: an end a refused value sits on is open, "above 0" is `(0`.
        ("cct".into(), "0.2,0\n", 2, "stdin line 1|(0, 1]"),
        (
            "cct".into(),
            "0.23,0.22\n",
            2,
            "stdin line 1|[1000, 100000) K",
        ),
        ("sample --sun-zenith 30".into(), "0,0\nx\n", 2, "line 2"),
        // Bad input files.
        (
            format!("sample --model neural --weights {g} --sun-zenith 30"),
            "",
            2,
            "--weights|truncated",
        ),
        (
            format!("train --init-weights {g}"),
            "",
            2,
            "--init-weights|truncated",
        ),
        (
            format!("train --checkpoint {g}"),
            "",
            2,
            "--checkpoint|not a sky-train checkpoint",
        ),
        (
            format!("export --format f32 --name X --weights {g} --out {t}/x.rs"),
            "",
            2,
            "--weights",
        ),
        (
            format!("eval --model neural --weights {g} --out {t}/e"),
            "",
            2,
            "--weights",
        ),
        (
            format!("captures train --input {t}/caps"),
            "",
            2,
            "--input|captures.toml",
        ),
        (
            format!("captures strip --input {t}/caps --weights {g} --out {t}/s.png"),
            "",
            2,
            "--weights",
        ),
        (
            format!("sample --model aoas --style {g} --sun-zenith 30"),
            "",
            2,
            "--style",
        ),
        (
            format!("{schedule} --measurements {t}/m.csv"),
            "",
            2,
            "--measurements|line 2",
        ),
        (
            format!("{schedule} --measurements {t}/none.csv"),
            "",
            2,
            "--measurements",
        ),
        // The work itself: a training with its defaults.
        ("train --model sh --max-iterations 1".into(), "", 0, ""),
    ];
    let mut wrong = Vec::new();
    for (line, stdin, status, needles) in &cases {
        let args: Vec<&str> = line.split(' ').collect();
        let out = sky_train(&args, stdin);
        let stderr = String::from_utf8_lossy(&out.stderr);
        let lines = stderr.trim_end().lines().count();
        let ok = out.status.code() == Some(*status)
            && (*status == 0 || lines == 1)
            && needles.split('|').all(|n| stderr.contains(n))
            && !(stderr.contains(" deg") && stderr.contains(" rad"))
            && !stderr.contains("e-38")
            && !stderr.contains("0000000");
        if !ok {
            wrong.push(format!("{line}: {:?} `{}`", out.status, stderr.trim_end()));
        }
    }
    // A failure of the work: stdout cannot be written.
    let full = Command::new(env!("CARGO_BIN_EXE_sky-train"))
        .args(["sample", "--sun-zenith", "30"])
        .stdin(std::fs::File::open("/dev/null").expect("null"))
        .stdout(
            std::fs::OpenOptions::new()
                .write(true)
                .open("/dev/full")
                .expect("full"),
        )
        .output()
        .expect("runs");
    if full.status.code() != Some(1) {
        wrong.push(format!("sample > /dev/full: {:?}", full.status));
    }
    assert!(
        wrong.is_empty(),
        "wrong status or message:\n{}",
        wrong.join("\n")
    );
}

/// Case 5 (`sample` in bounded memory): rows are streamed, a block of 4096 at a time: the first
/// block's results arrive while stdin is still open (before, every row was held until the end
/// of the input), and a bad line after it leaves that block written, exit status 2.
#[test]
fn sample_streams_its_rows() {
    use std::io::{BufRead, BufReader, Write};
    let mut child = spawn(&["sample", "--sun-zenith", "30"]);
    let mut stdin = child.stdin.take().expect("stdin");
    stdin
        .write_all("10,20\n".repeat(4096).as_bytes())
        .expect("written");
    stdin.flush().expect("flushed");
    let stdout = child.stdout.take().expect("stdout");
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        let lines: Vec<String> = BufReader::new(stdout)
            .lines()
            .take(4097)
            .map(|l| l.expect("text"))
            .collect();
        let _ = tx.send(lines);
    });
    let first = rx
        .recv_timeout(std::time::Duration::from_secs(120))
        .expect("the first block's rows arrive while stdin is open");
    assert_eq!(first.len(), 4097);
    assert!(first[4096].starts_with("10,20,"), "{}", first[4096]);
    stdin.write_all(b"x\n").expect("written");
    drop(stdin);
    let out = child.wait_with_output().expect("ends");
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("stdin line 4097"), "{stderr}");
}
