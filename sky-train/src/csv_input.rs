//! Two-column CSV on stdin (`sample`'s view directions, `cct`'s chromaticities), read by one
//! parser for every command; and the one bounded reader of every file the project reads
//! ([`open`], [`read_text`], [`read_lines`]).
//!
//! Every file read is first checked to be a regular file (symbolic links followed: a folder, a
//! FIFO, a device or a socket is refused before it is opened for reading, so that a FIFO cannot
//! hang the process and `/dev/zero` cannot fill its memory), then read through a
//! [`BoundedFile`] that fails once more than the limit for its kind has been read (so a file
//! that grows while it is read is stopped too). Text is read in lines of at most
//! [`MAX_LINE_BYTES`].
//!
//! A line is two comma-separated numbers; blank lines are skipped. The first line may instead
//! be a header: exactly the two column names (case and surrounding spaces aside), so that a
//! mistyped first row (`NaN,0`, `0.31.27,0.3290`) is an error like on any other line, never
//! taken for a header. A UTF-8 byte-order mark before the first line is an encoding mark and
//! is dropped. Numbers must be finite. Lines are at most [`MAX_LINE_BYTES`] long; the rows are
//! an iterator, so a command can work through any number of them in bounded memory.

use std::fs::File;
use std::io::{BufRead, Read, Seek};
use std::path::Path;

use crate::args::ParamError;

/// What kind of thing a file that is not a regular file is, for messages.
fn kind_of(file_type: std::fs::FileType) -> &'static str {
    use std::os::unix::fs::FileTypeExt;
    if file_type.is_dir() {
        "a folder"
    } else if file_type.is_fifo() {
        "a FIFO"
    } else if file_type.is_char_device() {
        "a character device"
    } else if file_type.is_block_device() {
        "a block device"
    } else if file_type.is_socket() {
        "a socket"
    } else {
        "not a regular file"
    }
}

/// The bytes shown in a message: `64 MiB` for whole MiB, else the count.
fn shown_bytes(n: u64) -> String {
    if n >= 1 << 20 && n.is_multiple_of(1 << 20) {
        format!("{} MiB", n >> 20)
    } else {
        format!("{n} bytes")
    }
}

/// A regular file open for reading that fails a read once more than its limit has been read
/// from it (made by [`open`]).
#[derive(Debug)]
pub struct BoundedFile {
    file: File,
    limit: u64,
    at: u64,
}

impl BoundedFile {
    /// The limit, in bytes.
    #[must_use]
    pub fn limit(&self) -> u64 {
        self.limit
    }

    fn too_long(&self) -> std::io::Error {
        std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            format!(
                "longer than {}, the largest file of its kind read",
                shown_bytes(self.limit)
            ),
        )
    }
}

impl Read for BoundedFile {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        if self.at > self.limit {
            return Err(self.too_long());
        }
        // One byte past the limit is asked for, so that a longer file shows.
        let room = usize::try_from(self.limit - self.at + 1).unwrap_or(usize::MAX);
        let n = buf.len().min(room);
        let got = self.file.read(&mut buf[..n])?;
        self.at += got as u64;
        if self.at > self.limit {
            return Err(self.too_long());
        }
        Ok(got)
    }
}

impl Seek for BoundedFile {
    fn seek(&mut self, pos: std::io::SeekFrom) -> std::io::Result<u64> {
        self.at = self.file.seek(pos)?;
        Ok(self.at)
    }
}

/// Opens `path` for reading at most `max_bytes` from it: it must be a regular file (symbolic
/// links followed), checked before it is opened and again on the open file, and not longer
/// than `max_bytes` by its length (then by what is read, see [`BoundedFile`]).
///
/// # Errors
/// An I/O error whose message says what is wrong (`is a FIFO, not a regular file`, `is 80 MiB
/// long, more than 64 MiB ...`), without the path: callers name the file and its flag.
pub fn open(path: &Path, max_bytes: u64) -> std::io::Result<BoundedFile> {
    use std::os::unix::fs::OpenOptionsExt;
    let not_regular = |t: std::fs::FileType| {
        std::io::Error::new(
            std::io::ErrorKind::InvalidInput,
            format!("is {}, not a regular file", kind_of(t)),
        )
    };
    let meta = std::fs::metadata(path)?;
    if !meta.is_file() {
        return Err(not_regular(meta.file_type()));
    }
    // Non-blocking, in case the path was swapped for a FIFO after the check: the open does not
    // wait for a writer, and the check on the open file below refuses it.
    #[allow(clippy::cast_possible_wrap)] // a flag bit
    let file = File::options()
        .read(true)
        .custom_flags(rustix::fs::OFlags::NONBLOCK.bits() as i32)
        .open(path)?;
    let meta = file.metadata()?;
    if !meta.is_file() {
        return Err(not_regular(meta.file_type()));
    }
    if meta.len() > max_bytes {
        return Err(std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            format!(
                "is {} long, more than {}, the largest file of its kind read",
                shown_bytes(meta.len()),
                shown_bytes(max_bytes)
            ),
        ));
    }
    Ok(BoundedFile {
        file,
        limit: max_bytes,
        at: 0,
    })
}

/// Reads the text file `path` whole through [`open`] (at most `max_bytes`), with every line at
/// most [`MAX_LINE_BYTES`] long.
///
/// # Errors
/// A [`ParamError`] starting with `source` (the flag and the file, e.g. `--style s.toml`):
/// the file cannot be opened, is not a regular file, is too long, is not UTF-8 or has a line
/// longer than [`MAX_LINE_BYTES`] (named by its number).
pub fn read_text(path: &Path, source: &str, max_bytes: u64) -> Result<String, ParamError> {
    let mut text = String::new();
    open(path, max_bytes)
        .and_then(|mut f| f.read_to_string(&mut text))
        .map_err(|e| ParamError(format!("{source}: {e}")))?;
    for (n, line) in text.split('\n').enumerate() {
        if line.len() > MAX_LINE_BYTES {
            return Err(ParamError(format!(
                "{source} line {}: the line is longer than {MAX_LINE_BYTES} bytes",
                n + 1
            )));
        }
    }
    Ok(text)
}

/// The lines of the text file `path` (read through [`open`], at most `max_bytes`), as
/// [`BufRead::lines`] gives them (line ends removed) but each at most [`MAX_LINE_BYTES`] long:
/// a longer line is an error at once, never a growing allocation.
///
/// # Errors
/// When the file cannot be opened or is not a regular file; each line is an error when it
/// cannot be read, the file is too long, the line is too long or not UTF-8.
pub fn read_lines(
    path: &Path,
    max_bytes: u64,
) -> std::io::Result<impl Iterator<Item = std::io::Result<String>>> {
    let mut input = std::io::BufReader::new(open(path, max_bytes)?);
    let mut buf = Vec::new();
    let mut failed = false;
    Ok(std::iter::from_fn(move || {
        if failed {
            return None;
        }
        buf.clear();
        let line = match (&mut input)
            .take(MAX_LINE_BYTES as u64 + 2)
            .read_until(b'\n', &mut buf)
        {
            Ok(0) => return None,
            Ok(_) => {
                if buf.last() == Some(&b'\n') {
                    buf.pop();
                    if buf.last() == Some(&b'\r') {
                        buf.pop();
                    }
                }
                if buf.len() > MAX_LINE_BYTES {
                    Err(std::io::Error::new(
                        std::io::ErrorKind::InvalidData,
                        format!("a line is longer than {MAX_LINE_BYTES} bytes"),
                    ))
                } else {
                    String::from_utf8(std::mem::take(&mut buf)).map_err(|_| {
                        std::io::Error::new(
                            std::io::ErrorKind::InvalidData,
                            "a line is not UTF-8 text",
                        )
                    })
                }
            }
            Err(e) => Err(e),
        };
        failed = line.is_err();
        Some(line)
    }))
}

/// The longest line read, in bytes (a line of two numbers needs far less; the limit keeps a
/// stream without newlines from growing a line without end).
pub const MAX_LINE_BYTES: usize = 4096;

/// One data line.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    /// Its 1-based line number.
    pub line: usize,
    /// The two fields as written (trimmed).
    pub text: [String; 2],
    /// The two fields' values, finite.
    pub values: [f64; 2],
}

/// The non-blank lines of a CSV input, trimmed, each with its 1-based number: a byte-order
/// mark before the first is dropped, a line longer than [`MAX_LINE_BYTES`] or not UTF-8 is an
/// error naming the input (`stdin`, `--measurements FILE`) and the line.
pub struct Lines<'a> {
    input: &'a mut dyn BufRead,
    source: String,
    line: usize,
    buf: Vec<u8>,
}

/// The lines of `input`, named `source` in errors (see [`Lines`]).
pub fn lines<'a>(input: &'a mut dyn BufRead, source: impl Into<String>) -> Lines<'a> {
    Lines {
        input,
        source: source.into(),
        line: 0,
        buf: Vec::new(),
    }
}

/// Whether `fields` are exactly the column `names` (case and surrounding spaces aside): how
/// every reader knows a header line.
#[must_use]
pub fn names_columns(fields: &[&str], names: &[&str]) -> bool {
    fields.len() == names.len()
        && fields
            .iter()
            .zip(names)
            .all(|(f, n)| f.trim().eq_ignore_ascii_case(n))
}

/// The data rows of `input` with the columns `names` (e.g. `["x", "y"]`), in order. Every
/// error is a one-line [`ParamError`] naming the line and the columns.
pub struct Rows<'a> {
    lines: Lines<'a>,
    names: [&'a str; 2],
}

/// The rows of `input` with the columns `names` (see the module docs).
pub fn rows<'a>(input: &'a mut dyn BufRead, names: [&'a str; 2]) -> Rows<'a> {
    Rows {
        lines: lines(input, "stdin"),
        names,
    }
}

impl Rows<'_> {
    fn error(&self, what: &str) -> ParamError {
        let [a, b] = self.names;
        self.lines.error(&format!("expected `{a},{b}`: {what}"))
    }
}

impl Lines<'_> {
    /// The number of the line last read.
    #[must_use]
    pub fn line(&self) -> usize {
        self.line
    }

    /// `what` as an error at the line last read.
    #[must_use]
    pub fn error(&self, what: &str) -> ParamError {
        ParamError(format!("{} line {}: {what}", self.source, self.line))
    }

    /// The next non-blank line's text, `None` at the end.
    pub fn next_line(&mut self) -> Option<Result<String, ParamError>> {
        use std::io::Read;
        loop {
            self.buf.clear();
            self.line += 1;
            let limit = MAX_LINE_BYTES as u64 + 1;
            match (&mut *self.input)
                .take(limit)
                .read_until(b'\n', &mut self.buf)
            {
                Ok(0) => return None,
                Ok(_) => {}
                Err(e) => {
                    return Some(Err(ParamError(format!(
                        "{}: cannot read: {e}",
                        self.source
                    ))));
                }
            }
            if self.buf.len() > MAX_LINE_BYTES {
                return Some(Err(
                    self.error(&format!("the line is longer than {MAX_LINE_BYTES} bytes"))
                ));
            }
            let mut bytes = &self.buf[..];
            if self.line == 1 {
                bytes = bytes.strip_prefix("\u{feff}".as_bytes()).unwrap_or(bytes);
            }
            let Ok(text) = std::str::from_utf8(bytes) else {
                return Some(Err(self.error("the line is not UTF-8 text")));
            };
            let text = text.trim();
            if !text.is_empty() {
                return Some(Ok(text.to_owned()));
            }
        }
    }
}

/// The text shown for a line in an error: control characters escaped, at most 80 characters.
pub fn shown(text: &str) -> String {
    let escaped: String = text.chars().flat_map(char::escape_debug).collect();
    match escaped.char_indices().nth(80) {
        Some((i, _)) => format!("{}...", &escaped[..i]),
        None => escaped,
    }
}

impl Iterator for Rows<'_> {
    type Item = Result<Row, ParamError>;

    fn next(&mut self) -> Option<Self::Item> {
        loop {
            let text = match self.lines.next_line()? {
                Ok(t) => t,
                Err(e) => return Some(Err(e)),
            };
            let mut fields = text.split(',').map(str::trim);
            let (Some(a), Some(b), None) = (fields.next(), fields.next(), fields.next()) else {
                return Some(Err(
                    self.error(&format!("got `{}` (not two fields)", shown(&text)))
                ));
            };
            let first_content_line = self.lines.line == 1;
            if first_content_line && names_columns(&[a, b], &self.names) {
                continue;
            }
            return Some(match (a.parse::<f64>(), b.parse::<f64>()) {
                (Ok(x), Ok(y)) if x.is_finite() && y.is_finite() => Ok(Row {
                    line: self.lines.line,
                    text: [a.to_owned(), b.to_owned()],
                    values: [x, y],
                }),
                _ => Err(self.error(&format!(
                    "got `{}`; both must be finite numbers{}",
                    shown(&text),
                    if first_content_line {
                        " (a header line names exactly these columns)"
                    } else {
                        ""
                    }
                ))),
            });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read(input: &str) -> Result<Vec<[f64; 2]>, String> {
        rows(&mut input.as_bytes(), ["x", "y"])
            .map(|r| r.map(|r| r.values).map_err(|e| e.0))
            .collect()
    }

    #[test]
    fn a_header_is_known_by_its_column_names() {
        assert_eq!(read("x,y\n0.3,0.3\n"), Ok(vec![[0.3, 0.3]]));
        assert_eq!(read(" X , Y \n\n0.3,0.3"), Ok(vec![[0.3, 0.3]]));
        assert_eq!(read("\u{feff}0.3,0.3\n"), Ok(vec![[0.3, 0.3]]));
        assert_eq!(read("\u{feff}x,y\n1,2\n"), Ok(vec![[1.0, 2.0]]));
        // Only the first line may be the header.
        let e = read("0.3,0.3\nx,y\n").expect_err("a second header");
        assert!(e.starts_with("stdin line 2:"), "{e}");
        for bad in ["NaN,0", "inf,0", "0.31.27,0.3290", "a,b", "1,2,3", "1"] {
            let e = read(&format!("{bad}\n0.3,0.3\n")).expect_err(bad);
            assert!(e.starts_with("stdin line 1: expected `x,y`"), "{e}");
            let e = read(&format!("0.3,0.3\n{bad}\n")).expect_err(bad);
            assert!(e.starts_with("stdin line 2: expected `x,y`"), "{e}");
        }
    }

    #[test]
    fn long_lines_and_bytes_that_are_not_text_are_errors() {
        let long = "1".repeat(MAX_LINE_BYTES + 10);
        let e = read(&long).expect_err("too long");
        assert!(e.contains("longer than 4096 bytes"), "{e}");
        let e = rows(&mut &b"0.3,\xff\n"[..], ["x", "y"])
            .next()
            .expect("a line")
            .expect_err("not UTF-8")
            .0;
        assert!(e.contains("not UTF-8"), "{e}");
        let e = read("\x1b[2J,1\n").expect_err("escape");
        assert!(!e.contains('\x1b') && e.contains("\\u{1b}"), "{e}");
    }
}
