use std::time::Duration;

use glam::{Vec2, Vec3, Vec3A};
use obvhs::BvhBuildParams;
use obvhs::aabb::Aabb as ObAabb;
use obvhs::bvh2::Bvh2;
use obvhs::bvh2::builder::build_bvh2;
use obvhs::ray::{Ray as ObRay, RayHit};

use super::ray::usable_max_t;
use super::{Aabb, GeomError, GridRect, GridTiling, HeightGrid, Hit, HitTarget, Ray};

/// A BVH over the tiles of a [`HeightGrid`] for fast ray casts on deformable ground.
///
/// Leaves are tiles ([`GridTiling`]); a leaf is intersected by walking its cells
/// (no triangles are stored). The grid itself is not owned: every query takes
/// the `&HeightGrid` the BVH was built from (same shape; edits are reported
/// through [`GridBvh::refit`]). Queries panic when given a grid of another shape.
#[derive(Clone)]
pub struct GridBvh {
    tiling: GridTiling,
    bvh: Bvh2,
    shape: GridShape,
}

#[derive(Debug, Clone, Copy, PartialEq)]
struct GridShape {
    origin: Vec2,
    cell: f32,
    nx: usize,
    nz: usize,
}

impl GridShape {
    fn of(grid: &HeightGrid) -> GridShape {
        GridShape {
            origin: grid.origin(),
            cell: grid.cell_size(),
            nx: grid.nx(),
            nz: grid.nz(),
        }
    }
}

impl GridBvh {
    /// Cells per tile side used by [`GridBvh::build`] (chosen by measurement, see the benchmarks).
    pub const DEFAULT_TILE_CELLS: usize = 16;

    /// Builds the BVH over tiles of [`GridBvh::DEFAULT_TILE_CELLS`] cells.
    pub fn build(grid: &HeightGrid) -> GridBvh {
        Self::build_with_tiles(grid, Self::DEFAULT_TILE_CELLS)
            .expect("the default tile size is valid")
    }

    /// Builds the BVH over tiles of `tile_cells` x `tile_cells` cells (`tile_cells >= 1`).
    pub fn build_with_tiles(grid: &HeightGrid, tile_cells: usize) -> Result<GridBvh, GeomError> {
        let tiling = GridTiling::new(grid, tile_cells)?;
        let shape = GridShape::of(grid);
        let boxes: Vec<ObAabb> = (0..tiling.tile_count())
            .map(|t| tile_box(&tiling, shape, t))
            .collect();
        // One tile per leaf, so that a refit can replace a leaf's box directly.
        let params = BvhBuildParams {
            max_prims_per_leaf: 1,
            ..BvhBuildParams::medium_build()
        };
        let mut bvh = build_bvh2(&boxes, params, &mut Duration::default());
        bvh.init_primitives_to_nodes_if_uninit();
        bvh.init_parents_if_uninit();
        Ok(GridBvh { tiling, bvh, shape })
    }

    /// The tiling and its per-tile height bounds.
    pub fn tiling(&self) -> &GridTiling {
        &self.tiling
    }

    /// Refits after the samples in `changed` were edited: recomputes the bounds of
    /// the tiles that rectangle touches and the boxes of their ancestors only.
    pub fn refit(&mut self, grid: &HeightGrid, changed: GridRect) {
        self.check_shape(grid);
        let tiles = self.tiling.update(grid, changed);
        let (tiles_x, _) = self.tiling.tile_counts();
        for (tx, tz) in tiles.iter() {
            let tile = tz * tiles_x + tx;
            let node = self.bvh.primitives_to_nodes[tile] as usize;
            self.bvh.nodes[node].set_aabb(tile_box(&self.tiling, self.shape, tile));
            self.bvh.refit_from(node);
        }
    }

    /// The closest hit of `ray` on the grid surface within `max_t`.
    pub fn cast(&self, grid: &HeightGrid, ray: &Ray, max_t: f32) -> Option<Hit> {
        self.check_shape(grid);
        if !usable_max_t(max_t) {
            return None;
        }
        let mut best: Option<Hit> = None;
        let mut hit = RayHit::none();
        self.bvh
            .ray_traverse(to_obvhs(ray, max_t), &mut hit, |r, slot| {
                let tile = self.bvh.primitive_indices[slot] as usize;
                match self.walk_tile(grid, ray, tile, r.tmax) {
                    Some(h) => {
                        if best.is_none_or(|b| closer(&h, &b)) {
                            best = Some(h);
                        }
                        h.distance
                    }
                    None => f32::INFINITY,
                }
            });
        best
    }

    /// True when `ray` meets the grid surface within `max_t`.
    pub fn any_hit(&self, grid: &HeightGrid, ray: &Ray, max_t: f32) -> bool {
        self.check_shape(grid);
        if !usable_max_t(max_t) {
            return false;
        }
        !self.bvh.ray_traverse_miss(to_obvhs(ray, max_t), |r, slot| {
            let tile = self.bvh.primitive_indices[slot] as usize;
            self.walk_tile(grid, ray, tile, r.tmax)
                .map_or(f32::INFINITY, |h| h.distance)
        })
    }

    /// The vertical-ray fast path: what a ray going straight down from
    /// `(x, from_y, z)` hits. Goes straight to the cell under `(x, z)` (no tree
    /// walk); the answer equals [`GridBvh::cast`] of that ray with no distance limit.
    pub fn cast_down(&self, grid: &HeightGrid, x: f32, z: f32, from_y: f32) -> Option<Hit> {
        self.check_shape(grid);
        grid.cast_down(x, z, from_y)
    }

    /// Walks the cells of `tile` over the part of the ray inside the tile's box:
    /// a crossing lies between the tile's lowest and highest sample, so the
    /// parts of the ray above or below them are skipped.
    fn walk_tile(&self, grid: &HeightGrid, ray: &Ray, tile: usize, max_t: f32) -> Option<Hit> {
        let b = tile_box(&self.tiling, self.shape, tile);
        let bounds = Aabb::new(Vec3::from(b.min), Vec3::from(b.max));
        let (t0, t1) = bounds.ray_interval(ray, max_t)?;
        grid.intersect_ray_in_cells(ray, self.tiling.walk_cells(tile), t0, t1)
    }

    /// True when `grid` has the shape (origin, cell size, samples) this BVH was built for.
    pub fn matches(&self, grid: &HeightGrid) -> bool {
        self.shape == GridShape::of(grid)
    }

    fn check_shape(&self, grid: &HeightGrid) {
        assert_eq!(
            self.shape,
            GridShape::of(grid),
            "GridBvh queried with a grid of another shape than the one it was built from"
        );
    }
}

impl std::fmt::Debug for GridBvh {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("GridBvh")
            .field("tile_cells", &self.tiling.tile_cells())
            .field("tiles", &self.tiling.tile_counts())
            .field("nodes", &self.bvh.nodes.len())
            .finish()
    }
}

/// Closer, with ties broken by cell so that the answer does not depend on tree order.
pub(crate) fn closer(a: &Hit, b: &Hit) -> bool {
    if a.distance != b.distance {
        return a.distance < b.distance;
    }
    match (a.target, b.target) {
        (HitTarget::Grid { i: ai, j: aj }, HitTarget::Grid { i: bi, j: bj }) => (aj, ai) < (bj, bi),
        _ => false,
    }
}

fn to_obvhs(ray: &Ray, max_t: f32) -> ObRay {
    ObRay::new(
        Vec3A::from(ray.origin()),
        Vec3A::from(ray.dir()),
        0.0,
        max_t,
    )
}

/// The world box of a tile's walk cells and height bounds, padded so that rays
/// lying exactly in a face plane (vertical rays on tile borders) are not
/// rejected by the slab test.
fn tile_box(tiling: &GridTiling, shape: GridShape, tile: usize) -> ObAabb {
    let cells = tiling.walk_cells(tile);
    let (lo, hi) = tiling.bounds(tile);
    let min = Vec3::new(
        shape.origin.x + cells.i0 as f32 * shape.cell,
        lo,
        shape.origin.y + cells.j0 as f32 * shape.cell,
    );
    let max = Vec3::new(
        shape.origin.x + cells.i1 as f32 * shape.cell,
        hi,
        shape.origin.y + cells.j1 as f32 * shape.cell,
    );
    let scale = min.abs().max(max.abs()).max_element();
    let pad = Vec3::splat(1e-3 * shape.cell + 1e-5 * scale);
    ObAabb::new(Vec3A::from(min - pad), Vec3A::from(max + pad))
}
