//! Triangle-mesh instances: one transform for the whole mesh, optionally one
//! more per named part (rigid-part characters: a capsule per bone).

use glam::{Mat3, Mat4, Vec3};
use rayon::prelude::*;

use super::Camera;
use super::batch::{CullMode, ScreenBatch, TriangleGroup, Viewport, to_clip};
use super::clip::ClipVertex;
use super::shading::{Lighting, encode_display};
use crate::geom::TriMesh;

/// Triangles per screen batch: the unit of parallel vertex work for big meshes.
const TRIANGLES_PER_BATCH: usize = 16_384;

/// A mesh placed in the frame.
#[derive(Debug, Clone, Copy)]
pub struct MeshInstance<'a> {
    /// The mesh (its triangles are counter-clockwise from the front).
    pub mesh: &'a TriMesh,
    /// Model-to-world transform of the whole mesh.
    pub transform: Mat4,
    /// Per-part transforms applied before `transform`, in the order of
    /// `mesh.parts`; empty (or too short) means identity for the missing parts.
    pub part_transforms: &'a [Mat4],
    /// Linear RGB albedo.
    pub color: Vec3,
    /// Facing to drop (back faces of closed meshes by default).
    pub cull: CullMode,
}

impl<'a> MeshInstance<'a> {
    /// A rigid instance of `mesh` with back-face culling.
    pub fn new(mesh: &'a TriMesh, transform: Mat4, color: Vec3) -> MeshInstance<'a> {
        MeshInstance {
            mesh,
            transform,
            part_transforms: &[],
            color,
            cull: CullMode::Back,
        }
    }

    /// The same instance with one transform per part (e.g. bone poses).
    pub fn with_parts(mut self, part_transforms: &'a [Mat4]) -> MeshInstance<'a> {
        self.part_transforms = part_transforms;
        self
    }

    /// The triangle ranges to draw with their own transforms.
    fn parts(&self) -> Vec<(std::ops::Range<usize>, Mat4)> {
        if self.mesh.parts.is_empty() {
            return vec![(0..self.mesh.triangles.len(), self.transform)];
        }
        self.mesh
            .parts
            .iter()
            .enumerate()
            .map(|(k, part)| {
                let local = self
                    .part_transforms
                    .get(k)
                    .copied()
                    .unwrap_or(Mat4::IDENTITY);
                (part.triangles.clone(), self.transform * local)
            })
            .collect()
    }

    /// Screen batches of at most [`TRIANGLES_PER_BATCH`] triangles per part,
    /// projected in parallel, in part order.
    pub(crate) fn batches(
        &self,
        camera: &Camera,
        lighting: &Lighting,
        vp: Viewport,
    ) -> Vec<ScreenBatch> {
        let view_proj = camera.view_proj();
        let mesh = self.mesh;
        let chunks: Vec<(std::ops::Range<usize>, Mat4)> = self
            .parts()
            .into_iter()
            .flat_map(|(range, model)| {
                range
                    .clone()
                    .step_by(TRIANGLES_PER_BATCH)
                    .map(move |start| (start..(start + TRIANGLES_PER_BATCH).min(range.end), model))
            })
            .collect();
        chunks
            .into_par_iter()
            .filter_map(|(range, model)| {
                let tris = mesh.triangles.get(range)?;
                let first = tris.iter().flatten().copied().min()? as usize;
                let last = tris.iter().flatten().copied().max()? as usize;
                let normal_matrix = Mat3::from_mat4(model).inverse().transpose();
                let verts: Vec<ClipVertex> = (first..=last)
                    .map(|v| {
                        let p = model.transform_point3(*mesh.positions.get(v)?);
                        let n = mesh.normals.get(v).copied().unwrap_or(Vec3::Y);
                        let n = (normal_matrix * n).normalize_or(Vec3::Y);
                        let sky = 0.65 + 0.35 * n.y;
                        let radiance = lighting.radiance(self.color, n, sky, 1.0);
                        Some(ClipVertex {
                            pos: to_clip(&view_proj, p),
                            color: lighting
                                .apply_fog(encode_display(radiance), (p - camera.eye).length()),
                        })
                    })
                    .collect::<Option<_>>()?;
                let local: Vec<[u32; 3]> =
                    tris.iter().map(|t| t.map(|v| v - first as u32)).collect();
                Some(ScreenBatch::build(
                    &verts,
                    &[TriangleGroup {
                        triangles: &local,
                        cull: self.cull,
                    }],
                    vp,
                ))
            })
            .collect()
    }
}
