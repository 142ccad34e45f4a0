use std::time::Duration;

use glam::{Vec3, Vec3A};
use obvhs::BvhBuildParams;
use obvhs::aabb::Aabb as ObAabb;
use obvhs::bvh2::builder::build_bvh2;

use super::ray::usable_max_t;
use super::triangle::ray_triangle_edges;
use super::wide_bvh::WideBvh;
use super::{Aabb, GeomError, Hit, HitTarget, MeshId, Ray, TriMesh};

/// Build preset: obvhs's medium preset with leaves of at most 4 triangles,
/// collapsed at a lower traversal cost than the preset's: with 4-wide nodes a
/// node test is cheap next to a triangle test (chosen by measurement).
const LEAF_BUILD: BvhBuildParams = BvhBuildParams {
    max_prims_per_leaf: 4,
    collapse_traversal_cost: 2.0,
    ..BvhBuildParams::medium_build()
};

/// A BVH over a static [`TriMesh`]: an obvhs PLOC binary BVH (medium preset)
/// collapsed into a 4-wide BVH with full-precision boxes.
///
/// Triangles are copied in traversal order, prepared as a corner and two
/// edges; hits name the triangle's index in the source mesh.
#[derive(Clone)]
pub struct MeshBvh {
    bvh: WideBvh,
    /// Triangles in BVH slot order, as `[a, b - a, c - a]`.
    triangles: Vec<[Vec3A; 3]>,
    /// Source triangle index of each slot.
    source: Vec<u32>,
    bounds: Aabb,
    id: MeshId,
}

impl std::fmt::Debug for MeshBvh {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("MeshBvh")
            .field("id", &self.id)
            .field("triangles", &self.triangles.len())
            .field("bounds", &self.bounds)
            .finish()
    }
}

impl MeshBvh {
    /// Builds the BVH after checking the mesh (non-empty, finite, indices in range).
    /// Hits carry `MeshId(0)` until [`MeshBvh::with_id`] says otherwise.
    pub fn build(mesh: &TriMesh) -> Result<MeshBvh, GeomError> {
        mesh.validate()?;
        let corners: Vec<[Vec3A; 3]> = mesh
            .triangles
            .iter()
            .map(|t| t.map(|v| Vec3A::from(mesh.positions[v as usize])))
            .collect();
        let bounds = Aabb::from_points(&mesh.positions);
        // Boxes padded so that a ray lying exactly in a box face (an axis-aligned
        // ray on a shared edge or on the mesh's outer face) is never rejected.
        let scale = bounds.min.abs().max(bounds.max.abs()).max_element();
        let pad = Vec3A::splat(1e-5 * scale.max(1e-3));
        let boxes: Vec<ObAabb> = corners
            .iter()
            .map(|&[a, b, c]| ObAabb::new(a.min(b).min(c) - pad, a.max(b).max(c) + pad))
            .collect();
        let bvh2 = build_bvh2(&boxes, LEAF_BUILD, &mut Duration::default());
        let bvh = WideBvh::from_bvh2(&bvh2);
        let source = bvh2.primitive_indices;
        let triangles = source
            .iter()
            .map(|&k| {
                let [a, b, c] = corners[k as usize];
                [a, b - a, c - a]
            })
            .collect();
        Ok(MeshBvh {
            bvh,
            triangles,
            source,
            bounds,
            id: MeshId(0),
        })
    }

    /// The same BVH, reporting hits as mesh `id`.
    pub fn with_id(mut self, id: MeshId) -> MeshBvh {
        self.id = id;
        self
    }

    /// The id hits carry.
    pub fn id(&self) -> MeshId {
        self.id
    }

    /// Bounding box of the mesh.
    pub fn bounds(&self) -> Aabb {
        self.bounds
    }

    /// Number of triangles.
    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    /// The closest hit of `ray` within `max_t` (triangles are two-sided).
    pub fn cast(&self, ray: &Ray, max_t: f32) -> Option<Hit> {
        let (t, slot) = self.traverse::<false>(ray, max_t)?;
        let [_, e1, e2] = self.triangles[slot];
        Some(Hit {
            point: ray.at(t),
            normal: Vec3::from(e1.cross(e2)).normalize_or(Vec3::Y),
            distance: t,
            target: HitTarget::Mesh {
                mesh: self.id,
                triangle: self.source[slot],
            },
        })
    }

    /// True when `ray` meets the mesh within `max_t`.
    pub fn any_hit(&self, ray: &Ray, max_t: f32) -> bool {
        self.traverse::<true>(ray, max_t).is_some()
    }

    /// The closest (or with `ANY` the first found) hit as `(distance, slot)`.
    fn traverse<const ANY: bool>(&self, ray: &Ray, max_t: f32) -> Option<(f32, usize)> {
        if !usable_max_t(max_t) {
            return None;
        }
        let (o, d) = (Vec3A::from(ray.origin()), Vec3A::from(ray.dir()));
        self.bvh.traverse::<ANY>(o, d, max_t, |slot, t_max| {
            ray_triangle_edges(o, d, self.triangles[slot], t_max)
        })
    }
}
