//! Ground materials: the library's presets plus the scene's `[[materials]]`.
//!
//! Each `[[materials]]` entry deserialises straight into a
//! [`TerrainMaterial`] (`depth` is the paper's d_t: a print is 0.1 m x d_t
//! deep; `layer` is the loose layer's thickness in metres, optional: a
//! preset's name keeps the preset's, another name gets the print depth). This file only checks entries with the field path prefixed and
//! assembles the [`MaterialTable`] a terrain indexes.

use softwalk_systems::terrain::{MaterialTable, TerrainError, TerrainMaterial};

use super::SceneError;
use super::check::identifier;

/// Checks one user material; `field` is its path, e.g. `materials[0]`.
pub(crate) fn validate_material(field: &str, material: &TerrainMaterial) -> Result<(), SceneError> {
    identifier(&format!("{field}.name"), &material.name)?;
    material.validate().map_err(|e| material_error(field, e))
}

/// A library refusal as an error on `field.<material field>`.
fn material_error(field: &str, error: TerrainError) -> SceneError {
    match error {
        TerrainError::InvalidMaterial {
            field: name,
            reason,
            ..
        } => SceneError::invalid(format!("{field}.{name}"), reason),
        other => SceneError::invalid(field, other.to_string()),
    }
}

/// The presets (sand, soil, mud, snow) with `user` materials after them; a
/// user material named like a preset replaces it in place.
pub(crate) fn material_table(user: &[TerrainMaterial]) -> Result<MaterialTable, SceneError> {
    let mut all: Vec<TerrainMaterial> = MaterialTable::with_presets().materials().to_vec();
    for m in user {
        match all.iter_mut().find(|p| p.name == m.name) {
            Some(preset) => *preset = m.clone(),
            None => all.push(m.clone()),
        }
    }
    MaterialTable::try_from(all).map_err(|e| SceneError::invalid("materials", e.to_string()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn user_materials_extend_or_replace_the_presets() {
        let mut ash = TerrainMaterial::soil();
        ash.name = "ash".into();
        let mut wet_sand = TerrainMaterial::dry_sand();
        wet_sand.depth = 0.2;
        let table = material_table(&[ash, wet_sand]).unwrap();
        let names: Vec<&str> = table.materials().iter().map(|m| m.name.as_str()).collect();
        assert_eq!(names, ["sand", "soil", "mud", "snow", "ash"]);
        assert_eq!(table.by_name("sand").unwrap().depth, 0.2);
    }

    #[test]
    fn bad_fields_carry_the_path() {
        let mut m = TerrainMaterial::mud();
        m.gait.speed_scale = f32::NAN;
        let e = validate_material("materials[2]", &m).unwrap_err();
        assert_eq!(e.field(), Some("materials[2].gait.speed_scale"));
        m = TerrainMaterial::mud();
        m.name = "wet mud".into();
        let e = validate_material("materials[0]", &m).unwrap_err();
        assert_eq!(e.field(), Some("materials[0].name"));
    }
}
