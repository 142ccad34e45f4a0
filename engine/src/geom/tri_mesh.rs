use glam::Vec3;

use super::GeomError;

/// A named run of triangles inside a [`TriMesh`]: an OBJ object or group, or a
/// character part named after its bone.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct MeshPart {
    /// The part's name (for characters, the bone it follows).
    pub name: String,
    /// Range of triangle indices (into [`TriMesh::triangles`]) of this part.
    pub triangles: std::ops::Range<usize>,
}

/// An indexed triangle mesh with per-vertex normals and named parts.
///
/// Shared by the ray-cast scene, the OBJ loader and the renderer.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct TriMesh {
    /// Vertex positions.
    pub positions: Vec<Vec3>,
    /// Unit vertex normals, one per position.
    pub normals: Vec<Vec3>,
    /// Triangles as three vertex indices, counter-clockwise seen from the front.
    pub triangles: Vec<[u32; 3]>,
    /// Named parts covering the triangles in order. May be empty (one anonymous part).
    pub parts: Vec<MeshPart>,
}

impl TriMesh {
    /// A mesh from positions and triangles, with area-weighted vertex normals,
    /// after checking that it is non-empty, finite and in range.
    pub fn new(positions: Vec<Vec3>, triangles: Vec<[u32; 3]>) -> Result<Self, GeomError> {
        let mut mesh = TriMesh {
            positions,
            normals: Vec::new(),
            triangles,
            parts: Vec::new(),
        };
        mesh.validate()?;
        mesh.compute_normals();
        Ok(mesh)
    }

    /// Checks that the mesh has triangles, finite positions and in-range indices.
    pub fn validate(&self) -> Result<(), GeomError> {
        if self.triangles.is_empty() || self.positions.is_empty() {
            return Err(GeomError::InvalidParameter {
                name: "mesh",
                reason: "the mesh has no triangles".into(),
            });
        }
        if let Some(k) = self.positions.iter().position(|p| !p.is_finite()) {
            return Err(GeomError::InvalidParameter {
                name: "positions",
                reason: format!("vertex {k} is {}", self.positions[k]),
            });
        }
        let n = self.positions.len() as u32;
        if let Some(t) = self
            .triangles
            .iter()
            .position(|t| t.iter().any(|&v| v >= n))
        {
            return Err(GeomError::InvalidParameter {
                name: "triangles",
                reason: format!("triangle {t} indexes past the {n} vertices"),
            });
        }
        if !self.normals.is_empty() && self.normals.len() != self.positions.len() {
            return Err(GeomError::InvalidParameter {
                name: "normals",
                reason: format!(
                    "{} normals for {} vertices",
                    self.normals.len(),
                    self.positions.len()
                ),
            });
        }
        Ok(())
    }

    /// Recomputes vertex normals as the area-weighted mean of face normals.
    pub fn compute_normals(&mut self) {
        let mut normals = vec![Vec3::ZERO; self.positions.len()];
        for t in &self.triangles {
            let [a, b, c] = t.map(|v| self.positions[v as usize]);
            let n = (b - a).cross(c - a);
            for &v in t {
                normals[v as usize] += n;
            }
        }
        for n in &mut normals {
            *n = n.try_normalize().unwrap_or(Vec3::Y);
        }
        self.normals = normals;
    }

    /// The part with this name, if any.
    pub fn part(&self, name: &str) -> Option<&MeshPart> {
        self.parts.iter().find(|p| p.name == name)
    }

    /// Appends another mesh (its parts keep their names).
    pub fn append(&mut self, other: &TriMesh) {
        let base = self.positions.len() as u32;
        let tri_base = self.triangles.len();
        self.positions.extend_from_slice(&other.positions);
        self.normals.extend_from_slice(&other.normals);
        self.triangles
            .extend(other.triangles.iter().map(|t| t.map(|v| v + base)));
        self.parts.extend(other.parts.iter().map(|p| MeshPart {
            name: p.name.clone(),
            triangles: p.triangles.start + tri_base..p.triangles.end + tri_base,
        }));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn validates_and_computes_normals() {
        let m = TriMesh::new(vec![Vec3::ZERO, Vec3::X, Vec3::Z], vec![[0, 2, 1]]).unwrap();
        assert!((m.normals[0] - Vec3::Y).length() < 1e-6);
        assert!(TriMesh::new(vec![Vec3::ZERO], vec![[0, 1, 2]]).is_err());
        assert!(TriMesh::new(vec![Vec3::NAN, Vec3::X, Vec3::Z], vec![[0, 1, 2]]).is_err());
        assert!(TriMesh::new(vec![], vec![]).is_err());
    }
}
