//! What the foot rays see: the deformed terrain and the static meshes, through the BVH.

use engine::geom::{HitTarget, RayScene};
use glam::Vec2;

use crate::ground::{Ground, GroundHit};
use crate::terrain::Heightfield;

/// The ground of a scene: the terrain and the ray-cast scene (its grid BVH
/// and static meshes). Vertical rays return the closest surface below.
///
/// Beyond the terrain's edge the ground continues the edge's heights (the
/// query point is clamped into the grid), so a foot near an edge always finds
/// a surface instead of a void. Nothing there can be carved, so it gives
/// nothing: a foot beyond the edge stands on that surface, not below it.
#[derive(Clone, Copy)]
pub struct SceneGround<'a> {
    /// The ray-cast scene (grid BVH, meshes).
    pub scene: &'a RayScene,
    /// The terrain the grid BVH was built over.
    pub terrain: Option<&'a Heightfield>,
}

impl SceneGround<'_> {
    /// `(x, z)` clamped into the terrain's extent (unchanged without a terrain).
    fn clamped(&self, x: f32, z: f32) -> Vec2 {
        let p = Vec2::new(x, z);
        match self.terrain.map(Heightfield::grid) {
            Some(g) if p.is_finite() => p.clamp(g.origin(), g.origin() + g.extent()),
            _ => p,
        }
    }
}

impl Ground for SceneGround<'_> {
    fn cast_down(&self, x: f32, z: f32, from_y: f32) -> Option<GroundHit> {
        let at = self.clamped(x, z);
        let grid = self.terrain.map(Heightfield::grid);
        let hit = self.scene.cast_down(grid, at.x, at.y, from_y)?;
        // The smooth grid normal (not the triangle's) keeps the feet from
        // snapping between facets.
        // Loose ground gives under a foot; meshes do not.
        // Beyond the grid's edge (a clamped point) nothing can be carved.
        let (normal, give) = match (hit.target, self.terrain) {
            (HitTarget::Grid { .. }, Some(t)) => (
                t.grid().normal_at(at.x, at.y).unwrap_or(hit.normal),
                if at == Vec2::new(x, z) {
                    t.give_below(at.x, at.y, hit.point.y).unwrap_or(0.0)
                } else {
                    0.0
                },
            ),
            _ => (hit.normal, 0.0),
        };
        let mut point = hit.point;
        (point.x, point.z) = (x, z);
        Some(GroundHit {
            point,
            normal,
            give,
        })
    }
}
