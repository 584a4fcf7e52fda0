//! Every page of `docs/` has its Rust blocks run as doctests: `tests/src/lib.rs` includes it.

use std::path::Path;

#[test]
fn every_docs_page_is_a_doctest() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let lib = std::fs::read_to_string(root.join("tests/src/lib.rs")).expect("tests/src/lib.rs");
    let mut missing = Vec::new();
    for entry in std::fs::read_dir(root.join("docs")).expect("docs/") {
        let name = entry.expect("docs/ entry").file_name();
        let name = name.to_string_lossy();
        if name.ends_with(".md") && !lib.contains(&format!("\"../../docs/{name}\"")) {
            missing.push(name.into_owned());
        }
    }
    assert!(
        missing.is_empty(),
        "docs pages not included in tests/src/lib.rs's `pages`: {missing:?}"
    );
}
