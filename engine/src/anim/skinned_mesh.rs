use glam::Vec3;

use super::AnimError;

/// How far a vertex's weights may sum from 1 and still be accepted.
pub const WEIGHT_SUM_TOLERANCE: f32 = 0.01;

/// A triangle mesh bound to a skeleton: each vertex follows up to 4 joints.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SkinnedMesh {
    positions: Vec<Vec3>,
    normals: Vec<Vec3>,
    indices: Vec<u32>,
    joints: Vec<[u16; 4]>,
    weights: Vec<[f32; 4]>,
    joint_count: usize,
}

impl SkinnedMesh {
    /// A mesh in its bind pose for a skeleton of `joint_count` joints: one
    /// position, normal, 4 joint indices and 4 weights per vertex, and 3 indices
    /// per triangle. Weights must sum to 1 within `WEIGHT_SUM_TOLERANCE` and are
    /// then rescaled to sum to exactly 1; normals are normalised.
    pub fn new(
        positions: Vec<Vec3>,
        normals: Vec<Vec3>,
        indices: Vec<u32>,
        joints: Vec<[u16; 4]>,
        mut weights: Vec<[f32; 4]>,
        joint_count: usize,
    ) -> Result<SkinnedMesh, AnimError> {
        let n = positions.len();
        for (what, len) in [
            ("normals", normals.len()),
            ("joint indices", joints.len()),
            ("weights", weights.len()),
        ] {
            if len != n {
                return Err(AnimError::Length {
                    what: what.to_string(),
                    expected: n,
                    found: len,
                });
            }
        }
        if !indices.len().is_multiple_of(3) {
            return Err(AnimError::Length {
                what: "triangle indices".to_string(),
                expected: indices.len() / 3 * 3,
                found: indices.len(),
            });
        }
        check_finite(&positions, "position")?;
        check_finite(&normals, "normal")?;
        check_indices(&indices, n)?;
        check_joints(&joints, &weights, joint_count)?;
        normalise_weights(&mut weights)?;
        let normals = normals.iter().map(|v| v.normalize_or_zero()).collect();
        Ok(SkinnedMesh {
            positions,
            normals,
            indices,
            joints,
            weights,
            joint_count,
        })
    }

    /// Bind-pose positions.
    pub fn positions(&self) -> &[Vec3] {
        &self.positions
    }

    /// Bind-pose unit normals.
    pub fn normals(&self) -> &[Vec3] {
        &self.normals
    }

    /// Triangle corners, 3 per triangle.
    pub fn indices(&self) -> &[u32] {
        &self.indices
    }

    /// 4 joint indices per vertex.
    pub fn joints(&self) -> &[[u16; 4]] {
        &self.joints
    }

    /// 4 weights per vertex, summing to 1.
    pub fn weights(&self) -> &[[f32; 4]] {
        &self.weights
    }

    /// How many joints the skeleton it is bound to has.
    pub fn joint_count(&self) -> usize {
        self.joint_count
    }

    /// How many vertices it has.
    pub fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    /// How many triangles it has.
    pub fn triangle_count(&self) -> usize {
        self.indices.len() / 3
    }
}

fn check_finite(values: &[Vec3], what: &str) -> Result<(), AnimError> {
    match values.iter().position(|v| !v.is_finite()) {
        Some(k) => Err(AnimError::NonFinite {
            what: format!("{what} {k}"),
        }),
        None => Ok(()),
    }
}

fn check_indices(indices: &[u32], vertices: usize) -> Result<(), AnimError> {
    match indices.iter().position(|&v| v as usize >= vertices) {
        Some(corner) => Err(AnimError::VertexOutOfRange {
            corner,
            vertex: indices[corner],
            vertices,
        }),
        None => Ok(()),
    }
}

fn check_joints(
    joints: &[[u16; 4]],
    weights: &[[f32; 4]],
    joint_count: usize,
) -> Result<(), AnimError> {
    for (vertex, (js, ws)) in joints.iter().zip(weights).enumerate() {
        if let Some(&joint) = js.iter().find(|&&j| j as usize >= joint_count) {
            return Err(AnimError::JointOutOfRange {
                vertex,
                joint: joint as usize,
                joints: joint_count,
            });
        }
        if ws.iter().any(|w| !w.is_finite() || *w < 0.0) {
            return Err(AnimError::NonFinite {
                what: format!("a weight of vertex {vertex} (or it is negative)"),
            });
        }
    }
    Ok(())
}

fn normalise_weights(weights: &mut [[f32; 4]]) -> Result<(), AnimError> {
    for (vertex, w) in weights.iter_mut().enumerate() {
        let sum: f32 = w.iter().sum();
        if (sum - 1.0).abs() > WEIGHT_SUM_TOLERANCE {
            return Err(AnimError::WeightSum { vertex, sum });
        }
        for x in w.iter_mut() {
            *x /= sum;
        }
    }
    Ok(())
}
