//! Triangle-mesh instances: one transform for the whole mesh, optionally one
//! more per named part (rigid-part characters: a capsule per bone).

use glam::{Mat3, Mat4, Vec3};
use rayon::prelude::*;

use super::frame_view::FrameView;
use super::raster::{ClipVertex, CullMode, TriangleBatch, TriangleGroup};
use super::shading::encode_display;
use crate::geom::TriMesh;

/// Triangles per batch: the unit of parallel vertex work for big meshes.
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
    /// Display-encoded RGB per vertex (indexed like `mesh.positions`) used
    /// instead of lighting `color`: baked or pre-lit colours. Fog still applies;
    /// vertices past the end of the slice are lit as usual.
    pub vertex_colors: Option<&'a [Vec3]>,
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
            vertex_colors: None,
        }
    }

    /// The same instance drawn with baked per-vertex display colours (see
    /// [`MeshInstance::vertex_colors`]) instead of lighting.
    pub fn with_vertex_colors(mut self, colors: &'a [Vec3]) -> MeshInstance<'a> {
        self.vertex_colors = Some(colors);
        self
    }

    /// The same instance with one transform per part (e.g. bone poses).
    pub fn with_parts(mut self, part_transforms: &'a [Mat4]) -> MeshInstance<'a> {
        self.part_transforms = part_transforms;
        self
    }

    /// The triangle ranges of its parts with the transforms placing them.
    pub(crate) fn placed_parts(&self) -> Vec<(std::ops::Range<usize>, Mat4)> {
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

    /// Its triangles in world space, each part placed by its transform.
    pub(crate) fn world_triangles(&self) -> impl Iterator<Item = [Vec3; 3]> + '_ {
        let positions = &self.mesh.positions;
        self.placed_parts()
            .into_iter()
            .flat_map(move |(range, model)| {
                self.mesh.triangles[range]
                    .iter()
                    .filter(|t| t.iter().all(|&k| (k as usize) < positions.len()))
                    .map(move |t| t.map(|k| model.transform_point3(positions[k as usize])))
            })
    }

    /// Its triangles in world space that may be the first surface the sun
    /// meets: all of them when both faces are drawn, only those facing
    /// `toward_sun` when back faces are culled (a closed mesh).
    pub(crate) fn sun_casters(&self, toward_sun: Vec3) -> impl Iterator<Item = [Vec3; 3]> + '_ {
        let closed = self.cull == CullMode::Back;
        self.world_triangles()
            .filter(move |[a, b, c]| !closed || (*b - *a).cross(*c - *a).dot(toward_sun) > 0.0)
    }

    /// Runs of at most [`TRIANGLES_PER_BATCH`] triangles of each part, in
    /// part order, with the part's transform: a batch each.
    fn runs(&self) -> Vec<(std::ops::Range<usize>, Mat4)> {
        self.placed_parts()
            .into_iter()
            .flat_map(|(range, model)| {
                range
                    .clone()
                    .step_by(TRIANGLES_PER_BATCH)
                    .map(move |start| (start..(start + TRIANGLES_PER_BATCH).min(range.end), model))
            })
            .collect()
    }

    /// The instance's batches as `view` sees them, one per run, in order.
    pub(crate) fn batches(&self, view: &FrameView<'_>) -> Vec<TriangleBatch> {
        self.runs()
            .par_iter()
            .filter_map(|run| self.batch(run, view))
            .collect()
    }

    /// A run's batch: its vertices placed, lit (or baked) and fogged, and its
    /// triangles; `None` when it has no triangles or indexes past the mesh's
    /// vertices.
    fn batch(
        &self,
        (range, model): &(std::ops::Range<usize>, Mat4),
        view: &FrameView<'_>,
    ) -> Option<TriangleBatch> {
        let mesh = self.mesh;
        let tris = mesh.triangles.get(range.clone())?;
        let indices = tris.as_flattened();
        let first = *indices.iter().min()?;
        let last = *indices.iter().max()? as usize;
        if last >= mesh.positions.len() {
            return None;
        }
        let normal_matrix = Mat3::from_mat4(*model).inverse().transpose();
        let eye = view.camera.eye;
        let lighting = view.lighting;
        let verts: Vec<ClipVertex> = (first as usize..=last)
            .map(|k| {
                let world = model.transform_point3(mesh.positions[k]);
                let baked = self.vertex_colors.and_then(|c| c.get(k)).copied();
                let color = baked.unwrap_or_else(|| {
                    let normal = mesh.normals.get(k).copied().unwrap_or(Vec3::Y);
                    let n = (normal_matrix * normal).normalize_or(Vec3::Y);
                    let sky = 0.65 + 0.35 * n.y;
                    let sun = view.sun_past_casters(world, n);
                    encode_display(lighting.radiance(self.color, n, sky, sun))
                });
                ClipVertex {
                    pos: view.view_proj * world.extend(1.0),
                    color: lighting.apply_fog(color, (world - eye).length()),
                    sun: Vec3::ZERO,
                }
            })
            .collect();
        let group = TriangleGroup {
            triangles: tris,
            cull: self.cull,
            first_vertex: first,
        };
        Some(TriangleBatch::build(&verts, &[group], None, view.vp))
    }
}

#[cfg(test)]
mod tests {
    use glam::{Mat4, Vec3};

    use crate::geom::TriMesh;
    use crate::render::{Camera, FrameScene, Lighting, MeshInstance, Renderer, encode_display};

    /// A bumpy 12 x 12 sheet facing up, seen from above and in front.
    fn sheet() -> (TriMesh, Camera) {
        let n = 12u32;
        let positions = (0..n * n)
            .map(|k| {
                let (i, j) = ((k % n) as f32, (k / n) as f32);
                Vec3::new(
                    i / 11.0 - 0.5,
                    0.05 * (i * 1.3).sin() * (j * 0.9).cos(),
                    j / 11.0 - 0.5,
                )
            })
            .collect();
        let mut triangles = Vec::new();
        for j in 0..n - 1 {
            for i in 0..n - 1 {
                let a = j * n + i;
                triangles.push([a, a + n + 1, a + 1]);
                triangles.push([a, a + n, a + n + 1]);
            }
        }
        let mesh = TriMesh::new(positions, triangles).unwrap();
        let camera = Camera::perspective(0.9, 64, 48, 0.05, 50.0)
            .unwrap()
            .look_at(Vec3::new(0.0, 0.9, -0.9), Vec3::ZERO, Vec3::Y);
        (mesh, camera)
    }

    #[test]
    fn baked_colours_equal_to_the_lighting_draw_the_same_image() {
        let (mesh, camera) = sheet();
        let lighting = Lighting::default();
        let albedo = Vec3::new(0.6, 0.5, 0.3);
        // What the mesh path computes per vertex before fog (identity transform).
        let baked: Vec<Vec3> = mesh
            .normals
            .iter()
            .map(|&n| {
                let n = n.normalize_or(Vec3::Y);
                encode_display(lighting.radiance(albedo, n, 0.65 + 0.35 * n.y, 1.0))
            })
            .collect();
        let lit = [MeshInstance::new(&mesh, Mat4::IDENTITY, albedo)];
        let pre_lit =
            [MeshInstance::new(&mesh, Mat4::IDENTITY, Vec3::ONE).with_vertex_colors(&baked)];
        let renderer = Renderer::new(64, 48).unwrap();
        let render = |meshes: &[MeshInstance<'_>]| {
            renderer.render(
                &FrameScene {
                    meshes,
                    lighting,
                    // The bumpy sheet would shade itself where baked colours cannot.
                    shadows: false,
                    ..FrameScene::new()
                },
                &camera,
            )
        };
        let (a, b) = (render(&lit), render(&pre_lit));
        assert!(
            a.pixels().filter(|p| p.0 != b.get_pixel(0, 0).0).count() > 500,
            "the sheet is drawn"
        );
        assert_eq!(a, b);
        // A different baked colour shows.
        let red = vec![Vec3::X; mesh.positions.len()];
        let red_sheet = [MeshInstance::new(&mesh, Mat4::IDENTITY, albedo).with_vertex_colors(&red)];
        let c = render(&red_sheet);
        assert_eq!(c.get_pixel(32, 30).0, [255, 0, 0, 255]);
    }
}
