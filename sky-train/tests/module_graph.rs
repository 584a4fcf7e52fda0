//! sky-train's modules depend on each other without cycles.
//!
//! Every file under `src/` (except the binary's `main.rs`) is lexed with `proc-macro2`, and every
//! path that names one of the crate's modules (`crate::…`, `super::…`, `self::…`, a child module
//! by name; in `use` trees, expressions, types and macro arguments alike) is an edge from the
//! module the path is written in to the deepest module it names. Inline modules (`mod tests`)
//! count as part of their file's module.
//!
//! The graph is checked level by level, as layered designs are: for every module, the edges
//! between its children (each child standing for its whole subtree) must form no cycle. So the
//! crate's top-level modules (`cli`, `commands`, `controller`, `captures`, `sources`,
//! `style_file`, …) are layers, and so are the modules inside each folder. A module's edges to
//! its own ancestors (`super::Frame`) and a parent's to its children (its re-exports) are
//! within one subtree and not checked. A failure prints the cycle and the paths behind it.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};
use std::str::FromStr;

use proc_macro2::{Delimiter, TokenStream, TokenTree};

/// A module's path below the crate root (`["captures", "load"]`); the root is empty.
type ModulePath = Vec<String>;

/// The file modules of the crate at `src`: module path -> file.
fn modules(src: &Path) -> BTreeMap<ModulePath, PathBuf> {
    fn walk(dir: &Path, prefix: &ModulePath, out: &mut BTreeMap<ModulePath, PathBuf>) {
        let mut entries: Vec<_> = std::fs::read_dir(dir)
            .expect("readable src folder")
            .map(|e| e.expect("directory entry").path())
            .collect();
        entries.sort();
        for path in entries {
            let name = path
                .file_stem()
                .and_then(|s| s.to_str())
                .expect("UTF-8 file name")
                .to_owned();
            if path.is_dir() {
                let mut p = prefix.clone();
                p.push(name);
                walk(&path, &p, out);
            } else if path.extension().is_some_and(|e| e == "rs") {
                let module = match name.as_str() {
                    "lib" | "mod" => prefix.clone(),
                    "main" if prefix.is_empty() => continue, // the binary, a separate crate
                    _ => {
                        let mut p = prefix.clone();
                        p.push(name);
                        p
                    }
                };
                out.insert(module, path);
            }
        }
    }
    let mut out = BTreeMap::new();
    walk(src, &Vec::new(), &mut out);
    out
}

/// Collects the dependency edges of one file.
struct Scanner<'a> {
    known: &'a BTreeSet<ModulePath>,
    /// The file's module: every edge starts here.
    file_module: ModulePath,
    edges: BTreeSet<ModulePath>,
}

impl Scanner<'_> {
    /// Records the deepest known module that `path` (absolute) lies in.
    fn record(&mut self, path: &[String]) {
        let deepest = (0..=path.len())
            .rev()
            .map(|n| path[..n].to_vec())
            .find(|p| self.known.contains(p))
            .unwrap_or_default();
        if deepest != self.file_module {
            self.edges.insert(deepest);
        }
    }

    /// The absolute form of a path's first segment written in module `scope`, if it names one of
    /// the crate's modules.
    fn start(&self, scope: &ModulePath, first: &str) -> Option<ModulePath> {
        match first {
            "crate" => Some(Vec::new()),
            "self" => Some(scope.clone()),
            "super" => scope.split_last().map(|(_, parent)| parent.to_vec()),
            name => {
                let mut child = scope.clone();
                child.push(name.to_owned());
                self.known.contains(&child).then_some(child)
            }
        }
    }

    /// Scans `tokens` written in module `scope` (the file's module, or an inline module in it).
    fn scan(&mut self, tokens: TokenStream, scope: &ModulePath) {
        let tokens: Vec<TokenTree> = tokens.into_iter().collect();
        let mut i = 0;
        while i < tokens.len() {
            match &tokens[i] {
                // `mod name;` declares a child (no dependency); `mod name { … }` is an inline
                // module, scanned in its own scope.
                TokenTree::Ident(id) if id == "mod" => {
                    if let Some(TokenTree::Ident(name)) = tokens.get(i + 1) {
                        if let Some(TokenTree::Group(body)) = tokens.get(i + 2)
                            && body.delimiter() == Delimiter::Brace
                        {
                            let mut inner = scope.clone();
                            inner.push(name.to_string());
                            self.scan(body.stream(), &inner);
                            i += 1;
                        }
                        i += 2;
                        continue;
                    }
                }
                // `pub(crate)`, `pub(super)`: visibility, not a dependency.
                TokenTree::Ident(id) if id == "pub" => {
                    if matches!(tokens.get(i + 1), Some(TokenTree::Group(g)) if g.delimiter() == Delimiter::Parenthesis)
                    {
                        i += 2;
                        continue;
                    }
                }
                TokenTree::Ident(id) if !follows_path_separator(&tokens, i) => {
                    if let Some(base) = self.start(scope, &id.to_string()) {
                        i = self.path(&tokens, i + 1, base);
                        continue;
                    }
                }
                TokenTree::Group(g) => self.scan(g.stream(), scope),
                _ => {}
            }
            i += 1;
        }
    }

    /// Follows a path from `tokens[i]` on (just after a segment), `base` being where it has got
    /// to; `use` groups (`::{a, b::c}`) branch. Returns the index after the path.
    fn path(&mut self, tokens: &[TokenTree], mut i: usize, mut base: ModulePath) -> usize {
        loop {
            if !is_path_separator(tokens, i) {
                self.record(&base);
                return i;
            }
            match tokens.get(i + 2) {
                Some(TokenTree::Ident(seg)) => {
                    let seg = seg.to_string();
                    match seg.as_str() {
                        "super" => {
                            base.pop();
                        }
                        "self" => {}
                        _ => base.push(seg),
                    }
                    i += 3;
                }
                Some(TokenTree::Group(g)) if g.delimiter() == Delimiter::Brace => {
                    let inner: Vec<TokenTree> = g.stream().into_iter().collect();
                    for item in
                        inner.split(|t| matches!(t, TokenTree::Punct(p) if p.as_char() == ','))
                    {
                        match item.first() {
                            Some(TokenTree::Ident(seg)) => {
                                let mut b = base.clone();
                                match seg.to_string().as_str() {
                                    "self" => {}
                                    "super" => {
                                        b.pop();
                                    }
                                    s => b.push(s.to_owned()),
                                }
                                self.path(item, 1, b);
                            }
                            // `*`, or empty after a trailing comma
                            _ => self.record(&base),
                        }
                    }
                    return i + 3;
                }
                // `::*`, `::<…>`
                _ => {
                    self.record(&base);
                    return i + 2;
                }
            }
        }
    }
}

/// Whether `tokens[i..]` starts with `::`.
fn is_path_separator(tokens: &[TokenTree], i: usize) -> bool {
    matches!((tokens.get(i), tokens.get(i + 1)),
        (Some(TokenTree::Punct(a)), Some(TokenTree::Punct(b))) if a.as_char() == ':' && b.as_char() == ':')
}

/// Whether `tokens[i]` is a later segment of a path (preceded by `::`).
fn follows_path_separator(tokens: &[TokenTree], i: usize) -> bool {
    i >= 2 && is_path_separator(tokens, i - 2)
}

/// The module graph: module -> the modules it names.
fn graph(src: &Path) -> BTreeMap<ModulePath, BTreeSet<ModulePath>> {
    let files = modules(src);
    let known: BTreeSet<ModulePath> = files.keys().cloned().collect();
    files
        .iter()
        .map(|(module, file)| {
            let text = std::fs::read_to_string(file).expect("readable source");
            let tokens = TokenStream::from_str(&text)
                .unwrap_or_else(|e| panic!("{}: cannot lex: {e}", file.display()));
            let mut scanner = Scanner {
                known: &known,
                file_module: module.clone(),
                edges: BTreeSet::new(),
            };
            scanner.scan(tokens, module);
            (module.clone(), scanner.edges)
        })
        .collect()
}

/// The graph of each module's children, from the file-module graph: an edge `a -> b` between
/// modules whose deepest common ancestor is `p` becomes an edge between the children of `p` that
/// contain them (and is left out when one of `a`, `b` is `p` itself). Each edge keeps the file
/// edges behind it.
fn levels(graph: &BTreeMap<ModulePath, BTreeSet<ModulePath>>) -> BTreeMap<ModulePath, Graph> {
    let mut out: BTreeMap<ModulePath, Graph> = BTreeMap::new();
    for (from, targets) in graph {
        for to in targets {
            let common = from.iter().zip(to).take_while(|(a, b)| a == b).count();
            if common == from.len() || common == to.len() {
                continue; // one is the other's ancestor
            }
            let a = from[..=common].to_vec();
            let b = to[..=common].to_vec();
            out.entry(from[..common].to_vec())
                .or_default()
                .entry(a)
                .or_default()
                .entry(b)
                .or_default()
                .push((from.clone(), to.clone()));
        }
    }
    out
}

/// Children -> children they depend on -> the file edges behind that.
type Graph = BTreeMap<ModulePath, BTreeMap<ModulePath, Vec<(ModulePath, ModulePath)>>>;

/// The groups of modules in `graph` that depend on each other in a circle (its strongly
/// connected components of more than one module).
fn cycles<V>(graph: &BTreeMap<ModulePath, BTreeMap<ModulePath, V>>) -> Vec<BTreeSet<ModulePath>> {
    let reach = |from: &ModulePath| {
        let mut seen = BTreeSet::new();
        let mut todo = vec![from.clone()];
        while let Some(n) = todo.pop() {
            for next in graph.get(&n).into_iter().flat_map(BTreeMap::keys) {
                if seen.insert(next.clone()) {
                    todo.push(next.clone());
                }
            }
        }
        seen
    };
    let reachable: BTreeMap<&ModulePath, BTreeSet<ModulePath>> =
        graph.keys().map(|n| (n, reach(n))).collect();
    let mut groups: Vec<BTreeSet<ModulePath>> = Vec::new();
    for (n, from_n) in &reachable {
        if !from_n.contains(*n) || groups.iter().any(|g| g.contains(*n)) {
            continue;
        }
        groups.push(
            from_n
                .iter()
                .filter(|m| reachable.get(m).is_some_and(|r| r.contains(*n)))
                .cloned()
                .collect(),
        );
    }
    groups
}

fn name(module: &ModulePath) -> String {
    if module.is_empty() {
        "crate".into()
    } else {
        module.join("::")
    }
}

#[test]
fn the_module_graph_has_no_cycle() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let graph = graph(&src);
    assert!(graph.len() > 20, "found only {} modules", graph.len());
    let mut failures = Vec::new();
    for (parent, children) in levels(&graph) {
        for group in cycles(&children) {
            let because: Vec<String> = group
                .iter()
                .flat_map(|a| &children[a])
                .filter(|(b, _)| group.contains(*b))
                .flat_map(|(_, files)| files)
                .map(|(a, b)| format!("    {} names {}", name(a), name(b)))
                .collect();
            let group: Vec<String> = group.iter().map(name).collect();
            failures.push(format!(
                "in {}: {} depend on each other:\n{}",
                name(&parent),
                group.join(", "),
                because.join("\n")
            ));
        }
    }
    assert!(
        failures.is_empty(),
        "import cycles:\n{}",
        failures.join("\n")
    );
}

/// The scanner sees the kinds of paths the crate writes (so that a passing test means something).
#[test]
fn the_scanner_finds_each_kind_of_path() {
    let known: BTreeSet<ModulePath> = [
        vec![],
        vec!["a".to_owned()],
        vec!["a".to_owned(), "b".to_owned()],
        vec!["a".to_owned(), "x".to_owned()],
        vec!["a".to_owned(), "x".to_owned(), "y".to_owned()],
        vec!["c".to_owned()],
        vec!["d".to_owned()],
        vec!["e".to_owned()],
    ]
    .into_iter()
    .collect();
    let text = r#"
        //! crate::e in a comment is no edge
        pub mod y;
        pub(crate) fn z() {}
        use super::b::{self, X};
        use crate::{c, d::Y};
        fn f() { b::g(); writeln!(out, "{}", crate::e::h()); }
        #[cfg(test)]
        mod tests { use super::*; }
    "#;
    let mut scanner = Scanner {
        known: &known,
        file_module: vec!["a".to_owned(), "x".to_owned()],
        edges: BTreeSet::new(),
    };
    let scope = vec!["a".to_owned(), "x".to_owned()];
    scanner.scan(TokenStream::from_str(text).expect("lexes"), &scope);
    let want: BTreeSet<ModulePath> = [
        vec!["a".to_owned(), "b".to_owned()],
        vec!["c".to_owned()],
        vec!["d".to_owned()],
        vec!["e".to_owned()],
        // `use super::*` in `mod tests` of module `a::x` names `a::x` itself: no edge.
    ]
    .into_iter()
    .collect();
    assert_eq!(scanner.edges, want);

    // Levels: a::x -> a::b is a cycle with a::b -> a::x; a::x -> a (its parent) is not checked.
    let file_graph: BTreeMap<ModulePath, BTreeSet<ModulePath>> = [
        (
            vec!["a".to_owned(), "x".to_owned()],
            [vec!["a".to_owned(), "b".to_owned()], vec!["a".to_owned()]],
        ),
        (
            vec!["a".to_owned(), "b".to_owned()],
            [vec!["a".to_owned(), "x".to_owned()], vec!["c".to_owned()]],
        ),
    ]
    .into_iter()
    .map(|(k, v)| (k, v.into_iter().collect()))
    .collect();
    let levels = levels(&file_graph);
    let in_a = cycles(&levels[&vec!["a".to_owned()]]);
    assert_eq!(in_a.len(), 1, "a::x <-> a::b");
    assert_eq!(in_a[0].len(), 2);
    assert!(cycles(&levels[&Vec::new()]).is_empty(), "a -> c only");
}
