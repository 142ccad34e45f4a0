use glam::{Affine3A, Mat4, Vec3, Vec3A};
use rayon::prelude::*;

use super::{AnimError, Skeleton, SkinnedMesh};

/// Vertices per task of the parallel skinning.
const CHUNK: usize = 1024;

/// Skinned positions and normals, one per vertex of a [`SkinnedMesh`].
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SkinnedVertices {
    /// Posed positions.
    pub positions: Vec<Vec3>,
    /// Posed unit normals.
    pub normals: Vec<Vec3>,
}

/// Writes each joint's skinning matrix (its global matrix times its inverse
/// bind matrix) into `out`, from the global matrices of a pose.
pub fn skin_matrices(skeleton: &Skeleton, globals: &[Mat4], out: &mut Vec<Affine3A>) {
    out.clear();
    out.extend(
        skeleton
            .joints()
            .iter()
            .zip(globals)
            .map(|(joint, global)| Affine3A::from_mat4(*global * joint.inverse_bind)),
    );
}

/// Linear blend skinning of `mesh` by `matrices` (from [`skin_matrices`]) into
/// `out`, parallel over vertices on the current rayon pool. Normals are moved by
/// the blended matrix's linear part and normalised (exact for rotations and
/// uniform scale). Refused if there are fewer matrices than the mesh's joints.
pub fn skin(
    mesh: &SkinnedMesh,
    matrices: &[Affine3A],
    out: &mut SkinnedVertices,
) -> Result<(), AnimError> {
    prepare(mesh, matrices, out)?;
    out.positions
        .par_chunks_mut(CHUNK)
        .zip(out.normals.par_chunks_mut(CHUNK))
        .enumerate()
        .for_each(|(c, (positions, normals))| {
            skin_range(mesh, matrices, c * CHUNK, positions, normals);
        });
    Ok(())
}

/// [`skin`] on the calling thread only.
pub fn skin_serial(
    mesh: &SkinnedMesh,
    matrices: &[Affine3A],
    out: &mut SkinnedVertices,
) -> Result<(), AnimError> {
    prepare(mesh, matrices, out)?;
    skin_range(mesh, matrices, 0, &mut out.positions, &mut out.normals);
    Ok(())
}

fn prepare(
    mesh: &SkinnedMesh,
    matrices: &[Affine3A],
    out: &mut SkinnedVertices,
) -> Result<(), AnimError> {
    if matrices.len() < mesh.joint_count() {
        return Err(AnimError::Length {
            what: "skinning matrices".to_string(),
            expected: mesh.joint_count(),
            found: matrices.len(),
        });
    }
    let n = mesh.vertex_count();
    out.positions.resize(n, Vec3::ZERO);
    out.normals.resize(n, Vec3::ZERO);
    Ok(())
}

/// Skins the vertices `first..first + positions.len()`.
fn skin_range(
    mesh: &SkinnedMesh,
    matrices: &[Affine3A],
    first: usize,
    positions: &mut [Vec3],
    normals: &mut [Vec3],
) {
    let range = first..first + positions.len();
    let sources = mesh.positions()[range.clone()]
        .iter()
        .zip(&mesh.normals()[range.clone()])
        .zip(&mesh.joints()[range.clone()])
        .zip(&mesh.weights()[range]);
    for ((((p, n), js), ws), (out_p, out_n)) in sources.zip(positions.iter_mut().zip(normals)) {
        let m = blend(matrices, js, ws);
        *out_p = Vec3::from(m.transform_point3a(Vec3A::from(*p)));
        *out_n = Vec3::from(m.matrix3 * Vec3A::from(*n)).normalize_or_zero();
    }
}

/// The weighted sum of a vertex's 4 joint matrices; joints of weight 0 are skipped.
#[inline(always)]
fn blend(matrices: &[Affine3A], joints: &[u16; 4], weights: &[f32; 4]) -> Affine3A {
    // Joint indices were checked against the mesh's joint count, and `prepare`
    // checked there are at least that many matrices.
    let first = &matrices[joints[0] as usize];
    let mut m = Affine3A {
        matrix3: first.matrix3 * weights[0],
        translation: first.translation * weights[0],
    };
    for (&j, &w) in joints.iter().zip(weights).skip(1) {
        if w != 0.0 {
            let a = &matrices[j as usize];
            m.matrix3 += a.matrix3 * w;
            m.translation += a.translation * w;
        }
    }
    m
}
