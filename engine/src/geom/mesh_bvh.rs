use std::time::Duration;

use glam::{Vec3, Vec3A};
use obvhs::BvhBuildParams;
use obvhs::aabb::Aabb as ObAabb;
use obvhs::cwbvh::CwBvh;
use obvhs::cwbvh::builder::build_cwbvh;
use obvhs::ray::RayHit;

use super::grid_bvh::to_obvhs;
use super::ray::usable_max_t;
use super::{Aabb, GeomError, Hit, HitTarget, MeshId, Ray, TriMesh, ray_triangle};

/// A BVH over a static [`TriMesh`] (an obvhs compressed wide BVH).
///
/// Triangles are copied in traversal order; hits name the triangle's index in
/// the source mesh.
#[derive(Clone)]
pub struct MeshBvh {
    bvh: CwBvh,
    /// Triangle corners in BVH slot order.
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
        let bvh = build_cwbvh(
            &boxes,
            BvhBuildParams::medium_build(),
            &mut Duration::default(),
        );
        let source = bvh.primitive_indices.clone();
        let triangles = source.iter().map(|&k| corners[k as usize]).collect();
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
        if !usable_max_t(max_t) {
            return None;
        }
        let (o, d) = (Vec3A::from(ray.origin()), Vec3A::from(ray.dir()));
        let mut hit = RayHit::none();
        let found = self
            .bvh
            .ray_traverse(to_obvhs(ray, max_t), &mut hit, |r, slot| {
                ray_triangle(o, d, self.triangles[slot], r.tmax).unwrap_or(f32::INFINITY)
            });
        found.then(|| {
            let slot = hit.primitive_id as usize;
            let [a, b, c] = self.triangles[slot];
            Hit {
                point: ray.at(hit.t),
                normal: Vec3::from((b - a).cross(c - a)).normalize_or(Vec3::Y),
                distance: hit.t,
                target: HitTarget::Mesh {
                    mesh: self.id,
                    triangle: self.source[slot],
                },
            }
        })
    }

    /// True when `ray` meets the mesh within `max_t`.
    pub fn any_hit(&self, ray: &Ray, max_t: f32) -> bool {
        if !usable_max_t(max_t) {
            return false;
        }
        let (o, d) = (Vec3A::from(ray.origin()), Vec3A::from(ray.dir()));
        !self.bvh.ray_traverse_miss(to_obvhs(ray, max_t), |r, slot| {
            ray_triangle(o, d, self.triangles[slot], r.tmax).unwrap_or(f32::INFINITY)
        })
    }
}
