//! Helpers shared by the hostile-input tests (`hostile*.rs`): each runs the `sky-train` binary
//! as a user would, under a 1 GiB address-space limit (`prlimit --as`), so that an allocation
//! beyond what a command states it needs fails the test instead of the machine.
//!
//! The binary is this build's, or `$SKY_TRAIN_UNDER_TEST`: so a case can be run against the
//! build before its fix, to see it fail there.

// Each test file is its own crate and uses a part of these.
#![allow(dead_code)]

use std::io::Write;
use std::path::Path;
use std::process::{Command, Output, Stdio};

/// The address space the binary may use: the largest frame (384 MiB) and its working arrays
/// fit; the 1.5 GiB and 24 GiB frames the cases' headers claim do not.
pub(crate) const ADDRESS_SPACE: &str = "--as=1073741824";

/// The binary under test: this build's, or `$SKY_TRAIN_UNDER_TEST`.
pub(crate) fn binary() -> std::ffi::OsString {
    std::env::var_os("SKY_TRAIN_UNDER_TEST")
        .unwrap_or_else(|| env!("CARGO_BIN_EXE_sky-train").into())
}

/// `sky-train args` under [`ADDRESS_SPACE`], stdin and stderr piped, stdout as given.
pub(crate) fn command(args: &[&str], stdout: Stdio) -> Command {
    let mut c = Command::new("prlimit");
    c.arg(ADDRESS_SPACE)
        .arg(binary())
        .args(args)
        .stdin(Stdio::piped())
        .stdout(stdout)
        .stderr(Stdio::piped());
    c
}

/// Starts `sky-train args` under [`ADDRESS_SPACE`], its stdin, stdout and stderr piped.
pub(crate) fn spawn(args: &[&str]) -> std::process::Child {
    command(args, Stdio::piped())
        .spawn()
        .expect("prlimit and sky-train run")
}

/// Runs `sky-train args` with `stdin` under [`ADDRESS_SPACE`].
pub(crate) fn sky_train(args: &[&str], stdin: &str) -> Output {
    let mut child = spawn(args);
    // A command that refuses its arguments may end before it reads stdin.
    let written = child
        .stdin
        .take()
        .expect("stdin")
        .write_all(stdin.as_bytes());
    if let Err(e) = written {
        assert_eq!(e.kind(), std::io::ErrorKind::BrokenPipe, "stdin written");
    }
    child.wait_with_output().expect("sky-train ends")
}

/// Asserts `args` succeed; returns stdout.
pub(crate) fn succeeds(args: &[&str], stdin: &str) -> String {
    let out = sky_train(args, stdin);
    assert!(
        out.status.success(),
        "{args:?}: {:?} {}",
        out.status,
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).expect("UTF-8")
}

/// Asserts that `out` of `args` is a failure with an exit status (not a signal: no abort, no
/// panic) and one stderr line holding every `needle`; returns the status and that line.
pub(crate) fn failure(args: &[&str], out: &Output, needles: &[&str]) -> (i32, String) {
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    let code = out
        .status
        .code()
        .unwrap_or_else(|| panic!("{args:?} was killed ({:?}): {stderr}", out.status));
    assert!(code != 0 && code != 101, "{args:?}: exit {code}: {stderr}");
    assert_eq!(stderr.trim_end().lines().count(), 1, "{args:?}: `{stderr}`");
    for needle in needles {
        assert!(
            stderr.contains(needle),
            "{args:?}: `{stderr}` lacks `{needle}`"
        );
    }
    (code, stderr)
}

/// Runs `args` with `stdin` and asserts its [`failure`]; returns the status.
pub(crate) fn fails(args: &[&str], stdin: &str, needles: &[&str]) -> i32 {
    failure(args, &sky_train(args, stdin), needles).0
}

pub(crate) fn path(p: &Path) -> &str {
    p.to_str().expect("UTF-8 path")
}

pub(crate) fn strs(v: &[String]) -> Vec<&str> {
    v.iter().map(String::as_str).collect()
}
