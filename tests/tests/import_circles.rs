//! No two modules of a crate import each other, directly or round a circle:
//! shared types live in leaf files, so each module can be read knowing only
//! the modules below it.
//!
//! Edges come from `use crate::…`, `use super::…` and `use self::…`
//! statements and from inline `crate::a::b` or `super::a` paths; comments and
//! `#[cfg(test)] mod tests` blocks are left out. A module's edges to its own
//! ancestors and descendants (a `mod.rs` re-exporting its children) are not
//! circles.

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};

/// Every module of the crate under `src`, by path (`a::b`), and its file.
fn modules(src: &Path) -> BTreeMap<String, PathBuf> {
    fn walk(dir: &Path, src: &Path, out: &mut BTreeMap<String, PathBuf>) {
        let mut entries: Vec<PathBuf> = fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().path())
            .collect();
        entries.sort();
        for path in entries {
            if path.is_dir() {
                walk(&path, src, out);
            } else if path.extension().is_some_and(|e| e == "rs") {
                let rel = path.strip_prefix(src).unwrap().with_extension("");
                let mut parts: Vec<String> = rel
                    .components()
                    .map(|c| c.as_os_str().to_string_lossy().into_owned())
                    .collect();
                if matches!(
                    parts.last().map(String::as_str),
                    Some("mod" | "lib" | "main")
                ) {
                    parts.pop();
                }
                out.insert(parts.join("::"), path);
            }
        }
    }
    let mut out = BTreeMap::new();
    walk(src, src, &mut out);
    out
}

/// The file's code without comment lines and without its test module.
fn code(text: &str) -> String {
    let text = text.split("#[cfg(test)]\nmod tests").next().unwrap_or("");
    text.lines()
        .filter(|l| !l.trim_start().starts_with("//"))
        .collect::<Vec<_>>()
        .join("\n")
}

fn is_ident(c: char) -> bool {
    c.is_ascii_alphanumeric() || c == '_'
}

/// The `a::b::c` path starting at `text[at..]`.
fn path_at(text: &str, at: usize) -> String {
    let mut end = at;
    let bytes = text.as_bytes();
    while end < text.len() {
        let c = bytes[end] as char;
        if is_ident(c) {
            end += 1;
        } else if text[end..].starts_with("::")
            && text[end + 2..].chars().next().is_some_and(is_ident)
        {
            end += 2;
        } else {
            break;
        }
    }
    text[at..end].to_string()
}

/// Every path a file names through `crate`, `super` or `self`: inline paths
/// and the items of `use` statements (one level of braces expanded).
fn named_paths(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    for root in ["crate::", "super::", "self::"] {
        for (at, _) in text.match_indices(root) {
            let before = text[..at].chars().next_back();
            if before.is_some_and(|c| is_ident(c) || c == ':') {
                continue;
            }
            let base = path_at(text, at);
            let after = &text[at + base.len()..];
            if let Some(list) = after.strip_prefix("::{") {
                let list = &list[..list.find(';').unwrap_or(list.len())];
                let mut depth = 0;
                let mut item = String::new();
                for c in list.chars() {
                    match c {
                        '{' => depth += 1,
                        '}' if depth == 0 => break,
                        '}' => depth -= 1,
                        ',' if depth == 0 => {
                            out.push(format!("{base}::{}", path_at(item.trim(), 0)));
                            item.clear();
                            continue;
                        }
                        _ => {}
                    }
                    item.push(c);
                }
                let last = item.trim();
                if !last.is_empty() {
                    out.push(format!("{base}::{}", path_at(last, 0)));
                }
            }
            out.push(base);
        }
    }
    out
}

/// The module a path from module `current` names, if any.
fn resolve(modules: &BTreeMap<String, PathBuf>, current: &[&str], path: &str) -> Option<String> {
    let mut segs: Vec<&str> = path.split("::").collect();
    let mut base: Vec<&str> = match segs[0] {
        "crate" => Vec::new(),
        "self" => current.to_vec(),
        _ => current[..current.len().saturating_sub(1)].to_vec(),
    };
    segs.remove(0);
    while segs.first() == Some(&"super") {
        base.pop();
        segs.remove(0);
    }
    (0..=segs.len()).rev().find_map(|k| {
        let candidate = base
            .iter()
            .chain(&segs[..k])
            .copied()
            .collect::<Vec<_>>()
            .join("::");
        modules.contains_key(&candidate).then_some(candidate)
    })
}

/// Modules that import each other round a circle, each circle sorted.
fn circles(src: &Path) -> Vec<Vec<String>> {
    let modules = modules(src);
    let mut edges: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for (name, file) in &modules {
        let current: Vec<&str> = name.split("::").filter(|s| !s.is_empty()).collect();
        let targets = edges.entry(name.clone()).or_default();
        if name.is_empty() {
            continue;
        }
        for path in named_paths(&code(&fs::read_to_string(file).unwrap())) {
            let Some(to) = resolve(&modules, &current, &path) else {
                continue;
            };
            let related = to.is_empty()
                || to == *name
                || name.starts_with(&format!("{to}::"))
                || to.starts_with(&format!("{name}::"));
            if !related {
                targets.insert(to);
            }
        }
    }
    strongly_connected(&edges)
}

/// Tarjan's strongly connected components of more than one module.
fn strongly_connected(edges: &BTreeMap<String, BTreeSet<String>>) -> Vec<Vec<String>> {
    struct State<'a> {
        edges: &'a BTreeMap<String, BTreeSet<String>>,
        index: BTreeMap<&'a str, usize>,
        low: BTreeMap<&'a str, usize>,
        stack: Vec<&'a str>,
        found: Vec<Vec<String>>,
    }
    fn visit<'a>(s: &mut State<'a>, v: &'a str) {
        let n = s.index.len();
        s.index.insert(v, n);
        s.low.insert(v, n);
        s.stack.push(v);
        for w in &s.edges[v] {
            let w = w.as_str();
            if !s.index.contains_key(w) {
                visit(s, w);
                let low = s.low[v].min(s.low[w]);
                s.low.insert(v, low);
            } else if s.stack.contains(&w) {
                let low = s.low[v].min(s.index[w]);
                s.low.insert(v, low);
            }
        }
        if s.low[v] == s.index[v] {
            let mut component = Vec::new();
            while let Some(w) = s.stack.pop() {
                component.push(w.to_string());
                if w == v {
                    break;
                }
            }
            if component.len() > 1 {
                component.sort();
                s.found.push(component);
            }
        }
    }
    let mut state = State {
        edges,
        index: BTreeMap::new(),
        low: BTreeMap::new(),
        stack: Vec::new(),
        found: Vec::new(),
    };
    for v in edges.keys() {
        if !state.index.contains_key(v.as_str()) {
            visit(&mut state, v);
        }
    }
    state.found
}

fn crate_src(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("..")
        .join(name)
        .join("src")
}

#[test]
fn no_crate_has_an_import_circle() {
    for krate in ["engine", "softwalk_systems", "softwalk_app"] {
        let found = circles(&crate_src(krate));
        assert!(
            found.is_empty(),
            "{krate}: modules importing round a circle: {found:?}"
        );
    }
}

#[test]
fn a_circle_is_found() {
    let dir = tempfile::tempdir().unwrap();
    let src = dir.path();
    fs::write(src.join("lib.rs"), "mod a;\nmod b;\nmod c;\n").unwrap();
    fs::write(src.join("a.rs"), "use crate::b::B;\npub struct A;\n").unwrap();
    fs::write(src.join("b.rs"), "pub struct B(super::c::C);\n").unwrap();
    fs::write(
        src.join("c.rs"),
        "// use crate::b;\nuse crate::{a::A, b};\npub struct C;\n",
    )
    .unwrap();
    let found = circles(src);
    assert_eq!(found, vec![vec!["a", "b", "c"]]);
    // Test modules do not count.
    fs::write(
        src.join("c.rs"),
        "pub struct C;\n#[cfg(test)]\nmod tests {\n    use crate::a::A;\n}\n",
    )
    .unwrap();
    assert!(circles(src).is_empty());
}
