//! Output paths checked before the work starts: every subcommand that writes files checks each
//! of them first (the folder exists, or can be created, and takes new files; a file's path is
//! not a folder), so that a bad path is refused at once with exit status 2 instead of after a
//! training or a precomputation.
//!
//! Whether a folder takes new files is found out by creating and removing a temporary file in
//! it, as the atomic write will ([`crate::image_io::write_atomically`]): permissions, read-only
//! mounts, ACLs and a full inode table all show, as they would at the end.

use std::io::ErrorKind;
use std::path::{Path, PathBuf};

use crate::args::ParamError;

/// Where a file's folder comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Folder {
    /// The folder must exist.
    Existing,
    /// The folder is created when missing (its nearest existing ancestor must take new
    /// folders).
    Created,
}

/// Checks that `path`, the value of `flag`, can be written as a file: it is not a folder, and
/// its folder takes new files (or, with [`Folder::Created`], can be created).
///
/// # Errors
/// A [`ParamError`] naming `flag`, the path and what is wrong.
pub fn file(flag: &str, path: &Path, folder: Folder) -> Result<(), ParamError> {
    if path.is_dir() {
        return Err(ParamError(format!(
            "{flag} {}: is a folder, not a file",
            path.display()
        )));
    }
    let parent = parent(path);
    match folder {
        Folder::Existing if !parent.exists() => Err(ParamError(format!(
            "{flag} {}: the folder {} does not exist",
            path.display(),
            parent.display()
        ))),
        _ => writable(flag, path, &parent),
    }
}

/// Checks that `path`, the value of `flag`, can be written as a file whose name ends in one
/// of `extensions` (without the dot, any case), in a folder that exists.
///
/// # Errors
/// As [`file()`], and a [`ParamError`] listing the extensions.
pub fn file_ending(flag: &str, path: &Path, extensions: &[&str]) -> Result<(), ParamError> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    if !extensions.iter().any(|e| ext.as_deref() == Some(*e)) {
        let names: Vec<String> = extensions.iter().map(|e| format!(".{e}")).collect();
        return Err(ParamError(format!(
            "{flag} {}: the file name must end in {}",
            path.display(),
            names.join(" or ")
        )));
    }
    file(flag, path, Folder::Existing)
}

/// Checks that `dir`, the value of `flag`, can be an output folder: a folder that takes new
/// files, or a path that can be created as one (its nearest existing ancestor is a folder that
/// takes new folders). Nothing is created.
///
/// # Errors
/// A [`ParamError`] naming `flag`, the path and what is wrong.
pub fn folder(flag: &str, dir: &Path) -> Result<(), ParamError> {
    writable(flag, dir, dir)
}

/// The folder a file is written in.
fn parent(path: &Path) -> PathBuf {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

/// Checks that `dir` (for the value `shown` of `flag`), or its nearest existing ancestor when
/// it does not exist yet, is a folder that takes new files.
fn writable(flag: &str, shown: &Path, dir: &Path) -> Result<(), ParamError> {
    let err = |what: String| ParamError(format!("{flag} {}: {what}", shown.display()));
    let existing = dir
        .ancestors()
        .filter(|a| !a.as_os_str().is_empty())
        .find(|a| a.exists())
        .unwrap_or(Path::new("."));
    if !existing.is_dir() {
        return Err(err(format!("{} is not a folder", existing.display())));
    }
    tempfile::Builder::new()
        .prefix(".sky-train-check-")
        .tempfile_in(existing)
        .map(drop)
        .map_err(|e| {
            let why = match e.kind() {
                ErrorKind::PermissionDenied => "permission denied".to_string(),
                _ => e.to_string(),
            };
            err(format!("cannot write in {} ({why})", existing.display()))
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paths_that_cannot_be_written_are_named() {
        let dir = tempfile::tempdir().expect("temp dir");
        let plain = dir.path().join("plain");
        std::fs::write(&plain, "x").expect("file");
        let message = |r: Result<(), ParamError>| r.expect_err("refused").0;

        let missing = dir.path().join("missing/x.skyn");
        let e = message(file("--out", &missing, Folder::Existing));
        assert!(
            e.starts_with("--out ") && e.ends_with("missing does not exist"),
            "{e}"
        );
        assert!(file("--out", &missing, Folder::Created).is_ok());
        let e = message(file("--out", dir.path(), Folder::Existing));
        assert!(e.ends_with("is a folder, not a file"), "{e}");
        let e = message(file("--out", &plain.join("x.skyn"), Folder::Created));
        assert!(e.ends_with("plain is not a folder"), "{e}");
        let e = message(folder("--out", &plain.join("a/b")));
        assert!(e.ends_with("plain is not a folder"), "{e}");
        let e = message(file_ending("--out", &dir.path().join("x.jpg"), &["png"]));
        assert!(e.ends_with("must end in .png"), "{e}");

        assert!(file("--out", &plain, Folder::Existing).is_ok(), "replaced");
        assert!(file("--out", Path::new("x.skyn"), Folder::Existing).is_ok());
        assert!(folder("--out", &dir.path().join("new/deeper")).is_ok());
        assert!(!dir.path().join("new").exists(), "nothing created");
        assert!(file_ending("--out", &dir.path().join("s.PNG"), &["png"]).is_ok());
        // The probe leaves nothing behind.
        let left: Vec<_> = std::fs::read_dir(dir.path()).expect("dir").collect();
        assert_eq!(left.len(), 1, "{left:?}");
    }
}
