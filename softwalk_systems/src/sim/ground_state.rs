//! [`GroundState`]: the one resource that owns the ground: the height field,
//! this step's change log and the ray-cast scene.

use engine::geom::{GeomError, GridRect, Hit, MeshId, Ray, RayScene, TriMesh};

use super::ground_view::SceneGround;
use crate::terrain::{DirtyRects, Heightfield, StepChanges};

/// Stale rectangles the BVH keeps before it refits them without being asked
/// (so the list stays short when no general ray is cast for a long time).
const MAX_STALE_RECTS: usize = 4096;

/// Resource: the ground of a simulation.
///
/// - the [`Heightfield`] (heights, materials, trodden mask) with its change
///   log for this step ([`StepChanges`]: a list of changed rectangles merged
///   only where they overlap or touch, the held samples and the volumes);
/// - the ray-cast scene ([`RayScene`]: the grid BVH and the static meshes);
/// - the rectangles changed since the renderer last looked
///   ([`GroundState::take_unseen`]);
/// - the terrain's total volume, kept up to date from what each step carved
///   and compacted (not by summing the grid).
///
/// Vertical rays ([`GroundState::view`]) go straight to the grid cell under
/// them and never need the grid BVH's bounds; a general ray
/// ([`GroundState::cast`]) first refits the tiles changed since the last
/// refit, so the BVH costs nothing while no such ray is cast.
#[derive(Debug)]
pub struct GroundState {
    terrain: Heightfield,
    scene: RayScene,
    stale: DirtyRects,
    unseen: DirtyRects,
    volume: f64,
}

impl GroundState {
    /// The ground over `terrain`, its grid BVH built, no meshes.
    pub fn new(terrain: Heightfield) -> Self {
        let mut scene = RayScene::new();
        scene.set_grid(terrain.grid());
        let volume = terrain.grid().volume();
        GroundState {
            terrain,
            scene,
            stale: DirtyRects::new(),
            unseen: DirtyRects::new(),
            volume,
        }
    }

    /// Replaces the height field (meshes are kept); rebuilds the grid BVH,
    /// the volume, and forgets the change logs.
    pub fn set_terrain(&mut self, terrain: Heightfield) {
        self.scene.set_grid(terrain.grid());
        self.volume = terrain.grid().volume();
        self.terrain = terrain;
        self.stale.clear();
        self.unseen.clear();
    }

    /// The height field.
    pub fn terrain(&self) -> &Heightfield {
        &self.terrain
    }

    /// The height field, writable. Report what you edit with
    /// [`Heightfield::mark_dirty`], or use [`GroundState::edit_heights`],
    /// which does it and keeps the volume.
    pub fn terrain_mut(&mut self) -> &mut Heightfield {
        &mut self.terrain
    }

    /// What changed this step (the rectangles, held samples and volumes).
    pub fn changes(&self) -> &StepChanges {
        self.terrain.changes()
    }

    /// The rectangles changed this step (merged where they overlap or touch
    /// once the step's `refit` system has run).
    pub fn changed_rects(&self) -> impl Iterator<Item = GridRect> + '_ {
        self.terrain.changes().rects.iter()
    }

    /// Sets each height inside `rect` (clipped to the grid) with
    /// `f(i, j, &mut height)`; marks the rectangle changed and adds the
    /// volume difference to [`GroundState::volume`].
    pub fn edit_heights(&mut self, rect: GridRect, mut f: impl FnMut(usize, usize, &mut f32)) {
        let grid = self.terrain.grid_mut();
        let rect = rect.intersect(&grid.full_rect());
        if rect.is_empty() {
            return;
        }
        let nx = grid.nx();
        let heights = grid.heights_mut();
        let mut added = 0.0f64;
        for (i, j) in rect.iter() {
            let h = &mut heights[j * nx + i];
            let before = *h;
            f(i, j, h);
            added += f64::from(*h) - f64::from(before);
        }
        let cell = f64::from(self.terrain.grid().cell_size());
        self.volume += added * cell * cell;
        self.terrain.mark_dirty(rect);
    }

    /// Paints material `id` on every sample within `radius` metres of
    /// `centre` (x, z) and marks the area for the renderer to redraw;
    /// heights are untouched, so the simulation's ray structure stays valid.
    pub fn paint_disc(
        &mut self,
        centre: glam::Vec2,
        radius: f32,
        id: crate::terrain::MaterialId,
    ) -> Result<(), crate::terrain::TerrainError> {
        if let Some(rect) = self.terrain.paint_disc(centre, radius, id)? {
            self.unseen.add(rect);
        }
        Ok(())
    }

    /// The terrain's total volume, cubic metres.
    pub fn volume(&self) -> f64 {
        self.volume
    }

    /// Adds `delta` cubic metres to the tracked volume (for stages that
    /// report their own volumes, such as carving).
    pub fn add_volume(&mut self, delta: f64) {
        self.volume += delta;
    }

    /// Adds a static mesh (rocks, steps) the feet can stand on.
    pub fn add_mesh(&mut self, mesh: TriMesh) -> Result<MeshId, GeomError> {
        self.scene.add_mesh(mesh)
    }

    /// The ray-cast scene. Its grid BVH may be stale where heights changed
    /// since the last refit: cast general rays with [`GroundState::cast`].
    pub fn scene(&self) -> &RayScene {
        &self.scene
    }

    /// What the foot rays see: vertical rays onto the terrain and the meshes.
    pub fn view(&self) -> SceneGround<'_> {
        SceneGround {
            scene: &self.scene,
            terrain: Some(&self.terrain),
        }
    }

    /// Closes the step's change log: its rectangles join the stale tiles of
    /// the BVH and the rectangles the renderer has not seen. Refits the BVH
    /// when the stale list grows long.
    pub fn end_step(&mut self) {
        self.terrain.merge_dirty();
        let rects = &self.terrain.changes().rects;
        self.stale.extend(rects);
        self.unseen.extend(rects);
        if self.stale.merged().len() > MAX_STALE_RECTS {
            self.refit();
        }
    }

    /// Refits the grid BVH over every rectangle changed since the last refit.
    pub fn refit(&mut self) {
        for rect in self.stale.take() {
            self.scene.refit_grid(self.terrain.grid(), rect);
        }
    }

    /// True when the grid BVH matches the heights (nothing left to refit).
    pub fn is_refit(&self) -> bool {
        self.stale.is_empty()
    }

    /// The closest hit of a general `ray` within `max_t` over the terrain and
    /// the meshes (refits the BVH first where it is stale).
    pub fn cast(&mut self, ray: &Ray, max_t: f32) -> Option<Hit> {
        self.refit();
        self.scene.cast(Some(self.terrain.grid()), ray, max_t)
    }

    /// The rectangles changed since the last call, none overlapping or
    /// touching another (for the renderer's re-meshing).
    pub fn take_unseen(&mut self) -> Vec<GridRect> {
        self.unseen.take()
    }

    /// Forgets the rectangles the renderer has not seen (a consumer that
    /// starts from the current heights).
    pub fn clear_unseen(&mut self) {
        self.unseen.clear();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::terrain::generate::{GridSpec, flat};
    use crate::terrain::{MaterialId, MaterialTable};

    fn ground() -> GroundState {
        let grid = flat(GridSpec::square(4.0, 101), 1.0).unwrap();
        let hf =
            Heightfield::from_grid(grid, MaterialTable::with_presets(), MaterialId(0)).unwrap();
        GroundState::new(hf)
    }

    #[test]
    fn edits_are_logged_refit_lazily_and_handed_to_the_renderer_once() {
        let mut g = ground();
        let v0 = g.volume();
        let cell = f64::from(g.terrain().grid().cell_size());
        g.terrain_mut().begin_step();
        g.edit_heights(GridRect::new(10, 10, 12, 12), |_, _, h| *h += 0.5);
        g.edit_heights(GridRect::new(80, 80, 81, 81), |_, _, h| *h -= 0.25);
        assert!((g.volume() - v0 - (4.0 * 0.5 - 0.25) * cell * cell).abs() < 1e-9);
        assert_eq!(g.changed_rects().count(), 2);
        g.end_step();
        // The BVH is stale until a general ray needs it.
        assert!(!g.is_refit());
        let down = Ray::new(glam::Vec3::new(0.44, 5.0, 0.44), glam::Vec3::NEG_Y).unwrap();
        let hit = g.cast(&down, 10.0).unwrap();
        assert!(g.is_refit());
        assert!((hit.point.y - 1.5).abs() < 1e-4, "{}", hit.point.y);
        let unseen = g.take_unseen();
        assert_eq!(unseen.len(), 2);
        assert!(g.take_unseen().is_empty());
    }
}
