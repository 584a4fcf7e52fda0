//! Hostile input, round 3 (issue 25), the file system's half: what is at an output path
//! (devices, FIFOs, sockets, symbolic links, modes, hard links), signals during a write and
//! the temporary files they leave, bounded reads of every file read, and the physical cache.
//! Each case runs the `sky-train` binary as a user would, under a 1 GiB address-space limit
//! (`prlimit --as`) like `hostile.rs`, with a time limit so that a read that hangs fails the
//! test instead of stalling it. Device nodes are private ones made by the test with `mknod` in
//! its temporary folder (the tests run as root), never the system's.
//!
//! `SKY_TRAIN_UNDER_TEST=/path/to/sky-train` runs the cases against another build of the
//! binary (how each was checked to fail on the binary before these fixes).

use std::os::unix::fs::{FileTypeExt, MetadataExt, PermissionsExt};
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant, SystemTime};

mod common;

use sky_train::physical::cache;
use sky_train::physical::{Atmosphere, Resolution};

use common::{ADDRESS_SPACE, binary, path, strs};

/// The longest a command of these cases may take once the atmosphere is cached.
const TIME_LIMIT: Duration = Duration::from_secs(120);

/// `sky-train args` under [`ADDRESS_SPACE`], with `env` set, its stdin, stdout and stderr
/// piped; `user` runs it as that uid and gid (`setpriv`).
fn command(args: &[&str], env: &[(&str, &str)], user: Option<u32>) -> Command {
    let mut c = match user {
        Some(id) => {
            let mut c = Command::new("setpriv");
            c.args([
                format!("--reuid={id}"),
                format!("--regid={id}"),
                "--clear-groups".into(),
                "prlimit".into(),
            ]);
            c
        }
        None => Command::new("prlimit"),
    };
    c.arg(ADDRESS_SPACE)
        .arg(binary())
        .args(args)
        .envs(env.iter().copied())
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped());
    c
}

/// Runs `sky-train args` with `stdin`, killed after `limit` (the test then fails, naming it).
fn run_as(
    args: &[&str],
    stdin: &str,
    env: &[(&str, &str)],
    user: Option<u32>,
    limit: Duration,
) -> Output {
    use std::io::Write;
    let mut child = command(args, env, user)
        .spawn()
        .expect("prlimit and sky-train run");
    let mut input = child.stdin.take().expect("stdin");
    let stdin = stdin.to_owned();
    let writer = std::thread::spawn(move || {
        // A command that refuses its arguments may end before it reads stdin.
        let _ = input.write_all(stdin.as_bytes());
    });
    let start = Instant::now();
    while child.try_wait().expect("wait").is_none() {
        if start.elapsed() > limit {
            let _ = child.kill();
            let out = child.wait_with_output().expect("killed");
            panic!(
                "{args:?} still ran after {limit:?} (killed): {}",
                String::from_utf8_lossy(&out.stderr)
            );
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    let _ = writer.join();
    child.wait_with_output().expect("sky-train ends")
}

fn run(args: &[&str], stdin: &str) -> Output {
    run_as(args, stdin, &[], None, TIME_LIMIT)
}

/// Asserts `args` succeed; returns stderr.
fn succeeds(args: &[&str], stdin: &str) -> String {
    checked_success(args, &run(args, stdin))
}

fn checked_success(args: &[&str], out: &Output) -> String {
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(out.status.success(), "{args:?}: {:?} {stderr}", out.status);
    stderr
}

/// Asserts that `out` of `args` is a failure with exit status `code` (not a signal) and one
/// stderr line holding every `needle`.
fn check_failure(args: &[&str], out: &Output, code: i32, needles: &[&str]) {
    let stderr = String::from_utf8_lossy(&out.stderr);
    let got = out
        .status
        .code()
        .unwrap_or_else(|| panic!("{args:?} was killed ({:?}): {stderr}", out.status));
    assert_eq!(got, code, "{args:?}: {stderr}");
    assert_eq!(stderr.trim_end().lines().count(), 1, "{args:?}: `{stderr}`");
    for needle in needles {
        assert!(
            stderr.contains(needle),
            "{args:?}: `{stderr}` lacks `{needle}`"
        );
    }
}

fn fails(args: &[&str], stdin: &str, code: i32, needles: &[&str]) {
    check_failure(args, &run(args, stdin), code, needles);
}

/// A temporary folder others may enter (for the case run as another user).
fn tempdir() -> tempfile::TempDir {
    let dir = tempfile::tempdir().expect("temp dir");
    std::fs::set_permissions(dir.path(), PermissionsExt::from_mode(0o755)).expect("chmod");
    dir
}

fn mknod(path: &Path, kind: &str, major_minor: Option<(u32, u32)>) {
    let mut c = Command::new(if kind == "p" { "mkfifo" } else { "mknod" });
    c.arg(path);
    if let Some((major, minor)) = major_minor {
        c.args([kind.to_string(), major.to_string(), minor.to_string()]);
    }
    let status = c.status().expect("mknod runs");
    assert!(status.success(), "{c:?}");
}

/// A private character device `major, minor` at `path` (1, 3 is null; 1, 5 is zero).
fn char_device(path: &Path, major: u32, minor: u32) {
    mknod(path, "c", Some((major, minor)));
}

fn fifo(path: &Path) {
    mknod(path, "p", None);
}

/// A small render of the Preetham sky to `out`.
fn render(out: &Path) -> Vec<String> {
    [
        "render",
        "--sun-zenith",
        "40",
        "--width",
        "32",
        "--out",
        path(out),
    ]
    .map(String::from)
    .to_vec()
}

/// The first bytes of a PNG and of an OpenEXR file.
const PNG_SIGNATURE: &[u8] = b"\x89PNG\r\n\x1a\n";
const EXR_MAGIC: &[u8] = &[0x76, 0x2f, 0x31, 0x01];

/// Item 1: `--out` naming a device node writes to the device, which stays a device (as root,
/// the atomic write's rename used to turn `/dev/null` into a regular file). Both formats: the
/// OpenEXR encoder seeks, so its file is encoded in memory first.
#[test]
fn an_output_that_is_a_device_node_is_written_to_not_replaced() {
    let dir = tempdir();
    for name in ["null.png", "null.exr"] {
        let node = dir.path().join(name);
        char_device(&node, 1, 3);
        succeeds(&strs(&render(&node)), "");
        let m = std::fs::symlink_metadata(&node).expect("still there");
        assert!(
            m.file_type().is_char_device(),
            "{name}: {:?}",
            m.file_type()
        );
        assert_eq!(
            m.rdev(),
            std::fs::metadata("/dev/null").expect("null").rdev()
        );
    }
    // Nothing else was left in the folder (no temporary file).
    let left: Vec<_> = std::fs::read_dir(dir.path()).expect("dir").collect();
    assert_eq!(left.len(), 2, "{left:?}");
}

/// Item 1: a FIFO at `--out` is written directly: a reader gets the whole file (PNG and
/// OpenEXR), and the FIFO stays.
#[test]
fn an_output_that_is_a_fifo_is_written_to_its_reader() {
    let dir = tempdir();
    for (name, magic) in [("pipe.png", PNG_SIGNATURE), ("pipe.exr", EXR_MAGIC)] {
        let pipe = dir.path().join(name);
        fifo(&pipe);
        let (send, got) = std::sync::mpsc::channel();
        let reader_path = pipe.clone();
        // Blocks until a writer opens the FIFO; detached if none ever does.
        std::thread::spawn(move || {
            let _ = send.send(std::fs::read(reader_path));
        });
        let args = render(&pipe);
        let out = run(&strs(&args), "");
        checked_success(&strs(&args), &out);
        let bytes = got
            .recv_timeout(Duration::from_secs(30))
            .unwrap_or_else(|_| panic!("{name}: nothing was written to the FIFO"))
            .expect("read the FIFO");
        assert!(
            bytes.starts_with(magic),
            "{name}: {:?}",
            &bytes[..8.min(bytes.len())]
        );
        assert!(bytes.len() > 100, "{name}: {} bytes", bytes.len());
        let m = std::fs::symlink_metadata(&pipe).expect("still there");
        assert!(m.file_type().is_fifo(), "{name}: {:?}", m.file_type());
    }
}

/// Item 1: an output that is a link to `/dev/stdout` (here a pipe to the test) prints the
/// file on stdout; the link stays.
#[test]
fn an_output_linked_to_stdout_prints_the_file() {
    let dir = tempdir();
    let link = dir.path().join("stdout.png");
    std::os::unix::fs::symlink("/dev/stdout", &link).expect("link");
    let args = render(&link);
    let out = run(&strs(&args), "");
    checked_success(&strs(&args), &out);
    assert!(
        out.stdout.starts_with(PNG_SIGNATURE),
        "{:?}",
        &out.stdout[..8.min(out.stdout.len())]
    );
    let m = std::fs::symlink_metadata(&link).expect("still there");
    assert!(m.file_type().is_symlink(), "{:?}", m.file_type());
}

/// Item 1: a socket at `--out` is refused at once (exit 2, naming the flag), not replaced.
#[test]
fn an_output_that_is_a_socket_is_refused() {
    let dir = tempdir();
    let socket = dir.path().join("s.png");
    let _listener = std::os::unix::net::UnixListener::bind(&socket).expect("socket");
    fails(&strs(&render(&socket)), "", 2, &["--out", "socket"]);
    let m = std::fs::symlink_metadata(&socket).expect("still there");
    assert!(m.file_type().is_socket());
}

/// Item 1: an output that is a symbolic link (to a file, to a link, dangling) is followed:
/// the link stays and its final target gets the new contents.
#[test]
fn an_output_that_is_a_symlink_is_followed_and_stays() {
    let dir = tempdir();
    let target = dir.path().join("real.png");
    std::fs::write(&target, "old").expect("target");
    let link = dir.path().join("link.png");
    std::os::unix::fs::symlink("real.png", &link).expect("link");
    let chain = dir.path().join("chain.png");
    std::os::unix::fs::symlink(&link, &chain).expect("link to link");
    let dangling = dir.path().join("dangling.png");
    std::os::unix::fs::symlink("later.png", &dangling).expect("dangling");
    for (out, written) in [
        (&link, &target),
        (&chain, &target),
        (&dangling, &dir.path().join("later.png")),
    ] {
        std::fs::write(&target, "old").expect("target");
        succeeds(&strs(&render(out)), "");
        let m = std::fs::symlink_metadata(out).expect("link");
        assert!(
            m.file_type().is_symlink(),
            "{out:?} replaced by {:?}",
            m.file_type()
        );
        let bytes = std::fs::read(written).expect("target");
        assert!(bytes.starts_with(PNG_SIGNATURE), "{out:?} -> {written:?}");
    }
}

/// Item 1: a replaced file keeps its mode: private stays private (600), an executable stays
/// executable (755); a new file gets 644 less the umask.
#[test]
fn a_replaced_file_keeps_its_mode() {
    let dir = tempdir();
    for mode in [0o600, 0o755, 0o640] {
        let out = dir.path().join(format!("m{mode:o}.png"));
        std::fs::write(&out, "old").expect("file");
        std::fs::set_permissions(&out, PermissionsExt::from_mode(mode)).expect("chmod");
        succeeds(&strs(&render(&out)), "");
        let m = std::fs::metadata(&out).expect("written");
        assert_eq!(m.mode() & 0o7777, mode, "{out:?}");
        assert!(std::fs::read(&out).expect("new").starts_with(PNG_SIGNATURE));
    }
}

/// Item 1, as documented (docs/testing.md, `output_path`): the atomic rename replaces a file
/// that has other hard links by a new one; the other names keep the old contents.
#[test]
fn a_hard_linked_output_is_replaced_and_its_other_names_keep_the_old_file() {
    let dir = tempdir();
    let out = dir.path().join("a.png");
    let other = dir.path().join("b.png");
    std::fs::write(&out, "old").expect("file");
    std::fs::hard_link(&out, &other).expect("hard link");
    succeeds(&strs(&render(&out)), "");
    assert!(std::fs::read(&out).expect("new").starts_with(PNG_SIGNATURE));
    assert_eq!(std::fs::read(&other).expect("other"), b"old");
    assert_eq!(std::fs::metadata(&out).expect("new").nlink(), 1);
}

/// The atomic write's temporary files in `dir`.
fn temporaries(dir: &Path) -> Vec<PathBuf> {
    std::fs::read_dir(dir)
        .expect("dir")
        .map(|e| e.expect("entry").path())
        .filter(|p| {
            p.file_name()
                .and_then(|n| n.to_str())
                .is_some_and(|n| n.starts_with(".sky-train-"))
        })
        .collect()
}

/// Item 2: SIGTERM and SIGINT during a write leave no temporary file. A large PNG (8192 x
/// 4096 pixels) is rendered; once its temporary file shows in the folder, the signal is sent;
/// the process ends by that signal and the folder holds neither the temporary file nor the
/// output.
#[test]
fn a_signal_during_a_write_leaves_no_temporary_file() {
    for (signal, number) in [("TERM", 15), ("INT", 2)] {
        let dir = tempdir();
        let out = dir.path().join("big.png");
        // No address-space limit: the 33-Mpixel image and its PNG bytes take some 600 MB.
        let mut child = Command::new(binary())
            .args([
                "render",
                "--sun-zenith",
                "40",
                "--width",
                "8192",
                "--out",
                path(&out),
            ])
            .stdin(Stdio::null())
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .expect("sky-train runs");
        let start = Instant::now();
        let seen = loop {
            if !temporaries(dir.path()).is_empty() {
                break true;
            }
            if child.try_wait().expect("wait").is_some() || start.elapsed() > TIME_LIMIT {
                break false;
            }
            std::thread::sleep(Duration::from_millis(1));
        };
        assert!(
            seen,
            "SIG{signal}: no temporary file showed during the write"
        );
        let kill = Command::new("kill")
            .args([format!("-{signal}"), child.id().to_string()])
            .status()
            .expect("kill runs");
        assert!(kill.success());
        let status = child.wait().expect("ends");
        use std::os::unix::process::ExitStatusExt;
        assert_eq!(status.signal(), Some(number), "SIG{signal}: {status:?}");
        assert_eq!(
            temporaries(dir.path()),
            Vec::<PathBuf>::new(),
            "SIG{signal}"
        );
        assert!(!out.exists(), "SIG{signal}: a partial output");
    }
}

/// Item 2: a run that writes in a folder first removes the temporary files an earlier run
/// left there (killed outright): exactly `.sky-train-` and six letters or digits, a regular
/// file, older than the run, not locked by a live writer. Every other file stays.
#[test]
fn the_next_run_removes_temporary_files_left_in_its_folder() {
    let dir = tempdir();
    let hour_ago = SystemTime::now() - Duration::from_secs(3600);
    let file = |name: &str, modified: SystemTime| {
        let p = dir.path().join(name);
        let f = std::fs::File::create(&p).expect("file");
        f.set_modified(modified).expect("mtime");
        p
    };
    let left = file(".sky-train-Ab12Cd", hour_ago);
    let left_too = file(".sky-train-zzzzzz", hour_ago);
    let kept = [
        file(".sky-train-Ab12C", hour_ago),
        file(".sky-train-Ab12Cde", hour_ago),
        file(".sky-train-check-Ab12Cd", hour_ago),
        file(".sky-train-Ab-2Cd", hour_ago),
        file("x.sky-train-Ab12Cd", hour_ago),
        file(
            ".sky-train-Ab12Ce",
            SystemTime::now() + Duration::from_secs(3600),
        ),
    ];
    let locked = file(".sky-train-LoCkEd", hour_ago);
    let lock = std::fs::File::open(&locked).expect("open");
    rustix::fs::flock(&lock, rustix::fs::FlockOperation::LockExclusive).expect("flock");
    let folder = dir.path().join(".sky-train-folder");
    std::fs::create_dir(&folder).expect("folder");
    let sub = dir.path().join("sub");
    std::fs::create_dir(&sub).expect("sub");
    let elsewhere = sub.join(".sky-train-Ab12Cd");
    std::fs::write(&elsewhere, "").expect("file");
    std::fs::File::options()
        .write(true)
        .open(&elsewhere)
        .expect("open")
        .set_modified(hour_ago)
        .expect("mtime");

    succeeds(&strs(&render(&dir.path().join("x.png"))), "");
    assert!(!left.exists() && !left_too.exists(), "left behind");
    for p in kept.iter().chain([&locked, &folder, &elsewhere]) {
        assert!(p.exists(), "{p:?} removed");
    }
    drop(lock);
}

/// Item 4: files read through a FIFO, a device or a folder are refused at once (exit 2,
/// naming the flag and what the path is) instead of hanging or reading without end: the
/// measurement file, a style file, a weight file, and `daylight-tables --data`.
#[test]
fn files_read_that_are_not_regular_files_are_refused() {
    let dir = tempdir();
    let pipe = dir.path().join("pipe.csv");
    fifo(&pipe);
    let zero = dir.path().join("zero.csv");
    char_device(&zero, 1, 5);
    let style_pipe = dir.path().join("pipe.toml");
    fifo(&style_pipe);
    let weights = dir.path().join("zero.skyn");
    char_device(&weights, 1, 5);
    let rs = dir.path().join("t.rs");
    let cases: Vec<(Vec<&str>, Vec<&str>)> = vec![
        (
            vec![
                "schedule",
                "--lat",
                "48",
                "--lon",
                "16",
                "--measurements",
                path(&pipe),
            ],
            vec!["--measurements", "a FIFO"],
        ),
        (
            vec![
                "schedule",
                "--lat",
                "48",
                "--lon",
                "16",
                "--measurements",
                path(&zero),
            ],
            vec!["--measurements", "a character device"],
        ),
        (
            vec![
                "schedule",
                "--lat",
                "48",
                "--lon",
                "16",
                "--measurements",
                path(dir.path()),
            ],
            vec!["--measurements", "a folder"],
        ),
        (
            vec![
                "render",
                "--model",
                "aoas",
                "--sun-zenith",
                "40",
                "--style",
                path(&style_pipe),
                "--out",
                "x.png",
            ],
            vec!["--style", "a FIFO"],
        ),
        (
            vec![
                "sample",
                "--model",
                "neural",
                "--sun-zenith",
                "30",
                "--weights",
                path(&weights),
            ],
            vec![path(&weights), "a character device"],
        ),
        (
            vec!["daylight-tables", "--data", path(&pipe), "--out", path(&rs)],
            vec![path(&pipe), "a FIFO"],
        ),
    ];
    for (args, needles) in cases {
        let out = run_as(&args, "0,0\n", &[], None, Duration::from_secs(30));
        check_failure(&args, &out, 2, &needles);
    }
}

/// Item 4: `daylight-tables --data` reads lines of at most 4096 bytes and a file of at most
/// 1 MiB: a 100 kB line is refused naming the limit, and a 4 GiB file without a newline (sparse)
/// is refused from its length instead of read into one line (it used to abort, exit 134).
#[test]
fn daylight_tables_data_lines_and_files_are_bounded() {
    let dir = tempdir();
    let rs = dir.path().join("t.rs");
    let long = dir.path().join("long.csv");
    std::fs::write(
        &long,
        format!(
            "aod,sun_elevation_deg,x_lux,y_lux,z_lux,melanopic_edi_lux\n{}\n",
            "1".repeat(100_000)
        ),
    )
    .expect("long line");
    let args = ["daylight-tables", "--data", path(&long), "--out", path(&rs)];
    let out = run(&args, "");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.code().is_some(), "{stderr}");
    assert!(!out.status.success(), "{stderr}");
    assert!(stderr.contains("longer than 4096 bytes"), "{stderr}");
    assert!(stderr.contains(path(&long)), "{stderr}");

    let huge = dir.path().join("huge.csv");
    std::fs::File::create(&huge)
        .expect("file")
        .set_len(4 << 30)
        .expect("sparse 4 GiB");
    let args = ["daylight-tables", "--data", path(&huge), "--out", path(&rs)];
    let out = run(&args, "");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        out.status.code().is_some(),
        "killed: {:?} {stderr}",
        out.status
    );
    assert!(!out.status.success(), "{stderr}");
    assert!(stderr.contains("more than 1 MiB"), "{stderr}");
    assert!(!rs.exists());
}

/// The folder of the default atmosphere's cache entry: the test target's temporary folder,
/// where the workspace's other tests of the physical atmosphere (`tests/tests/physical.rs`,
/// `daylight.rs`) cache it too, so that a test run precomputes it once; precomputed here
/// (about a minute) when no test has yet. These tests only read it, and copy it elsewhere to
/// change it.
fn reference_cache() -> &'static Path {
    static DIR: std::sync::OnceLock<PathBuf> = std::sync::OnceLock::new();
    DIR.get_or_init(|| {
        let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR"));
        std::fs::create_dir_all(&dir).expect("cache folder");
        if !entry(&dir).exists() {
            let args = sample_physical(&dir);
            let out = run_as(&strs(&args), "0,0\n", &[], None, Duration::from_secs(900));
            checked_success(&strs(&args), &out);
        }
        assert!(entry(&dir).exists(), "the default atmosphere cached");
        dir
    })
}

/// The default atmosphere's entry in `dir`.
fn entry(dir: &Path) -> PathBuf {
    cache::path(dir, &Atmosphere::default(), &Resolution::default())
}

fn sample_physical(dir: &Path) -> Vec<String> {
    [
        "sample",
        "--model",
        "physical",
        "--sun-zenith",
        "30",
        "--cache-dir",
        path(dir),
    ]
    .map(String::from)
    .to_vec()
}

/// A fresh cache folder holding a copy of the default atmosphere's entry.
fn cache_with_entry() -> (tempfile::TempDir, PathBuf) {
    let dir = tempdir();
    let copy = entry(dir.path());
    std::fs::copy(entry(reference_cache()), &copy).expect("copied");
    (dir, copy)
}

/// The cache entries in `dir`.
fn entries(dir: &Path) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .expect("dir")
        .map(|e| e.expect("entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "bin"))
        .collect();
    v.sort();
    v
}

/// Items 4 and 5: a cache entry that is a FIFO (a read hung forever), a device (a link to a
/// zero device read gigabytes) or a folder (found only after the minute of precomputation) is
/// refused before any work, naming the entry, what it is and where the folder came from.
#[test]
fn a_cache_entry_that_is_not_a_file_is_refused_before_the_work() {
    for (kind, what) in [
        ("fifo", "a FIFO"),
        ("zero", "a character device"),
        ("folder", "a folder"),
    ] {
        let dir = tempdir();
        let at = entry(dir.path());
        match kind {
            "fifo" => fifo(&at),
            "zero" => {
                let zero = dir.path().join("zero");
                char_device(&zero, 1, 5);
                std::os::unix::fs::symlink(&zero, &at).expect("link");
            }
            _ => std::fs::create_dir(&at).expect("folder"),
        }
        let args = sample_physical(dir.path());
        let start = Instant::now();
        let out = run_as(&strs(&args), "0,0\n", &[], None, Duration::from_secs(30));
        check_failure(&strs(&args), &out, 2, &["--cache-dir", "cache entry", what]);
        assert!(
            start.elapsed() < Duration::from_secs(20),
            "{kind}: {:?}",
            start.elapsed()
        );
    }
}

/// The f64 values of the entry `bytes`'s first transmittance column replaced by `v`, the
/// checksum made valid again (as a cache written by a broken build, or by hand, would be).
fn with_first_column(bytes: &[u8], v: f64) -> Vec<u8> {
    // magic (8), version (4), key (8), then nr and nmu (8 each), then the columns.
    let mut body = bytes[20..bytes.len() - 8].to_vec();
    body[16..24].copy_from_slice(&v.to_le_bytes());
    let key = u64::from_le_bytes(bytes[12..20].try_into().expect("key"));
    cache::seal(&body, key)
}

/// Item 5: a cache file whose checksum is valid but which holds a NaN is not used: it is
/// rebuilt (with a note on stderr), and the sky sampled is finite and the same as from the
/// good file.
#[test]
fn a_cache_file_with_nan_values_is_rebuilt() {
    let (dir, copy) = cache_with_entry();
    let args = sample_physical(dir.path());
    let good = run(&strs(&args), "0,0\n10,20\n");
    checked_success(&strs(&args), &good);
    let bytes = std::fs::read(&copy).expect("entry");
    std::fs::write(&copy, with_first_column(&bytes, f64::NAN)).expect("poisoned");
    let out = run_as(
        &strs(&args),
        "0,0\n10,20\n",
        &[],
        None,
        Duration::from_secs(900),
    );
    let stderr = checked_success(&strs(&args), &out);
    assert!(
        stderr.contains("not usable") && stderr.contains("column density"),
        "{stderr}"
    );
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(!text.to_lowercase().contains("nan"), "{text}");
    assert_eq!(out.stdout, good.stdout, "the rebuilt atmosphere's sky");
    assert_eq!(
        std::fs::read(&copy).expect("rebuilt"),
        bytes,
        "the entry rebuilt as it was"
    );
}

/// Item 5: `--aod -0` and `--aod 1e-320` are the atmosphere of `--aod 0`, and one cache entry:
/// with the entry of `--aod 0` present, neither precomputes or writes another.
#[test]
fn aerosol_depths_that_are_zero_share_one_cache_entry() {
    let dir = tempdir();
    // The default atmosphere's tables under the key of `--aod 0` (which cache entry is used is
    // what is tested; the tables' values do not matter here).
    let zero = Atmosphere {
        aod_550: 0.0,
        ..Atmosphere::default()
    };
    let bytes = std::fs::read(entry(reference_cache())).expect("entry");
    let key = cache::version_key(&zero, &Resolution::default());
    let at = cache::path(dir.path(), &zero, &Resolution::default());
    std::fs::write(&at, cache::seal(&bytes[20..bytes.len() - 8], key)).expect("entry");
    for aod in ["0", "-0", "1e-320", "5e-10", "0.0000000000"] {
        let mut args = sample_physical(dir.path());
        args.push(format!("--aod={aod}"));
        let out = run_as(&strs(&args), "0,0\n", &[], None, Duration::from_secs(60));
        checked_success(&strs(&args), &out);
        assert_eq!(entries(dir.path()), vec![at.clone()], "--aod {aod}");
    }
}

/// Item 5: the cache folder is capped at 1 GiB (`cache::MAX_CACHE_BYTES`): when it holds
/// more, the least recently used entries are removed until the rest fit; the entry in use and
/// files that are not entries stay. Sparse files of 400 MiB stand for old entries.
#[test]
fn the_cache_folder_is_capped_by_evicting_the_least_recently_used() {
    assert_eq!(cache::MAX_CACHE_BYTES, 1 << 30);
    let (dir, copy) = cache_with_entry();
    let old = |hex: &str, hours: u64| {
        let p = dir.path().join(format!("physical-{hex}.bin"));
        let f = std::fs::File::create(&p).expect("file");
        f.set_len(400 << 20).expect("sparse");
        f.set_modified(SystemTime::now() - Duration::from_secs(3600 * hours))
            .expect("mtime");
        p
    };
    let oldest = old("000000000000000a", 3);
    let middle = old("000000000000000b", 2);
    let newest = old("000000000000000c", 1);
    let not_an_entry = dir.path().join("physical-notes.bin");
    std::fs::File::create(&not_an_entry)
        .expect("file")
        .set_len(400 << 20)
        .expect("sparse");
    // The entry in use was used longest ago of all, yet stays.
    std::fs::File::options()
        .write(true)
        .open(&copy)
        .expect("entry")
        .set_modified(SystemTime::now() - Duration::from_secs(3600 * 24))
        .expect("mtime");
    succeeds(&strs(&sample_physical(dir.path())), "0,0\n");
    // 3 x 400 MiB + ~50 MB is over 1 GiB; without the oldest, 800 MiB + ~50 MB fits.
    assert!(!oldest.exists(), "the least recently used entry stays");
    assert!(middle.exists() && newest.exists() && copy.exists() && not_an_entry.exists());
    let used = std::fs::metadata(&copy)
        .expect("entry")
        .modified()
        .expect("mtime");
    assert!(
        used > SystemTime::now() - Duration::from_secs(600),
        "use renews the entry"
    );
}

/// Item 5: a cache folder that can be read but not written, and holds the atmosphere, is used
/// (run as the unprivileged user 65534, for whom the folder's mode 555 holds: root ignores it).
#[test]
fn a_read_only_cache_folder_that_holds_the_atmosphere_is_used() {
    let (dir, copy) = cache_with_entry();
    std::fs::set_permissions(&copy, PermissionsExt::from_mode(0o444)).expect("chmod");
    std::fs::set_permissions(dir.path(), PermissionsExt::from_mode(0o555)).expect("chmod");
    let args = sample_physical(dir.path());
    let out = run_as(
        &strs(&args),
        "0,0\n",
        &[],
        Some(65534),
        Duration::from_secs(60),
    );
    let stderr = checked_success(&strs(&args), &out);
    assert!(!stderr.contains("precomputing"), "{stderr}");
    assert_eq!(entries(dir.path()), vec![copy]);
    // A folder that cannot be written and lacks the atmosphere is refused before the work,
    // naming where its path came from.
    let empty = tempdir();
    std::fs::set_permissions(empty.path(), PermissionsExt::from_mode(0o555)).expect("chmod");
    let args = ["sample", "--model", "physical", "--sun-zenith", "30"];
    let env = [("SKY_TRAIN_CACHE_DIR", path(empty.path()))];
    let out = run_as(&args, "0,0\n", &env, Some(65534), Duration::from_secs(30));
    check_failure(
        &args,
        &out,
        2,
        &["$SKY_TRAIN_CACHE_DIR", path(empty.path()), "cannot write"],
    );
}

/// Item 5: messages about the cache folder name where its path came from.
#[test]
fn cache_folder_messages_name_where_the_path_came_from() {
    let dir = tempdir();
    let plain = dir.path().join("plain");
    std::fs::write(&plain, "x").expect("file");
    let inside = plain.join("cache");
    let args = ["sample", "--model", "physical", "--sun-zenith", "30"];
    let env = [("SKY_TRAIN_CACHE_DIR", path(&inside))];
    let out = run_as(&args, "0,0\n", &env, None, Duration::from_secs(30));
    check_failure(&args, &out, 2, &["$SKY_TRAIN_CACHE_DIR", "not a folder"]);
    let mut flagged: Vec<&str> = args.to_vec();
    flagged.extend(["--cache-dir", path(&inside)]);
    let out = run_as(&flagged, "0,0\n", &env, None, Duration::from_secs(30));
    check_failure(&flagged, &out, 2, &["--cache-dir", "not a folder"]);
}
