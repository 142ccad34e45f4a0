//! Small range checks that produce [`SceneError::Invalid`] with the field named.

use super::SceneError;

/// Refuses NaN and infinities.
pub(crate) fn finite(field: &str, value: f32) -> Result<f32, SceneError> {
    if value.is_nan() {
        Err(SceneError::invalid(field, "NaN is not allowed"))
    } else if value.is_infinite() {
        Err(SceneError::invalid(
            field,
            format!("{value} is not allowed (must be finite)"),
        ))
    } else {
        Ok(value)
    }
}

/// A finite value in `[min, max]`.
pub(crate) fn in_range(field: &str, value: f32, min: f32, max: f32) -> Result<f32, SceneError> {
    finite(field, value)?;
    bounded(field, value, min, max)
}

/// A finite value in `(0, max]`.
pub(crate) fn positive(field: &str, value: f32, max: f32) -> Result<f32, SceneError> {
    finite(field, value)?;
    if value <= 0.0 {
        Err(SceneError::invalid(
            field,
            format!("{value} must be > 0; allowed (0, {max}]"),
        ))
    } else if value > max {
        Err(SceneError::invalid(
            field,
            format!("{value} exceeds the maximum {max}; allowed (0, {max}]"),
        ))
    } else {
        Ok(value)
    }
}

/// An integer in `[min, max]`.
pub(crate) fn count_in_range(
    field: &str,
    value: u32,
    min: u32,
    max: u32,
) -> Result<u32, SceneError> {
    bounded(field, value, min, max)
}

/// `value` within `[min, max]`, or an error naming `field` and the bound it crossed.
fn bounded<T: PartialOrd + std::fmt::Display>(
    field: &str,
    value: T,
    min: T,
    max: T,
) -> Result<T, SceneError> {
    if value < min {
        Err(SceneError::invalid(
            field,
            format!("{value} must be >= {min}; allowed [{min}, {max}]"),
        ))
    } else if value > max {
        Err(SceneError::invalid(
            field,
            format!("{value} exceeds the maximum {max}; allowed [{min}, {max}]"),
        ))
    } else {
        Ok(value)
    }
}

/// A finite interval `[lo, hi]` with `lo < hi`, inside `[min, max]`.
pub(crate) fn interval(field: &str, value: [f32; 2], min: f32, max: f32) -> Result<(), SceneError> {
    in_range(&format!("{field}[0]"), value[0], min, max)?;
    in_range(&format!("{field}[1]"), value[1], min, max)?;
    if value[0] >= value[1] {
        return Err(SceneError::invalid(
            field,
            format!(
                "[{}, {}] must have its first bound below its second",
                value[0], value[1]
            ),
        ));
    }
    Ok(())
}

/// A point `[x, z]` on the terrain, `[0, size_x] x [0, size_z]`.
pub(crate) fn on_terrain(field: &str, p: [f32; 2], size: [f32; 2]) -> Result<(), SceneError> {
    in_range(&format!("{field}[0]"), p[0], 0.0, size[0])?;
    in_range(&format!("{field}[1]"), p[1], 0.0, size[1])?;
    Ok(())
}

/// At most `max` entries in the array `field`; the first one too many is named.
pub(crate) fn count_at_most(field: &str, len: usize, max: usize) -> Result<(), SceneError> {
    if len > max {
        return Err(SceneError::invalid(
            format!("{field}[{max}]"),
            format!("{len} entries; at most {max} are accepted"),
        ));
    }
    Ok(())
}

/// Every component finite.
pub(crate) fn finite3(field: &str, v: [f32; 3]) -> Result<(), SceneError> {
    for (k, c) in v.iter().enumerate() {
        finite(&format!("{field}[{k}]"), *c)?;
    }
    Ok(())
}

/// A name made of ASCII letters, digits, `-` and `_` (safe in CSV and file names).
pub(crate) fn identifier(field: &str, name: &str) -> Result<(), SceneError> {
    if name.is_empty() {
        return Err(SceneError::invalid(field, "must not be empty"));
    }
    if let Some(c) = name
        .chars()
        .find(|c| !(c.is_ascii_alphanumeric() || *c == '-' || *c == '_'))
    {
        return Err(SceneError::invalid(
            field,
            format!("\"{name}\" contains {c:?}; use letters, digits, '-' and '_'"),
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn messages_name_the_problem() {
        assert_eq!(
            positive("sim.dt", 0.0, 1.0).unwrap_err().to_string(),
            "sim.dt: 0 must be > 0; allowed (0, 1]"
        );
        assert_eq!(
            finite("characters[1].alpha", f32::NAN)
                .unwrap_err()
                .to_string(),
            "characters[1].alpha: NaN is not allowed"
        );
        assert_eq!(
            count_in_range("terrain.resolution", 100000, 2, 8192)
                .unwrap_err()
                .to_string(),
            "terrain.resolution: 100000 exceeds the maximum 8192; allowed [2, 8192]"
        );
        assert!(interval("x", [2.0, 1.0], 0.0, 10.0).is_err());
        assert!(interval("x", [1.0, 2.0], 0.0, 10.0).is_ok());
        assert!(identifier("n", "a b").is_err());
        assert!(identifier("n", "walker-1_b").is_ok());
    }
}
