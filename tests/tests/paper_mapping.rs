//! `docs/paper-mapping.md` cites only files and code names that exist.
//!
//! Every span in backticks is read as one of:
//! - a file path (it has an extension such as `.rs` or `.toml`): it must exist
//!   relative to the repository root or to `docs/`; a `::test_name` after it
//!   must be a name in the code;
//! - a code path such as `character::balance_stage` or
//!   `TerrainMaterial::{dry_sand, soil}`: every identifier in it that looks
//!   like code (snake_case or CamelCase, three characters or more) must occur
//!   in the workspace's Rust sources, or be a test file's name;
//! - anything else (formulas, values, prose): ignored.

use std::collections::BTreeSet;
use std::fs;
use std::path::{Path, PathBuf};

fn workspace_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("the tests crate lives in the workspace")
        .to_path_buf()
}

/// Every `.rs` file under `dir`, skipping build output.
fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        if path.is_dir() {
            if path.file_name().is_some_and(|n| n == "target") {
                continue;
            }
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// The words of the workspace's Rust code, plus each Rust file's stem (a test
/// binary is named after its file).
fn code_words(root: &Path) -> BTreeSet<String> {
    let mut files = Vec::new();
    for krate in [
        "engine",
        "softwalk_systems",
        "softwalk_app",
        "demos",
        "tests",
        "benches",
    ] {
        rust_files(&root.join(krate), &mut files);
    }
    let mut words = BTreeSet::new();
    for file in &files {
        if let Some(stem) = file.file_stem() {
            words.insert(stem.to_string_lossy().into_owned());
        }
        let text = fs::read_to_string(file).expect("a workspace source file is readable");
        words.extend(identifiers(&text).map(str::to_owned));
    }
    words
}

/// The identifier-shaped words of `text`.
fn identifiers(text: &str) -> impl Iterator<Item = &str> {
    text.split(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
        .filter(|w| w.starts_with(|c: char| c.is_ascii_alphabetic() || c == '_'))
}

/// Whether `word` looks like a code name rather than an English word or a
/// one-letter symbol.
fn looks_like_code(word: &str) -> bool {
    word.len() >= 3 && (word.contains('_') || word.chars().any(|c| c.is_ascii_uppercase()))
}

/// Whether `span` is a code path: identifiers joined by `::`, optionally with
/// a `{a, b}` group and a trailing `()`.
fn is_code_path(span: &str) -> bool {
    let body = span.strip_suffix("()").unwrap_or(span);
    !body.is_empty()
        && body
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || "_:{}, ".contains(c))
        && body.starts_with(|c: char| c.is_ascii_alphabetic() || c == '_')
        && (!body.contains(' ') || body.contains('{'))
}

fn is_file_path(span: &str) -> bool {
    let first = span.split("::").next().unwrap_or(span);
    !span.contains(' ')
        && [".rs", ".toml", ".md", ".png"]
            .iter()
            .any(|ext| first.ends_with(ext))
}

fn backtick_spans(doc: &str) -> Vec<&str> {
    doc.split('`').skip(1).step_by(2).collect()
}

#[test]
fn every_cited_file_and_code_name_exists() {
    let root = workspace_root();
    let doc = fs::read_to_string(root.join("docs/paper-mapping.md"))
        .expect("docs/paper-mapping.md is readable");
    let words = code_words(&root);
    let mut missing = Vec::new();
    let mut checked = 0;
    for span in backtick_spans(&doc) {
        if span.contains('…') || span.contains('*') {
            continue;
        }
        if is_file_path(span) {
            checked += 1;
            let mut parts = span.split("::");
            let file = parts.next().unwrap_or(span);
            if !root.join(file).exists() && !root.join("docs").join(file).exists() {
                missing.push(format!("file `{file}`"));
            }
            for name in parts.filter(|n| !words.contains(*n)) {
                missing.push(format!("`{name}` (in `{span}`)"));
            }
        } else if is_code_path(span) {
            for name in identifiers(span).filter(|w| looks_like_code(w)) {
                checked += 1;
                if !words.contains(name) {
                    missing.push(format!("`{name}` (in `{span}`)"));
                }
            }
        }
    }
    assert!(
        checked > 100,
        "expected the mapping to cite many names, found {checked}"
    );
    assert!(
        missing.is_empty(),
        "docs/paper-mapping.md cites what does not exist:\n  {}",
        missing.join("\n  ")
    );
}

#[test]
fn the_checker_tells_code_from_prose() {
    assert!(is_code_path("character::balance_stage"));
    assert!(is_code_path("TerrainMaterial::{dry_sand, soil}"));
    assert!(is_code_path("GrassSettings::small()"));
    assert!(!is_code_path("t_max/gamma"));
    assert!(!is_code_path("0.1 m * d_t"));
    assert!(is_file_path("tests/tests/gait_quality.rs"));
    assert!(is_file_path(
        "engine/tests/geom_raycast.rs::vertical_rays_hit"
    ));
    assert!(!is_file_path("t_max/gamma"));
    assert!(looks_like_code("balance_stage"));
    assert!(looks_like_code("RigidProxy"));
    assert!(!looks_like_code("the"));
}
