//! The `Heightfield` component: a height grid with a material per sample,
//! the initial surface (over firm ground, a loose layer per material), a
//! trodden-ground mask and a per-step change record (a list of changed rectangles).

use engine::geom::{GridRect, HeightGrid};
use glam::Vec2;

use super::dirty_rects::DirtyRects;
use super::error::TerrainError;
use super::held::{HeldMask, HeldSamples};
use super::material::TerrainMaterial;
use super::material_table::{MaterialId, MaterialTable};
use super::pending_settle::PendingSettle;

/// `disturbed` value of a sample pressed by a sole.
pub const DISTURBED_PRESSED: u8 = 255;
/// `disturbed` value of a sample in a print's rim.
pub const DISTURBED_RIM: u8 = 128;
/// `disturbed` value of a sample moved by settling.
pub const DISTURBED_SLUMPED: u8 = 32;

/// What the terrain stages changed since [`Heightfield::begin_step`].
///
/// Volumes are in cubic metres, accumulated in `f64`.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct StepChanges {
    /// The rectangles whose samples changed, merged only where they overlap or touch.
    pub rects: DirtyRects,
    /// One rectangle per [`super::carve`] call that touched the ground this
    /// step (a foot pressing, or the print of a foot that lifted), in call order.
    pub carved: Vec<GridRect>,
    /// The window of each [`super::smooth`] call this step, in call order
    /// (the smooth system calls it once per carved rectangle, same order).
    pub smoothed: Vec<GridRect>,
    /// Volume removed from contact samples by carving.
    pub carved_volume: f64,
    /// Part of the carved volume compacted (lost): c_t of it.
    pub compacted_volume: f64,
    /// Part of the carved volume pushed onto the rims: 1 - c_t of it.
    pub rim_volume: f64,
    /// Samples held by a foot: everything its current contact has pressed so far
    /// (smoothing and settling leave them alone until the foot lifts).
    pub held: HeldSamples,
    /// The rectangles released this step by feet that lifted (see
    /// [`super::carve`]): their settling starts in the next step
    /// ([`super::settle_step`]), as the release step already smooths them.
    pub released: DirtyRects,
    /// Pairwise transfers made by settling.
    pub settle_transfers: usize,
    /// Samples visited by settling sweeps (its work).
    pub settle_visits: usize,
    /// Smoothing calls whose passes were cut at
    /// [`super::MAX_SMOOTHING_PASSES`] (their variance fell short).
    pub smoothing_capped: usize,
}

impl StepChanges {
    /// Empties the record, keeping its buffers (every field is named, so a
    /// new one cannot be forgotten).
    pub fn clear(&mut self) {
        let StepChanges {
            rects,
            carved,
            smoothed,
            carved_volume,
            compacted_volume,
            rim_volume,
            held,
            released,
            settle_transfers,
            settle_visits,
            smoothing_capped,
        } = self;
        rects.clear();
        carved.clear();
        smoothed.clear();
        held.clear();
        released.clear();
        (*carved_volume, *compacted_volume, *rim_volume) = (0.0, 0.0, 0.0);
        (*settle_transfers, *settle_visits, *smoothing_capped) = (0, 0, 0);
    }
}

/// A deformable loose ground: heights, a material per sample and the trodden mask.
///
/// It remembers the surface it was created with: each sample's material is a
/// loose layer of [`TerrainMaterial::layer`] metres over firm ground, so its
/// firm floor ([`Heightfield::firm_floor`]) is its initial height minus the
/// layer of its current material (painting a material moves the floor with
/// it). Carving, compaction and settling never take a sample below its floor.
///
/// Every stage that edits heights reports the edited rectangle through
/// [`Heightfield::mark_dirty`]; it joins this step's list of changed
/// rectangles ([`StepChanges::rects`]), which the BVH refit and the render
/// patches read.
#[derive(Debug, Clone)]
pub struct Heightfield {
    grid: HeightGrid,
    /// The heights at creation (same layout as `grid`).
    initial: HeightGrid,
    table: MaterialTable,
    material: Vec<u8>,
    disturbed: Vec<u8>,
    held_mask: HeldMask,
    changes: StepChanges,
    pending_settle: Vec<PendingSettle>,
}

impl Heightfield {
    /// A terrain over `grid`, every sample of material `fill` from `table`.
    pub fn from_grid(
        grid: HeightGrid,
        table: MaterialTable,
        fill: MaterialId,
    ) -> Result<Self, TerrainError> {
        table.get(fill)?;
        let n = grid.nx() * grid.nz();
        Ok(Heightfield {
            initial: grid.clone(),
            grid,
            table,
            material: vec![fill.0; n],
            disturbed: vec![0; n],
            held_mask: HeldMask::new(n),
            changes: StepChanges::default(),
            pending_settle: Vec::new(),
        })
    }

    /// The heights.
    pub fn grid(&self) -> &HeightGrid {
        &self.grid
    }

    /// The heights, writable. Report what you edit with [`Heightfield::mark_dirty`].
    pub fn grid_mut(&mut self) -> &mut HeightGrid {
        &mut self.grid
    }

    /// The heights the terrain was created with (the same grid shape as
    /// [`Heightfield::grid`]).
    pub fn initial(&self) -> &HeightGrid {
        &self.initial
    }

    /// The firm floor of sample index `k`: its initial height minus the layer
    /// of its material. Nothing but the user (through [`Heightfield::grid_mut`])
    /// takes a sample below it.
    #[inline]
    pub fn firm_floor(&self, k: usize) -> f32 {
        self.initial.heights()[k] - self.material_of(k).layer
    }

    /// How far a planted sole can still press the surface at world `(x, z)`,
    /// metres: [`Heightfield::give_below`] the surface there; `None` off the grid.
    pub fn give_at(&self, x: f32, z: f32) -> Option<f32> {
        self.give_below(x, z, self.grid.height_at(x, z)?)
    }

    /// How far a sole standing at height `surface` over world `(x, z)` can
    /// press the ground, metres: the material's print depth (nearest sample),
    /// or less where the loose layer between `surface` and the firm floor
    /// (interpolated like the surface) is thinner; never below 0. `None` off
    /// the grid. Measured from the surface a ray found, so surface minus give
    /// is never below the firm floor, even on a print's wall.
    pub fn give_below(&self, x: f32, z: f32, surface: f32) -> Option<f32> {
        let k = self.nearest_index(x, z)?;
        let material = self.material_of(k);
        let firm_floor = self.initial.height_at(x, z)? - material.layer;
        Some(material.print_depth().min(surface - firm_floor).max(0.0))
    }

    /// Index of the sample nearest to world `(x, z)`, or `None` off the grid.
    fn nearest_index(&self, x: f32, z: f32) -> Option<usize> {
        if !self.grid.contains_xz(x, z) {
            return None;
        }
        let g = self.grid.to_grid(x, z).round();
        Some(self.grid.index(g.x as usize, g.y as usize))
    }

    /// The material table the material map indexes.
    pub fn table(&self) -> &MaterialTable {
        &self.table
    }

    /// Per-sample material ids, row-major like the heights.
    pub fn material_map(&self) -> &[u8] {
        &self.material
    }

    /// Per-sample trodden amount, row-major: 0 untouched, [`DISTURBED_SLUMPED`]
    /// slumped, [`DISTURBED_RIM`] rim, [`DISTURBED_PRESSED`] pressed by a sole;
    /// samples moved by smoothing take half their neighbours' level, so the
    /// amount fades over a few samples around each print.
    pub fn disturbed(&self) -> &[u8] {
        &self.disturbed
    }

    /// The material of sample index `k` (row-major).
    #[inline]
    pub fn material_of(&self, k: usize) -> &TerrainMaterial {
        &self.table.materials()[self.material[k] as usize]
    }

    /// The material of the sample nearest to world `(x, z)`, or `None` off the grid.
    pub fn material_at(&self, x: f32, z: f32) -> Option<&TerrainMaterial> {
        self.nearest_index(x, z).map(|k| self.material_of(k))
    }

    /// Print depth in metres of the material under world `(x, z)`.
    pub fn print_depth_at(&self, x: f32, z: f32) -> Option<f32> {
        self.material_at(x, z).map(TerrainMaterial::print_depth)
    }

    /// Lowest height among the samples inside the world XZ box `[min, max]`,
    /// or `None` when the box holds no sample (for measuring prints).
    pub fn lowest_in(&self, min: Vec2, max: Vec2) -> Option<f32> {
        let rect = self.grid.rect_covering(min, max);
        (!rect.is_empty()).then(|| self.grid.min_max_in(&rect).0)
    }

    /// Sets every sample inside `rect` (clipped to the grid) to material `id`.
    pub fn paint_rect(&mut self, rect: GridRect, id: MaterialId) -> Result<(), TerrainError> {
        self.table.get(id)?;
        let rect = rect.intersect(&self.grid.full_rect());
        let nx = self.grid.nx();
        for j in rect.j0..rect.j1 {
            self.material[j * nx + rect.i0..j * nx + rect.i1].fill(id.0);
        }
        Ok(())
    }

    /// Sets every sample within `radius` metres of `centre` (x, z) to
    /// material `id`; returns the grid rectangle it covered (`None` when the
    /// disc misses the grid or `radius` is not a positive number).
    pub fn paint_disc(
        &mut self,
        centre: Vec2,
        radius: f32,
        id: MaterialId,
    ) -> Result<Option<GridRect>, TerrainError> {
        self.table.get(id)?;
        if !(radius > 0.0 && radius.is_finite() && centre.is_finite()) {
            return Ok(None);
        }
        let reach = Vec2::splat(radius);
        let rect = self.grid.rect_covering(centre - reach, centre + reach);
        if rect.is_empty() {
            return Ok(None);
        }
        let nx = self.grid.nx();
        for (i, j) in rect.iter() {
            let p = self.grid.sample_position(i, j);
            if Vec2::new(p.x, p.z).distance(centre) <= radius {
                self.material[j * nx + i] = id.0;
            }
        }
        Ok(Some(rect))
    }

    /// Sets each sample's material to `f(x, z)` (world position); the map is
    /// left unchanged if `f` returns an id not in the table.
    pub fn paint_fn(
        &mut self,
        mut f: impl FnMut(f32, f32) -> MaterialId,
    ) -> Result<(), TerrainError> {
        let (nx, nz) = (self.grid.nx(), self.grid.nz());
        let mut map = Vec::with_capacity(nx * nz);
        for j in 0..nz {
            for i in 0..nx {
                let p = self.grid.sample_position(i, j);
                let id = f(p.x, p.z);
                self.table.get(id)?;
                map.push(id.0);
            }
        }
        self.material = map;
        Ok(())
    }

    /// Splits the terrain into `ids.len()` equal bands along X, the first band
    /// at the smallest X.
    pub fn paint_bands_x(&mut self, ids: &[MaterialId]) -> Result<(), TerrainError> {
        if ids.is_empty() {
            return Err(TerrainError::InvalidParameter {
                name: "ids",
                reason: "no material given for the bands".into(),
            });
        }
        let nx = self.grid.nx();
        for (b, &id) in ids.iter().enumerate() {
            let i0 = b * nx / ids.len();
            let i1 = (b + 1) * nx / ids.len();
            self.paint_rect(GridRect::new(i0, 0, i1, self.grid.nz()), id)?;
        }
        Ok(())
    }

    /// Adds `rect` to this step's changed rectangles (what caches must redo).
    pub fn mark_dirty(&mut self, rect: GridRect) {
        self.changes.rects.add(rect);
    }

    /// The rectangles changed since the last [`Heightfield::begin_step`]
    /// (merged as of the last [`Heightfield::merge_dirty`]).
    pub fn dirty(&self) -> &DirtyRects {
        &self.changes.rects
    }

    /// Merges this step's changed rectangles where they overlap or touch.
    pub fn merge_dirty(&mut self) {
        self.changes.rects.merge();
    }

    /// What changed since the last [`Heightfield::begin_step`].
    pub fn changes(&self) -> &StepChanges {
        &self.changes
    }

    /// Starts a new step record, emptying the previous one in place (its
    /// buffers are reused). Call it once at the start of every fixed step,
    /// before carving (the held samples of the last step are released).
    pub fn begin_step(&mut self) {
        self.held_mask.clear(self.changes.held.all());
        self.changes.clear();
    }

    /// True while settling work left by [`super::settle_step`] waits for
    /// [`super::settle_pending`] (a released print still slumping).
    pub fn settling_pending(&self) -> bool {
        !self.pending_settle.is_empty()
    }

    /// The settling work left for later steps.
    pub(crate) fn pending_settle_mut(&mut self) -> &mut Vec<PendingSettle> {
        &mut self.pending_settle
    }

    /// Mutable access for the stages: heights, materials, disturbed mask, step record.
    pub(crate) fn parts_mut(&mut self) -> TerrainParts<'_> {
        let nx = self.grid.nx();
        TerrainParts {
            heights: self.grid.heights_mut(),
            initial: self.initial.heights(),
            nx,
            table: &self.table,
            material: &self.material,
            disturbed: &mut self.disturbed,
            held_mask: &mut self.held_mask,
            changes: &mut self.changes,
        }
    }
}

/// Split borrows of a [`Heightfield`] for the carving, smoothing and settling stages.
pub(crate) struct TerrainParts<'a> {
    pub heights: &'a mut [f32],
    /// The heights at creation.
    pub initial: &'a [f32],
    pub nx: usize,
    pub table: &'a MaterialTable,
    pub material: &'a [u8],
    pub disturbed: &'a mut [u8],
    /// The samples held by soles this step, one bit each.
    pub held_mask: &'a mut HeldMask,
    pub changes: &'a mut StepChanges,
}

impl<'a> TerrainParts<'a> {
    /// The material of sample index `k`.
    #[inline]
    pub fn material(&self, k: usize) -> &'a TerrainMaterial {
        &self.table.materials()[self.material[k] as usize]
    }

    /// The firm floor of sample index `k` (see [`Heightfield::firm_floor`]).
    #[inline]
    pub fn floor(&self, k: usize) -> f32 {
        self.initial[k] - self.material(k).layer
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::terrain::generate::{GridSpec, flat};

    fn field() -> Heightfield {
        let grid = flat(GridSpec::square(4.0, 41), 1.0).unwrap();
        Heightfield::from_grid(grid, MaterialTable::with_presets(), MaterialId(0)).unwrap()
    }

    #[test]
    fn materials_paint_and_lookup() {
        let mut hf = field();
        assert_eq!(hf.material_at(1.0, 1.0).unwrap().name, "sand");
        let snow = hf.table().id("snow").unwrap();
        hf.paint_rect(GridRect::new(0, 0, 10, 41), snow).unwrap();
        assert_eq!(hf.material_at(0.5, 3.0).unwrap().name, "snow");
        assert_eq!(hf.material_at(2.0, 3.0).unwrap().name, "sand");
        assert!(hf.material_at(-1.0, 0.0).is_none());
        assert!(
            hf.paint_rect(GridRect::new(0, 0, 1, 1), MaterialId(7))
                .is_err()
        );
        let ids = [MaterialId(1), MaterialId(2)];
        hf.paint_bands_x(&ids).unwrap();
        assert_eq!(hf.material_at(0.1, 2.0).unwrap().name, "soil");
        assert_eq!(hf.material_at(3.9, 2.0).unwrap().name, "mud");
        hf.paint_fn(|_, z| {
            if z < 2.0 {
                MaterialId(3)
            } else {
                MaterialId(1)
            }
        })
        .unwrap();
        assert_eq!(
            hf.print_depth_at(1.0, 1.0),
            Some(TerrainMaterial::snow().print_depth())
        );
        assert!(hf.paint_fn(|_, _| MaterialId(200)).is_err());
        assert_eq!(hf.material_at(1.0, 3.0).unwrap().name, "soil");
        assert!(
            Heightfield::from_grid(hf.grid().clone(), MaterialTable::new(), MaterialId(0)).is_err()
        );
    }

    #[test]
    fn dirty_rectangles_accumulate_apart_and_clear_each_step() {
        let mut hf = field();
        assert!(hf.dirty().is_empty());
        hf.mark_dirty(GridRect::new(1, 1, 3, 3));
        hf.mark_dirty(GridRect::new(30, 30, 32, 32));
        hf.mark_dirty(GridRect::new(3, 0, 6, 2));
        hf.merge_dirty();
        assert_eq!(
            hf.dirty().rects(),
            &[GridRect::new(1, 0, 6, 3), GridRect::new(30, 30, 32, 32)]
        );
        assert_eq!(hf.changes().rects.clone().area(), 4 + 15);
        hf.begin_step();
        assert!(hf.changes().rects.is_empty());
    }

    #[test]
    fn the_floor_follows_the_painted_material_and_give_stops_at_it() {
        let mut hf = field();
        let k = hf.grid().index(20, 20);
        assert!((hf.firm_floor(k) - 0.95).abs() < 1e-6);
        // Fresh sand gives its print depth (5 cm, as thick as its layer).
        assert!((hf.give_at(2.0, 2.0).unwrap() - 0.05).abs() < 1e-6);
        let mud = hf.table().id("mud").unwrap();
        hf.paint_rect(GridRect::new(15, 15, 25, 25), mud).unwrap();
        assert!((hf.firm_floor(k) - 0.85).abs() < 1e-6);
        // Mud prints 0.2 m but its layer is 0.15 m: the layer bounds the give.
        assert!((hf.give_at(2.0, 2.0).unwrap() - 0.15).abs() < 1e-6);
        hf.grid_mut().set_height(20, 20, 0.9);
        assert!((hf.give_at(2.0, 2.0).unwrap() - 0.05).abs() < 1e-6);
        hf.grid_mut().set_height(20, 20, 0.7);
        assert_eq!(hf.give_at(2.0, 2.0), Some(0.0));
        assert_eq!(hf.give_at(-1.0, 2.0), None);
        assert_eq!(hf.initial().height_at(2.0, 2.0), Some(1.0));
        assert_eq!(hf.initial().height_at(5.0, 2.0), None);
        assert!(hf.initial().heights().iter().all(|&h| h == 1.0));
    }

    #[test]
    fn lowest_in_box() {
        let mut hf = field();
        hf.grid_mut().set_height(20, 20, 0.25);
        assert_eq!(hf.lowest_in(Vec2::splat(1.5), Vec2::splat(2.5)), Some(0.25));
        assert_eq!(hf.lowest_in(Vec2::splat(2.5), Vec2::splat(3.0)), Some(1.0));
        assert_eq!(hf.lowest_in(Vec2::splat(9.0), Vec2::splat(10.0)), None);
    }
}
