//! Output paths checked before the work starts: every subcommand that writes files checks each
//! of them first (the folder exists, or can be created, and takes new files; a file's path is
//! not a folder), so that a bad path is refused at once with exit status 2 instead of after a
//! training or a precomputation.
//!
//! Whether a folder takes new files is found out by creating and removing a temporary file in
//! it, as the atomic write will ([`write_atomically`]): permissions, read-only mounts, ACLs and
//! a full inode table all show, as they would at the end.
//!
//! # The atomic write
//!
//! [`write_atomically`] writes into a hidden temporary file `.sky-train-XXXXXX` (six random
//! letters and digits) beside the output, then renames it into place, so that readers see the
//! old file or the whole new one, never a part. What is at the output path decides how:
//!
//! - nothing, or a regular file: the atomic write. A replaced file keeps its permission bits
//!   (a mode-600 file stays private, an executable stays executable) and, where the process
//!   may set them (as root), its owner and group. A file with other hard links is replaced by
//!   a new file at this name: the other names keep the old contents (the rename cannot keep a
//!   link, and writing in place would lose the atomicity).
//! - a symbolic link: followed (links to links too); the new file is made beside the link's
//!   final target and renamed over it, so the link stays and points at the new contents.
//! - a character or block device or a FIFO: written directly, never replaced (`--out
//!   /dev/null` discards the output, `--out /dev/stdout` prints it, a FIFO's reader gets it);
//!   an OpenEXR file, whose encoder seeks, is encoded in memory first.
//! - a socket: refused, naming the flag (it cannot be opened as a file).
//!
//! A temporary file is removed when the write fails, and on SIGINT, SIGTERM or SIGHUP during
//! the write ([`remove_temporaries_on_signals`], called by the binary at its start, then the
//! process ends by the signal as it would have). One left by a process killed outright
//! (SIGKILL, a power cut) is removed by the next run that writes in the same folder: a regular
//! file whose name is exactly `.sky-train-` and six letters or digits, last modified before
//! that run started, and not locked by a live writer (each writer holds an exclusive `flock`
//! on its temporary file).

use std::collections::HashSet;
use std::fs::File;
use std::io::ErrorKind;
use std::path::{Path, PathBuf};
use std::sync::{Mutex, OnceLock, PoisonError};
use std::time::SystemTime;

use anyhow::{Context, Result, bail};

use crate::args::ParamError;

/// The prefix of the atomic write's temporary files; six random letters and digits follow.
pub const TEMPORARY_PREFIX: &str = ".sky-train-";

/// The most symbolic links followed from an output path (as the kernel's `ELOOP` limit).
const MAX_LINKS: usize = 40;

/// Where a write to `path` lands: `path` with its symbolic links followed to the final
/// target (which need not exist: a dangling link's target is created).
///
/// # Errors
/// A link that cannot be read, or more than 40 links in a row.
pub fn resolve(path: &Path) -> std::io::Result<PathBuf> {
    let mut p = path.to_path_buf();
    for _ in 0..MAX_LINKS {
        match std::fs::symlink_metadata(&p) {
            Ok(m) if m.file_type().is_symlink() => {
                let target = std::fs::read_link(&p)?;
                p = if target.is_absolute() {
                    target
                } else {
                    parent(&p).join(target)
                };
            }
            _ => return Ok(p),
        }
    }
    Err(std::io::Error::other(format!(
        "more than {MAX_LINKS} symbolic links in a row"
    )))
}

/// The temporary files being written now, removed by the signal handler.
static TEMPORARIES: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// When this run started (set by [`remove_temporaries_on_signals`]); the sweep of leftover
/// temporary files only runs once it is set.
static RUN_START: OnceLock<SystemTime> = OnceLock::new();

/// The folders already swept in this run.
static SWEPT: Mutex<Option<HashSet<PathBuf>>> = Mutex::new(None);

/// Notes the run's start and installs handlers of SIGINT, SIGTERM and SIGHUP that remove the
/// atomic write's temporary files being written, then end the process by the same signal (as
/// its default action would have: the exit status still says which signal). Called once by
/// the binary at its start.
///
/// # Errors
/// When the handlers cannot be installed.
pub fn remove_temporaries_on_signals() -> std::io::Result<()> {
    use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};
    let _ = RUN_START.set(SystemTime::now());
    let mut signals = signal_hook::iterator::Signals::new([SIGINT, SIGTERM, SIGHUP])?;
    std::thread::Builder::new()
        .name("signal cleanup".into())
        .spawn(move || {
            if let Some(signal) = signals.forever().next() {
                // Held until the end: no new temporary file is made meanwhile.
                let temporaries = TEMPORARIES.lock().unwrap_or_else(PoisonError::into_inner);
                for t in temporaries.iter() {
                    let _ = std::fs::remove_file(t);
                }
                let _ = signal_hook::low_level::emulate_default_handler(signal);
                // Only reached for a signal whose default action does not end the process.
                std::process::exit(128 + signal);
            }
        })?;
    Ok(())
}

/// Whether `name` is one of the atomic write's temporary files: `.sky-train-` and exactly
/// six ASCII letters or digits.
fn is_temporary_name(name: &std::ffi::OsStr) -> bool {
    name.to_str()
        .and_then(|n| n.strip_prefix(TEMPORARY_PREFIX))
        .is_some_and(|rest| rest.len() == 6 && rest.bytes().all(|b| b.is_ascii_alphanumeric()))
}

/// Removes from `dir` the temporary files that an earlier run left (see the module docs),
/// once per folder and run; nothing before the run's start is known.
pub fn sweep_temporaries(dir: &Path) {
    let Some(&start) = RUN_START.get() else {
        return;
    };
    {
        let mut swept = SWEPT.lock().unwrap_or_else(PoisonError::into_inner);
        if !swept
            .get_or_insert_with(HashSet::new)
            .insert(dir.to_path_buf())
        {
            return;
        }
    }
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        if !is_temporary_name(&entry.file_name()) {
            continue;
        }
        let path = entry.path();
        let old = std::fs::symlink_metadata(&path)
            .is_ok_and(|m| m.is_file() && m.modified().is_ok_and(|t| t < start));
        // A live writer holds an exclusive lock on its file.
        let unlocked = || {
            File::open(&path).is_ok_and(|f| {
                rustix::fs::flock(&f, rustix::fs::FlockOperation::NonBlockingLockExclusive).is_ok()
            })
        };
        if old && unlocked() {
            let _ = std::fs::remove_file(&path);
        }
    }
}

/// A temporary file beside the output: removed when dropped before it is persisted, and on the
/// signals of [`remove_temporaries_on_signals`] meanwhile.
struct Temporary {
    /// The file, until it is persisted.
    file: Option<tempfile::NamedTempFile>,
    /// Its path, as registered.
    path: PathBuf,
}

impl Temporary {
    /// A new temporary file in `dir`, registered for removal on a signal and locked against
    /// another run's sweep.
    fn new(dir: &Path) -> std::io::Result<Self> {
        let mut builder = tempfile::Builder::new();
        builder.prefix(TEMPORARY_PREFIX);
        // Temporary files are private (0600); the finished file gets the usual 0644 (less
        // umask), or the replaced file's mode.
        builder.permissions(std::os::unix::fs::PermissionsExt::from_mode(0o644));
        let mut temporaries = TEMPORARIES.lock().unwrap_or_else(PoisonError::into_inner);
        let file = builder.tempfile_in(dir)?;
        let path = file.path().to_path_buf();
        temporaries.push(path.clone());
        drop(temporaries);
        let tmp = Self {
            file: Some(file),
            path,
        };
        rustix::fs::flock(tmp.file(), rustix::fs::FlockOperation::LockExclusive)?;
        Ok(tmp)
    }

    /// The open file.
    fn file(&self) -> &File {
        self.file
            .as_ref()
            .map_or_else(|| unreachable!("persisted"), |f| f.as_file())
    }

    /// Renames the file to `target` (on failure it is removed when `self` drops).
    fn persist(mut self, target: &Path) -> std::io::Result<()> {
        match self.file.take() {
            Some(f) => f.persist(target).map(drop).map_err(|e| e.error),
            None => Ok(()),
        }
    }
}

impl Drop for Temporary {
    fn drop(&mut self) {
        // Removed first (when not persisted), then forgotten.
        drop(self.file.take());
        let mut temporaries = TEMPORARIES.lock().unwrap_or_else(PoisonError::into_inner);
        temporaries.retain(|t| *t != self.path);
    }
}

/// Writes a file through `write` to `path` as the module docs say: atomically (a temporary
/// file beside it, then a rename) for a new or regular file, keeping a replaced file's mode;
/// through a symbolic link to its target; directly to a device or FIFO.
///
/// # Errors
/// Any I/O error, with the path in its context; a socket; the temporary file is removed on
/// failure.
pub fn write_atomically(path: &Path, write: impl FnOnce(&mut File) -> Result<()>) -> Result<()> {
    // What the path names, links followed by the kernel (which also follows the magic links
    // of /proc: `/dev/stdout` to a pipe is no path that `resolve` could name).
    let existing = match std::fs::metadata(path) {
        Ok(m) => Some(m),
        Err(e) if e.kind() == ErrorKind::NotFound => None,
        Err(e) => return Err(e).with_context(|| format!("cannot write {}", path.display())),
    };
    if let Some(m) = &existing
        && !m.is_file()
    {
        return write_directly(path, m, write);
    }
    let target =
        resolve(path).with_context(|| format!("cannot follow the link {}", path.display()))?;
    let dir = parent(&target);
    sweep_temporaries(&dir);
    let tmp = Temporary::new(&dir)
        .with_context(|| format!("cannot create a temporary file in {}", dir.display()))?;
    if let Some(m) = &existing {
        use std::os::unix::fs::MetadataExt;
        let file = tmp.file();
        // The owner first: changing it may clear set-user-ID bits that the mode then restores.
        let _ = std::os::unix::fs::fchown(file, Some(m.uid()), Some(m.gid()));
        file.set_permissions(m.permissions())
            .with_context(|| format!("cannot keep the mode of {}", path.display()))?;
    }
    let mut file = tmp.file().try_clone()?;
    write(&mut file).with_context(|| format!("cannot write {}", path.display()))?;
    file.sync_all()
        .with_context(|| format!("cannot write {}", path.display()))?;
    tmp.persist(&target)
        .with_context(|| format!("cannot move the finished file to {}", path.display()))?;
    Ok(())
}

/// Writes through `write` to the device or FIFO at `path` (links followed), in place.
fn write_directly(
    path: &Path,
    meta: &std::fs::Metadata,
    write: impl FnOnce(&mut File) -> Result<()>,
) -> Result<()> {
    use std::os::unix::fs::FileTypeExt;
    let kind = meta.file_type();
    if kind.is_dir() {
        bail!("{}: is a folder, not a file", path.display());
    }
    if kind.is_socket() {
        bail!(
            "{}: is a socket, which cannot be written as a file",
            path.display()
        );
    }
    let mut file = File::options()
        .write(true)
        .open(path)
        .with_context(|| format!("cannot open {} for writing", path.display()))?;
    write(&mut file).with_context(|| format!("cannot write {}", path.display()))?;
    std::io::Write::flush(&mut file).with_context(|| format!("cannot write {}", path.display()))?;
    Ok(())
}

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
    use std::os::unix::fs::FileTypeExt;
    if path.is_dir() {
        return Err(ParamError(format!(
            "{flag} {}: is a folder, not a file",
            path.display()
        )));
    }
    if let Ok(m) = std::fs::metadata(path)
        && !m.is_file()
    {
        // A device or a FIFO is written directly, with no temporary file.
        if m.file_type().is_socket() {
            return Err(ParamError(format!(
                "{flag} {}: is a socket, which cannot be written as a file",
                path.display()
            )));
        }
        return Ok(());
    }
    let target =
        resolve(path).map_err(|e| ParamError(format!("{flag} {}: {e}", path.display())))?;
    let parent = parent(&target);
    sweep_temporaries(&parent);
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
        // A link is checked where it points: at a folder, refused; at a new file, taken.
        let to_dir = dir.path().join("to-dir.png");
        std::os::unix::fs::symlink(dir.path().join("new"), &to_dir).expect("link");
        std::fs::create_dir(dir.path().join("new")).expect("folder");
        assert!(
            message(file("--out", &to_dir, Folder::Existing)).ends_with("is a folder, not a file")
        );
        std::fs::remove_dir(dir.path().join("new")).expect("removed");
        assert_eq!(resolve(&to_dir).expect("resolved"), dir.path().join("new"));
        std::fs::remove_file(&to_dir).expect("removed");
        // The probe leaves nothing behind.
        let left: Vec<_> = std::fs::read_dir(dir.path()).expect("dir").collect();
        assert_eq!(left.len(), 1, "{left:?}");
    }

    #[test]
    fn only_our_temporary_names_count() {
        for (name, ours) in [
            (".sky-train-Ab12Cd", true),
            (".sky-train-000000", true),
            (".sky-train-Ab12C", false),
            (".sky-train-Ab12Cde", false),
            (".sky-train-check-Ab12Cd", false),
            (".sky-train-cache", false),
            (".sky-train-Ab-2Cd", false),
            ("x.sky-train-Ab12Cd", false),
        ] {
            assert_eq!(
                is_temporary_name(std::ffi::OsStr::new(name)),
                ours,
                "{name}"
            );
        }
    }
}
