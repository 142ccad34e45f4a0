//! Triangle-mesh instances: one transform for the whole mesh, optionally one
//! more per named part (rigid-part characters: a capsule per bone).

use glam::{Mat4, Vec3};
use multiversion::multiversion;

use super::batch::{BatchTarget, CullMode, TriangleGroup};
use super::mesh_shader::MeshShader;
use super::project::TransformedPoints;
use super::scene_geometry::{FrameView, SceneGeometry};
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

    /// Runs of at most [`TRIANGLES_PER_BATCH`] triangles of each part, in
    /// part order, with the part's transform: a batch each.
    fn runs(&self) -> Vec<(std::ops::Range<usize>, Mat4)> {
        self.parts()
            .into_iter()
            .flat_map(|(range, model)| {
                range
                    .clone()
                    .step_by(TRIANGLES_PER_BATCH)
                    .map(move |start| (start..(start + TRIANGLES_PER_BATCH).min(range.end), model))
            })
            .collect()
    }

    /// What a run's batch is built from: its vertices placed and lit, and
    /// its triangles; `None` when it has no triangles or indexes past the
    /// mesh's vertices.
    fn run_sources(
        &self,
        (range, model): &(std::ops::Range<usize>, Mat4),
        view: &FrameView<'_>,
    ) -> Option<(TransformedPoints<'a>, MeshShader<'a>, TriangleGroup<'a>)> {
        let mesh = self.mesh;
        let tris = mesh.triangles.get(range.clone())?;
        let (first, last) = index_range(tris)?;
        let (first, last) = (first as usize, last as usize);
        if last >= mesh.positions.len() {
            return None;
        }
        // The batch's run of a per-vertex slice (shorter when the slice ends
        // inside the run).
        let run = |s: &'a [Vec3]| &s[first.min(s.len())..(last + 1).min(s.len())];
        let positions =
            TransformedPoints::new(&mesh.positions[first..=last], *model, view.view_proj);
        let shader = MeshShader::new(
            positions,
            run(&mesh.normals),
            self.vertex_colors.map(run),
            self.color,
            *view.lighting,
            view.camera.eye,
        );
        let group = TriangleGroup {
            triangles: tris,
            cull: self.cull,
            first_vertex: first as u32,
        };
        Some((positions, shader, group))
    }
}

/// A piece per run of at most [`TRIANGLES_PER_BATCH`] triangles of each
/// part, in part order.
impl SceneGeometry for MeshInstance<'_> {
    type Piece = (std::ops::Range<usize>, Mat4);

    fn pieces(&self, _view: &FrameView<'_>) -> Vec<Self::Piece> {
        self.runs()
    }

    fn build(
        &self,
        run: &Self::Piece,
        view: &FrameView<'_>,
        target: BatchTarget<'_, '_>,
    ) -> Option<usize> {
        let (positions, shader, group) = self.run_sources(run, view)?;
        Some(target.build_shaded(positions, shader, &[group], view.vp, view.kernels))
    }
}

/// The smallest and largest vertex index of `triangles` (`None` when empty).
///
/// Compiled for AVX2 too (picked at run time), whose `u32` minimum and
/// maximum take eight indices per instruction; baseline SSE2 has none.
#[multiversion(targets("x86_64+avx2"))]
fn index_range(triangles: &[[u32; 3]]) -> Option<(u32, u32)> {
    let indices = triangles.as_flattened();
    let first = *indices.first()?;
    // A plain loop, which the compiler turns into vector minima and maxima
    // (an iterator adapter such as `fold` would stay out of line, in
    // baseline code).
    let (mut min, mut max) = (first, first);
    for &index in indices {
        min = min.min(index);
        max = max.max(index);
    }
    Some((min, max))
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
    fn index_range_is_the_smallest_and_largest_index() {
        use super::index_range;
        use crate::rng::SplitMix64;
        assert_eq!(index_range(&[]), None);
        let mut rng = SplitMix64::new(7);
        for len in [1usize, 2, 3, 5, 8, 9, 40] {
            for spread in [10u32, 1 << 20, u32::MAX] {
                let tris: Vec<[u32; 3]> = (0..len)
                    .map(|_| [(); 3].map(|_| (rng.next_u64() as u32) % spread.max(1)))
                    .collect();
                let flat = tris.iter().flatten().copied();
                let expected = (flat.clone().min().unwrap(), flat.max().unwrap());
                assert_eq!(index_range(&tris), Some(expected), "{tris:?}");
            }
        }
        assert_eq!(
            index_range(&[[u32::MAX, 0, 1 << 31], [(1 << 31) - 1, 5, 6]]),
            Some((0, u32::MAX))
        );
        // Around the largest index exact as `f32`, and past it.
        let edge = 1u32 << 24;
        for (tris, expected) in [
            ([[edge - 1, edge - 2, 7]], (7, edge - 1)),
            ([[edge + 1, edge, 7]], (7, edge + 1)),
            ([[edge + 3, edge + 1, edge + 2]], (edge + 1, edge + 3)),
            ([[1 << 31, 3, 2]], (2, 1 << 31)),
        ] {
            assert_eq!(index_range(&tris), Some(expected));
        }
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
