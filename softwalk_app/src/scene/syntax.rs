//! Turns a TOML/serde error into a [`SceneError::Syntax`] that names the field and line.
//!
//! The parser reports a byte span; the dotted field path is recovered by
//! replaying the table headers (`[a.b]`, `[[c]]`) that precede it.

use super::SceneError;

/// Longest field path or message echoed back, in characters: a scene with a
/// huge key must not print it whole.
const MAX_ECHO_CHARS: usize = 160;

/// Converts a parse error on `text` into a [`SceneError::Syntax`].
///
/// A missing field is named after the table the parser reports it in (the
/// field itself, not the first key of that table).
pub(crate) fn syntax_error(text: &str, err: &toml::de::Error) -> SceneError {
    let offset = err.span().map_or(0, |s| s.start).min(text.len());
    let (line, column) = line_column(text, offset);
    let message = err.message().trim();
    let field = if err.span().is_none() {
        "<root>".to_owned()
    } else if let Some(missing) = missing_field(message) {
        join_path(&table_path(text, line), missing)
    } else if let Some(key) = bad_value(message).and_then(|v| key_in_table(text, line, v)) {
        join_path(&table_path(text, line), &key)
    } else {
        field_path(text, line)
    };
    SceneError::Syntax {
        field: shortened(&field),
        message: shortened(message),
        line,
        column,
    }
}

/// The name in serde's "missing field `name`" message.
fn missing_field(message: &str) -> Option<&str> {
    message
        .strip_prefix("missing field `")
        .and_then(|rest| rest.split('`').next())
}

/// The value quoted in serde's "invalid type: floating point `1.0`, ..." message.
fn bad_value(message: &str) -> Option<&str> {
    message
        .strip_prefix("invalid type: ")
        .or_else(|| message.strip_prefix("invalid value: "))
        .and_then(|rest| rest.split('`').nth(1))
}

/// The one key of the table starting on 1-based `line` whose value is
/// written as `value`: a tagged table is reported as a whole, so the key its
/// bad value sits under is found by the value.
fn key_in_table(text: &str, line: usize, value: &str) -> Option<String> {
    let mut keys = text
        .lines()
        .skip(line)
        .take_while(|l| !l.trim_start().starts_with('['))
        .filter_map(|l| l.split_once('='))
        .filter(|(_, v)| v.trim() == value)
        .map(|(k, _)| k.trim().trim_matches('"').to_owned());
    let key = keys.next()?;
    keys.next().is_none().then_some(key)
}

fn join_path(table: &str, key: &str) -> String {
    if table.is_empty() {
        key.to_owned()
    } else {
        format!("{table}.{key}")
    }
}

/// `text` cut to [`MAX_ECHO_CHARS`] characters, with an ellipsis when cut.
fn shortened(text: &str) -> String {
    match text.char_indices().nth(MAX_ECHO_CHARS) {
        Some((end, _)) => format!("{}…", &text[..end]),
        None => text.to_owned(),
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
    let (table, key) = path_parts(text, line);
    match (table.is_empty(), key) {
        (true, None) => "<root>".to_owned(),
        (true, Some(k)) => k,
        (false, None) => table,
        (false, Some(k)) => format!("{table}.{k}"),
    }
}

/// The dotted path of the table open on 1-based `line` (empty at the top level).
fn table_path(text: &str, line: usize) -> String {
    path_parts(text, line).0
}

/// The table open on 1-based `line`, and the key assigned on it, if any.
fn path_parts(text: &str, line: usize) -> (String, Option<String>) {
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
    (table, key)
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
    fn a_missing_field_is_named_after_its_table_not_the_first_key() {
        let err = toml::from_str::<toml::Table>("x = [").unwrap_err();
        assert!(missing_field(err.message()).is_none());
        assert_eq!(missing_field("missing field `terrain`"), Some("terrain"));
        assert_eq!(join_path(&table_path(TEXT, 1), "terrain"), "terrain");
        assert_eq!(
            join_path(&table_path(TEXT, 9), "kind"),
            "characters[1].path.kind"
        );
    }

    #[test]
    fn a_bad_value_in_a_tagged_table_names_its_key() {
        let text = "[path]\nkind = \"straight\"\nstart = 1.0\nheading_deg = 0.0\n";
        let message = "invalid type: floating point `1.0`, expected an array of length 2";
        assert_eq!(bad_value(message), Some("1.0"));
        assert_eq!(key_in_table(text, 1, "1.0").as_deref(), Some("start"));
        assert_eq!(key_in_table(text, 1, "2.0"), None);
        let twice = "[path]\na = 1.0\nb = 1.0\n";
        assert_eq!(
            key_in_table(twice, 1, "1.0"),
            None,
            "ambiguous: no key named"
        );
    }

    #[test]
    fn long_keys_are_not_echoed_whole() {
        let key = "a.".repeat(100_000);
        let short = shortened(&key);
        assert_eq!(short.chars().count(), MAX_ECHO_CHARS + 1);
        assert!(short.ends_with('…'));
        assert_eq!(shortened("terrain"), "terrain");
    }

    #[test]
    fn line_and_column_are_one_based() {
        assert_eq!(line_column("ab\ncd", 4), (2, 2));
        assert_eq!(line_column("ab", 0), (1, 1));
    }
}
