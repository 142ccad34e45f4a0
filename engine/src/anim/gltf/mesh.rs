use glam::Vec3;
use gltf::Semantic;
use gltf::mesh::Mode;

use super::GltfError;
use super::accessor::AccessorReader;
use crate::anim::SkinnedMesh;

/// The primitives of `meshes`, merged into one [`SkinnedMesh`] whose joint indices
/// are skeleton joints (`skin_to_joint` maps the skin's joint list onto them).
/// Normals missing from a primitive are computed (area-weighted smooth normals).
pub(super) fn skinned_mesh(
    meshes: &[gltf::Mesh],
    skin_to_joint: &[usize],
    joint_count: usize,
    reader: &AccessorReader,
) -> Result<SkinnedMesh, GltfError> {
    let path = reader.path;
    let mut merged = Merged::default();
    for mesh in meshes {
        for primitive in mesh.primitives() {
            let part = format!("mesh {} primitive {}", mesh.index(), primitive.index());
            merged.append(&primitive, &part, skin_to_joint, reader)?;
        }
    }
    let indices: Vec<String> = meshes.iter().map(|m| m.index().to_string()).collect();
    let part = match indices.len() {
        1 => format!("mesh {}", indices[0]),
        _ => format!("meshes {}", indices.join(", ")),
    };
    SkinnedMesh::new(
        merged.positions,
        merged.normals,
        merged.indices,
        merged.joints,
        merged.weights,
        joint_count,
    )
    .map_err(|e| GltfError::from_anim(path, &part, e))
}

/// The primitives read so far.
#[derive(Default)]
struct Merged {
    positions: Vec<Vec3>,
    normals: Vec<Vec3>,
    indices: Vec<u32>,
    joints: Vec<[u16; 4]>,
    weights: Vec<[f32; 4]>,
}

impl Merged {
    /// Reads `primitive` (named `part` in errors) and appends it, its skin
    /// joints mapped onto skeleton joints through `skin_to_joint`.
    fn append(
        &mut self,
        primitive: &gltf::Primitive,
        part: &str,
        skin_to_joint: &[usize],
        reader: &AccessorReader,
    ) -> Result<(), GltfError> {
        let path = reader.path;
        let read = PrimitiveData::read(primitive, part, reader)?;
        let first_vertex = self.positions.len();
        let base = first_vertex as u32;
        self.indices.extend(read.indices.iter().map(|&i| base + i));
        self.positions.extend(read.positions);
        self.normals.extend(read.normals);
        self.weights.extend(read.weights);
        for (vertex, js) in read.joints.iter().enumerate() {
            let mapped = map_joints(js, skin_to_joint).ok_or_else(|| {
                let joint = js
                    .iter()
                    .copied()
                    .find(|&j| j as usize >= skin_to_joint.len())
                    .unwrap_or(0);
                GltfError::JointOutOfRange {
                    path: path.to_path_buf(),
                    part: format!("{part} JOINTS_0"),
                    vertex: first_vertex + vertex,
                    joint: joint as usize,
                    joints: skin_to_joint.len(),
                }
            })?;
            self.joints.push(mapped);
        }
        Ok(())
    }
}

/// One triangle primitive's vertices as read, joints still skin-joint indices.
struct PrimitiveData {
    positions: Vec<Vec3>,
    normals: Vec<Vec3>,
    indices: Vec<u32>,
    joints: Vec<[u32; 4]>,
    weights: Vec<[f32; 4]>,
}

impl PrimitiveData {
    /// Reads and checks a triangle primitive's positions, skin joints and weights,
    /// indices (or one per vertex) and normals (or smooth ones computed).
    fn read(
        primitive: &gltf::Primitive,
        part: &str,
        reader: &AccessorReader,
    ) -> Result<Self, GltfError> {
        let path = reader.path;
        if primitive.mode() != Mode::Triangles {
            return Err(GltfError::Unsupported {
                path: path.to_path_buf(),
                part: part.to_string(),
                reason: format!("mode {:?} (only triangles)", primitive.mode()),
            });
        }
        let attribute = |semantic: Semantic, name: &str| {
            primitive
                .get(&semantic)
                .ok_or_else(|| GltfError::MissingSkin {
                    path: path.to_path_buf(),
                    reason: format!("{part} has no {name}"),
                })
        };
        let positions: Vec<Vec3> = reader
            .floats::<3>(
                &attribute(Semantic::Positions, "POSITION")?,
                &format!("{part} POSITION"),
            )?
            .into_iter()
            .map(Vec3::from)
            .collect();
        let joints = reader.uints::<4>(
            &attribute(Semantic::Joints(0), "JOINTS_0")?,
            &format!("{part} JOINTS_0"),
        )?;
        let weights = reader.floats::<4>(
            &attribute(Semantic::Weights(0), "WEIGHTS_0")?,
            &format!("{part} WEIGHTS_0"),
        )?;
        let indices = match primitive.indices() {
            Some(a) => reader
                .uints::<1>(&a, &format!("{part} indices"))?
                .into_iter()
                .map(|[i]| i)
                .collect(),
            None => (0..positions.len() as u32).collect::<Vec<u32>>(),
        };
        let normals = match primitive.get(&Semantic::Normals) {
            Some(a) => reader
                .floats::<3>(&a, &format!("{part} NORMAL"))?
                .into_iter()
                .map(Vec3::from)
                .collect(),
            None => smooth_normals(&positions, &indices),
        };
        let data = PrimitiveData {
            positions,
            normals,
            indices,
            joints,
            weights,
        };
        data.check(part, reader)?;
        Ok(data)
    }

    /// Every attribute has one value per position, and every index names a vertex.
    fn check(&self, part: &str, reader: &AccessorReader) -> Result<(), GltfError> {
        let n = self.positions.len();
        for (what, len) in [
            ("NORMAL", self.normals.len()),
            ("JOINTS_0", self.joints.len()),
            ("WEIGHTS_0", self.weights.len()),
        ] {
            if len != n {
                return Err(reader.invalid(part, format!("{len} {what} for {n} positions")));
            }
        }
        if let Some(k) = self.indices.iter().position(|&i| i as usize >= n) {
            return Err(reader.invalid(
                part,
                format!(
                    "index {k} names vertex {}, past {n} vertices",
                    self.indices[k]
                ),
            ));
        }
        Ok(())
    }
}

/// A vertex's skin-joint indices as skeleton joint indices; `None` if one is
/// past the skin's joint list.
fn map_joints(joints: &[u32; 4], skin_to_joint: &[usize]) -> Option<[u16; 4]> {
    let mut out = [0u16; 4];
    for (o, &j) in out.iter_mut().zip(joints) {
        let joint = *skin_to_joint.get(j as usize)?;
        *o = u16::try_from(joint).ok()?;
    }
    Some(out)
}

/// Area-weighted smooth vertex normals of a triangle list.
fn smooth_normals(positions: &[Vec3], indices: &[u32]) -> Vec<Vec3> {
    let mut normals = vec![Vec3::ZERO; positions.len()];
    for t in indices.chunks_exact(3) {
        let [a, b, c] = [t[0], t[1], t[2]].map(|i| i as usize);
        if a.max(b).max(c) >= positions.len() {
            continue;
        }
        let n = (positions[b] - positions[a]).cross(positions[c] - positions[a]);
        for v in [a, b, c] {
            normals[v] += n;
        }
    }
    normals.iter().map(|n| n.normalize_or_zero()).collect()
}
