//! The table of materials a terrain's per-sample material map indexes.

use serde::{Deserialize, Serialize};

use super::error::TerrainError;
use super::material::TerrainMaterial;

/// Index of a material in a [`MaterialTable`] (one byte per terrain sample).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
pub struct MaterialId(pub u8);

/// Up to 256 validated materials with unique names, in insertion order.
///
/// Serialised as a list of materials; deserialising validates every entry
/// like [`MaterialTable::add`].
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(try_from = "Vec<TerrainMaterial>", into = "Vec<TerrainMaterial>")]
pub struct MaterialTable {
    materials: Vec<TerrainMaterial>,
}

impl TryFrom<Vec<TerrainMaterial>> for MaterialTable {
    type Error = TerrainError;

    /// A table of `materials` in order, each validated (ids follow the order).
    fn try_from(materials: Vec<TerrainMaterial>) -> Result<Self, TerrainError> {
        let mut table = MaterialTable::new();
        for m in materials {
            table.add(m)?;
        }
        Ok(table)
    }
}

impl From<MaterialTable> for Vec<TerrainMaterial> {
    fn from(table: MaterialTable) -> Self {
        table.materials
    }
}

impl MaterialTable {
    /// An empty table.
    pub fn new() -> Self {
        Self::default()
    }

    /// The paper's presets: sand (id 0), soil (1), mud (2), snow (3).
    pub fn with_presets() -> Self {
        MaterialTable {
            materials: TerrainMaterial::presets().into(),
        }
    }

    /// Adds a material after validating it; refuses duplicate names and a 257th entry.
    pub fn add(&mut self, material: TerrainMaterial) -> Result<MaterialId, TerrainError> {
        material.validate()?;
        if self.materials.iter().any(|m| m.name == material.name) {
            return Err(TerrainError::DuplicateMaterial(material.name));
        }
        let id = u8::try_from(self.materials.len()).map_err(|_| TerrainError::TooManyMaterials)?;
        self.materials.push(material);
        Ok(MaterialId(id))
    }

    /// The id of the material called `name`.
    pub fn id(&self, name: &str) -> Result<MaterialId, TerrainError> {
        self.materials
            .iter()
            .position(|m| m.name == name)
            .map(|k| MaterialId(k as u8))
            .ok_or_else(|| TerrainError::UnknownMaterial {
                name: name.to_owned(),
                known: self
                    .materials
                    .iter()
                    .map(|m| m.name.as_str())
                    .collect::<Vec<_>>()
                    .join(", "),
            })
    }

    /// The material with this id, or an error when the id is out of range.
    pub fn get(&self, id: MaterialId) -> Result<&TerrainMaterial, TerrainError> {
        self.materials
            .get(id.0 as usize)
            .ok_or(TerrainError::UnknownMaterialId {
                id: id.0,
                len: self.materials.len(),
            })
    }

    /// The material called `name`.
    pub fn by_name(&self, name: &str) -> Result<&TerrainMaterial, TerrainError> {
        self.get(self.id(name)?)
    }

    /// All materials, indexed by id.
    pub fn materials(&self) -> &[TerrainMaterial] {
        &self.materials
    }

    /// Number of materials.
    pub fn len(&self) -> usize {
        self.materials.len()
    }

    /// True when the table holds no material.
    pub fn is_empty(&self) -> bool {
        self.materials.is_empty()
    }

    /// The largest smoothness s_t in the table (0 when empty).
    pub fn max_smoothness(&self) -> f32 {
        self.materials
            .iter()
            .map(|m| m.smoothness)
            .fold(0.0, f32::max)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::terrain::GaitResponse;

    #[test]
    fn lookup_by_name_and_errors() {
        let mut t = MaterialTable::with_presets();
        assert_eq!(t.id("mud").unwrap(), MaterialId(2));
        assert_eq!(t.by_name("snow").unwrap().depth, 3.0);
        let e = t.id("lava").unwrap_err();
        assert!(e.to_string().contains("lava") && e.to_string().contains("sand"));
        assert!(matches!(
            t.add(TerrainMaterial::soil()),
            Err(TerrainError::DuplicateMaterial(_))
        ));
        let mut gravel = TerrainMaterial::soil();
        gravel.name = "gravel".into();
        gravel.smoothness = -1.0;
        assert!(t.add(gravel.clone()).is_err());
        gravel.smoothness = 1.0;
        assert_eq!(t.add(gravel).unwrap(), MaterialId(4));
        assert!(t.get(MaterialId(9)).is_err());
        assert_eq!(t.max_smoothness(), 4.0);
    }

    #[test]
    fn tables_load_from_data_and_are_validated() {
        let json = serde_json::to_string(&MaterialTable::with_presets()).unwrap();
        let back: MaterialTable = serde_json::from_str(&json).unwrap();
        assert_eq!(back, MaterialTable::with_presets());
        let custom = r#"[{"name": "gravel", "depth": 0.2, "compression": 0.5,
            "smoothness": 1.0, "repose_deg": 40.0}]"#;
        let t: MaterialTable = serde_json::from_str(custom).unwrap();
        assert_eq!(t.by_name("gravel").unwrap().gait, GaitResponse::NEUTRAL);
        let bad = custom.replace("0.5", "2.5");
        let e = serde_json::from_str::<MaterialTable>(&bad).unwrap_err();
        assert!(e.to_string().contains("compression"), "{e}");
        let twice = format!("[{0}, {0}]", &custom[1..custom.len() - 1]);
        assert!(serde_json::from_str::<MaterialTable>(&twice).is_err());
    }

    #[test]
    fn table_is_capped_at_256() {
        let mut t = MaterialTable::new();
        for k in 0..256 {
            let mut m = TerrainMaterial::soil();
            m.name = format!("m{k}");
            t.add(m).unwrap();
        }
        let mut m = TerrainMaterial::soil();
        m.name = "one too many".into();
        assert_eq!(t.add(m), Err(TerrainError::TooManyMaterials));
    }
}
