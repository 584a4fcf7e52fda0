//! Two-column CSV on stdin (`sample`'s view directions, `cct`'s chromaticities), read by one
//! parser for every command.
//!
//! A line is two comma-separated numbers; blank lines are skipped. The first line may instead
//! be a header: exactly the two column names (case and surrounding spaces aside), so that a
//! mistyped first row (`NaN,0`, `0.31.27,0.3290`) is an error like on any other line, never
//! taken for a header. A UTF-8 byte-order mark before the first line is an encoding mark and
//! is dropped. Numbers must be finite. Lines are at most [`MAX_LINE_BYTES`] long; the rows are
//! an iterator, so a command can work through any number of them in bounded memory.

use std::io::BufRead;

use crate::args::ParamError;

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
                Err(e) => return Some(Err(ParamError(format!("cannot read stdin: {e}")))),
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
