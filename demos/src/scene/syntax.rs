//! Turns a TOML/serde error into a [`SceneError::Syntax`] that names the field and line.
//!
//! The parser reports a byte span; the dotted field path is recovered by
//! replaying the table headers (`[a.b]`, `[[c]]`) that precede it.

use super::SceneError;

/// Converts a parse error on `text` into a [`SceneError::Syntax`].
pub(crate) fn syntax_error(text: &str, err: &toml::de::Error) -> SceneError {
    let offset = err.span().map_or(0, |s| s.start).min(text.len());
    let (line, column) = line_column(text, offset);
    SceneError::Syntax {
        field: field_path(text, line),
        message: err.message().trim().to_owned(),
        line,
        column,
    }
}

/// 1-based line and column of a byte offset.
fn line_column(text: &str, offset: usize) -> (usize, usize) {
    let before = &text[..floor_char_boundary(text, offset)];
    let line = before.matches('\n').count() + 1;
    let column = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, column)
}

fn floor_char_boundary(text: &str, mut offset: usize) -> usize {
    while !text.is_char_boundary(offset) {
        offset -= 1;
    }
    offset
}

/// The dotted path of the table (and key) on 1-based `line`, e.g. `characters[1].alpha`.
fn field_path(text: &str, line: usize) -> String {
    let mut table = String::new();
    let mut array_counts: Vec<(String, usize)> = Vec::new();
    let mut key = None;
    for (n, raw) in text.lines().enumerate().take(line) {
        let l = raw.trim();
        let is_target = n + 1 == line;
        if let Some(name) = l.strip_prefix("[[").and_then(|r| r.split("]]").next()) {
            let name = name.trim().to_owned();
            let index = match array_counts.iter_mut().find(|(k, _)| *k == name) {
                Some((_, c)) => {
                    *c += 1;
                    *c - 1
                }
                None => {
                    array_counts.push((name.clone(), 1));
                    0
                }
            };
            // A new element of `a` restarts the numbering of its sub-arrays `a.b`.
            let prefix = format!("{name}.");
            array_counts.retain(|(k, _)| !k.starts_with(&prefix));
            table = indexed_path(&name, &array_counts, index);
        } else if let Some(name) = l.strip_prefix('[').and_then(|r| r.split(']').next()) {
            let name = name.trim();
            table = indexed_path(name, &array_counts, usize::MAX);
        } else if is_target {
            key = l
                .split_once('=')
                .map(|(k, _)| k.trim().trim_matches('"').to_owned())
                .filter(|k| !k.is_empty() && !k.starts_with('#'));
        }
    }
    match (table.is_empty(), key) {
        (true, None) => "<root>".to_owned(),
        (true, Some(k)) => k,
        (false, None) => table,
        (false, Some(k)) => format!("{table}.{k}"),
    }
}

/// `characters.path` becomes `characters[2].path` when `characters` is an array of
/// tables whose current element is 2; `own_index` is the index of `name` itself
/// when it is an array element (`usize::MAX` for a plain table).
fn indexed_path(name: &str, arrays: &[(String, usize)], own_index: usize) -> String {
    let mut out = String::new();
    let mut prefix = String::new();
    let parts: Vec<&str> = name.split('.').map(str::trim).collect();
    for (k, part) in parts.iter().enumerate() {
        if !prefix.is_empty() {
            prefix.push('.');
            out.push('.');
        }
        prefix.push_str(part);
        out.push_str(part);
        let last = k + 1 == parts.len();
        if last && own_index != usize::MAX {
            out.push_str(&format!("[{own_index}]"));
        } else if !last && let Some((_, count)) = arrays.iter().find(|(a, _)| *a == prefix) {
            out.push_str(&format!("[{}]", count.saturating_sub(1)));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    const TEXT: &str = "name = \"x\"\n[terrain]\nsize_x = 1\n[[characters]]\nname = \"a\"\n[[characters]]\nname = \"b\"\n[characters.path]\nlength = 3\n";

    #[test]
    fn paths_follow_headers_and_array_indices() {
        assert_eq!(field_path(TEXT, 1), "name");
        assert_eq!(field_path(TEXT, 2), "terrain");
        assert_eq!(field_path(TEXT, 3), "terrain.size_x");
        assert_eq!(field_path(TEXT, 5), "characters[0].name");
        assert_eq!(field_path(TEXT, 7), "characters[1].name");
        assert_eq!(field_path(TEXT, 9), "characters[1].path.length");
    }

    #[test]
    fn line_and_column_are_one_based() {
        assert_eq!(line_column("ab\ncd", 4), (2, 2));
        assert_eq!(line_column("ab", 0), (1, 1));
    }
}
