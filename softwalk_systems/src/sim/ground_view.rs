//! What the foot rays see: the deformed terrain and the static meshes, through the BVH.

use engine::geom::{HeightGrid, RayScene};

use crate::ground::{Ground, GroundHit};

/// The ground of a scene: the terrain's grid and the ray-cast scene (its grid
/// BVH and static meshes). Vertical rays return the closest surface below.
#[derive(Clone, Copy)]
pub struct SceneGround<'a> {
    /// The ray-cast scene (grid BVH, meshes).
    pub scene: &'a RayScene,
    /// The terrain heights the grid BVH was built over.
    pub grid: Option<&'a HeightGrid>,
}

impl Ground for SceneGround<'_> {
    fn cast_down(&self, x: f32, z: f32, from_y: f32) -> Option<GroundHit> {
        let hit = self.scene.cast_down(self.grid, x, z, from_y)?;
        // The smooth grid normal (not the triangle's) keeps the feet from
        // snapping between facets.
        let normal = match hit.target {
            engine::geom::HitTarget::Grid { .. } => self
                .grid
                .and_then(|g| g.normal_at(x, z))
                .unwrap_or(hit.normal),
            _ => hit.normal,
        };
        Some(GroundHit {
            point: hit.point,
            normal,
        })
    }
}
