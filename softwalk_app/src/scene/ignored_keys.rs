//! Keys a scene file spells out that the parsed scene does not keep.
//!
//! `deny_unknown_fields` refuses most unknown keys, but serde lets some
//! through silently: the extra keys of a tag-only variant (`[terrain.shape]
//! kind = "flat"` with `angle_deg = 30.0`) are dropped. The parsed scene is
//! written back to TOML and every key of the text that is missing from it is
//! refused, with its path and line.

use toml::de::{DeTable, DeValue};

use super::SceneError;

/// The first key of `text` that `kept` (the parsed scene written back as a
/// TOML table) does not have, as an error naming the key's path and line.
/// An empty array is not a key the scene drops: it is written back as nothing.
pub(crate) fn check_no_ignored_keys(text: &str, kept: &toml::Table) -> Result<(), SceneError> {
    let Ok(root) = DeTable::parse(text) else {
        return Ok(());
    };
    match first_ignored(root.get_ref(), kept, "") {
        Some((path, offset, allowed)) => {
            let line = text.as_bytes()[..offset.min(text.len())]
                .iter()
                .filter(|b| **b == b'\n')
                .count()
                + 1;
            Err(SceneError::Syntax {
                field: path,
                message: format!("this key is not used here (keys used: {allowed})"),
                line,
                column: 1,
            })
        }
        None => Ok(()),
    }
}

/// Path, byte offset and the kept keys of the first dropped key under `table`.
fn first_ignored(
    table: &DeTable<'_>,
    kept: &toml::Table,
    prefix: &str,
) -> Option<(String, usize, String)> {
    for (key, value) in table.iter() {
        let name = key.get_ref().as_ref();
        let path = if prefix.is_empty() {
            name.to_owned()
        } else {
            format!("{prefix}.{name}")
        };
        let Some(kept_value) = kept.get(name) else {
            if matches!(value.get_ref(), DeValue::Array(a) if a.is_empty()) {
                continue;
            }
            let allowed: Vec<&str> = kept.keys().map(String::as_str).collect();
            return Some((path, key.span().start, allowed.join(", ")));
        };
        let found = match (value.get_ref(), kept_value) {
            (DeValue::Table(t), toml::Value::Table(k)) => first_ignored(t, k, &path),
            (DeValue::Array(items), toml::Value::Array(k)) => {
                items.iter().zip(k).enumerate().find_map(|(i, (item, k))| {
                    match (item.get_ref(), k) {
                        (DeValue::Table(t), toml::Value::Table(k)) => {
                            first_ignored(t, k, &format!("{path}[{i}]"))
                        }
                        _ => None,
                    }
                })
            }
            _ => None,
        };
        if found.is_some() {
            return found;
        }
    }
    None
}
