use super::{GeomError, GridRect, HeightGrid};

/// A [`HeightGrid`] cut into square tiles of `tile_cells` x `tile_cells` cells,
/// with the lowest and highest height each tile's ray walk can meet.
///
/// A tile's walk covers its own cells plus a one-cell apron on every side
/// (clipped to the grid), so that a ray crossing the surface exactly on a tile
/// border is seen whole by at least one tile. The bounds cover the samples of
/// that apron too.
#[derive(Debug, Clone, PartialEq)]
pub struct GridTiling {
    tile_cells: usize,
    cells_x: usize,
    cells_z: usize,
    tiles_x: usize,
    tiles_z: usize,
    bounds: Vec<(f32, f32)>,
}

impl GridTiling {
    /// Tiles `grid` into squares of `tile_cells` cells (the last row and column may be smaller).
    pub fn new(grid: &HeightGrid, tile_cells: usize) -> Result<GridTiling, GeomError> {
        if tile_cells == 0 {
            return Err(GeomError::InvalidParameter {
                name: "tile_cells",
                reason: "a tile needs at least one cell".into(),
            });
        }
        let (cells_x, cells_z) = grid.cell_counts();
        let tiles_x = cells_x.div_ceil(tile_cells);
        let tiles_z = cells_z.div_ceil(tile_cells);
        let mut tiling = GridTiling {
            tile_cells,
            cells_x,
            cells_z,
            tiles_x,
            tiles_z,
            bounds: vec![(0.0, 0.0); tiles_x * tiles_z],
        };
        tiling.update(grid, grid.full_rect());
        Ok(tiling)
    }

    /// Cells per tile side.
    pub fn tile_cells(&self) -> usize {
        self.tile_cells
    }

    /// Tiles along X and Z.
    pub fn tile_counts(&self) -> (usize, usize) {
        (self.tiles_x, self.tiles_z)
    }

    /// Number of tiles; tile `(tx, tz)` has index `tz * tiles_x + tx`.
    pub fn tile_count(&self) -> usize {
        self.tiles_x * self.tiles_z
    }

    /// `(tx, tz)` of tile `index`.
    pub fn tile_coords(&self, index: usize) -> (usize, usize) {
        (index % self.tiles_x, index / self.tiles_x)
    }

    /// The cells a tile owns (cell indices, half-open).
    pub fn own_cells(&self, index: usize) -> GridRect {
        let (tx, tz) = self.tile_coords(index);
        let t = self.tile_cells;
        GridRect::new(
            tx * t,
            tz * t,
            ((tx + 1) * t).min(self.cells_x),
            ((tz + 1) * t).min(self.cells_z),
        )
    }

    /// The cells a tile's ray walk covers: its own plus a one-cell apron, clipped.
    pub fn walk_cells(&self, index: usize) -> GridRect {
        self.own_cells(index).expand(1, self.cells_x, self.cells_z)
    }

    /// The samples under [`GridTiling::walk_cells`]: the ones its bounds cover.
    pub fn walk_samples(&self, index: usize) -> GridRect {
        let c = self.walk_cells(index);
        GridRect::new(c.i0, c.j0, c.i1 + 1, c.j1 + 1)
    }

    /// Lowest and highest height over [`GridTiling::walk_samples`] of tile `index`.
    pub fn bounds(&self, index: usize) -> (f32, f32) {
        self.bounds[index]
    }

    /// The tiles (as a rectangle of tile coordinates) whose bounds depend on any
    /// sample of `changed` (sample indices, half-open).
    pub fn tiles_touching(&self, changed: GridRect) -> GridRect {
        let changed = changed.intersect(&GridRect::new(0, 0, self.cells_x + 1, self.cells_z + 1));
        if changed.is_empty() {
            return GridRect::EMPTY;
        }
        // Tile t covers samples t*T - 1 ..= (t+1)*T + 1 (see `walk_samples`).
        let t = self.tile_cells;
        let first = |s: usize| s.saturating_sub(2) / t;
        let last = |s: usize, n: usize| ((s + 1) / t).min(n - 1);
        GridRect::new(
            first(changed.i0),
            first(changed.j0),
            last(changed.i1 - 1, self.tiles_x) + 1,
            last(changed.j1 - 1, self.tiles_z) + 1,
        )
    }

    /// Recomputes the bounds of every tile that `changed` (samples) touches;
    /// returns those tiles as a rectangle of tile coordinates.
    pub fn update(&mut self, grid: &HeightGrid, changed: GridRect) -> GridRect {
        let tiles = self.tiles_touching(changed);
        for (tx, tz) in tiles.iter() {
            let index = tz * self.tiles_x + tx;
            self.bounds[index] = grid.min_max_in(&self.walk_samples(index));
        }
        tiles
    }
}

impl HeightGrid {
    /// This grid cut into square tiles of `tile_cells` cells, with per-tile height bounds.
    pub fn tiling(&self, tile_cells: usize) -> Result<GridTiling, GeomError> {
        GridTiling::new(self, tile_cells)
    }
}

#[cfg(test)]
mod tests {
    use glam::Vec2;

    use super::*;

    #[test]
    fn touching_tiles_cover_every_tile_that_sees_a_sample() {
        let g = HeightGrid::new(Vec2::ZERO, 1.0, 70, 40, 0.0).unwrap();
        let tiling = g.tiling(16).unwrap();
        assert_eq!(tiling.tile_counts(), (5, 3));
        for s in 0..70 {
            let got = tiling.tiles_touching(GridRect::new(s, 0, s + 1, 1));
            for tx in 0..5 {
                let sees = tiling.walk_samples(tx).contains(s, 0);
                assert_eq!(got.contains(tx, 0), sees, "sample {s}, tile {tx}");
            }
        }
        assert!(GridTiling::new(&g, 0).is_err());
    }
}
