//! The line of a scene field, found from its dotted path (`characters[1].body.beta`).
//!
//! The TOML text is parsed once more with spans; the path is followed key by
//! key and index by index as far as the text spells it out. A field left to
//! its default is not in the text: its line is the line of the nearest table
//! that is.

use toml::de::{DeTable, DeValue};

/// 1-based line of `field` in `text`, or of the deepest table on its path
/// that the text contains; `None` when the text does not parse.
pub(crate) fn field_line(text: &str, field: &str) -> Option<usize> {
    let root = DeTable::parse(text).ok()?;
    let mut offset = None;
    let mut table: Option<&DeTable<'_>> = Some(root.get_ref());
    let mut value: Option<&DeValue<'_>> = None;
    for segment in segments(field) {
        let found = match segment {
            Segment::Key(key) => table.and_then(|t| {
                t.iter()
                    .find(|(k, _)| k.get_ref().as_ref() == key)
                    .map(|(k, v)| (k.span().start, v))
            }),
            Segment::Index(index) => match value {
                Some(DeValue::Array(items)) => items.get(index).map(|v| (v.span().start, v)),
                _ => None,
            },
        };
        let Some((start, next)) = found else { break };
        offset = Some(start);
        value = Some(next.get_ref());
        table = match next.get_ref() {
            DeValue::Table(t) => Some(t),
            _ => None,
        };
    }
    let offset = offset?.min(text.len());
    Some(
        text.as_bytes()[..offset]
            .iter()
            .filter(|b| **b == b'\n')
            .count()
            + 1,
    )
}

/// One step of a field path.
enum Segment<'a> {
    /// A table key.
    Key(&'a str),
    /// An array index.
    Index(usize),
}

/// `a.b[2].c` as `Key(a), Key(b), Index(2), Key(c)`.
fn segments(field: &str) -> Vec<Segment<'_>> {
    let mut out = Vec::new();
    for part in field.split('.') {
        let mut rest = part;
        if let Some(open) = rest.find('[') {
            out.push(Segment::Key(&rest[..open]));
            rest = &rest[open..];
            while let Some(close) = rest.find(']') {
                if let Ok(index) = rest[1..close].parse() {
                    out.push(Segment::Index(index));
                }
                rest = &rest[close + 1..];
            }
        } else {
            out.push(Segment::Key(rest));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    const TEXT: &str = "name = \"x\"\n[terrain]\nsize_x = 1\n[[characters]]\nname = \"a\"\n[[characters]]\nname = \"b\"\n[characters.path]\nlength = 3\npoints = [[1, 2],\n [3, 4]]\n";

    #[test]
    fn lines_follow_keys_and_indices() {
        assert_eq!(field_line(TEXT, "name"), Some(1));
        assert_eq!(field_line(TEXT, "terrain.size_x"), Some(3));
        assert_eq!(field_line(TEXT, "characters[1].name"), Some(7));
        assert_eq!(field_line(TEXT, "characters[1].path.length"), Some(9));
        assert_eq!(field_line(TEXT, "characters[1].path.points[1]"), Some(11));
        assert_eq!(
            field_line(TEXT, "characters[1].path.points[1][0]"),
            Some(11)
        );
    }

    #[test]
    fn a_default_field_points_at_its_table() {
        assert_eq!(field_line(TEXT, "terrain.size_z"), Some(2));
        assert_eq!(field_line("x = [", "x"), None);
    }
}
