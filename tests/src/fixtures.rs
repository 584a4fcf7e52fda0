//! Reading the reference fixtures under `tests/fixtures/` (written once by
//! `tests/reference/gen_fixtures.py` with published implementations).

/// The data rows of fixture `name`: comment lines (`#`) and the header line skipped, each row
/// split at commas.
///
/// # Panics
/// If the file cannot be read (a test's missing input).
#[must_use]
pub fn rows(name: &str) -> Vec<Vec<String>> {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("fixtures")
        .join(name);
    std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .lines()
        .filter(|l| !l.starts_with('#'))
        .skip(1)
        .map(|l| l.split(',').map(str::to_owned).collect())
        .collect()
}

/// A fixture field as a number.
///
/// # Panics
/// If the field is not a number.
#[must_use]
pub fn num(s: &str) -> f64 {
    s.parse().unwrap_or_else(|_| panic!("not a number: {s}"))
}
