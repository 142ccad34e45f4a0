//! A uniform grid over a patch, so a foot only visits the blades near it.
//!
//! Blades are stored sorted by cell (row-major, Z rows of X cells), so the
//! cells of one row that a query touches form ONE contiguous range of blade
//! indices: a query is a handful of slices, cache friendly, no per-cell lists.

use std::ops::Range;

use glam::Vec2;

use super::area::XzRect;

/// Most cells a grid may have; coarser cells are used beyond it.
const MAX_CELLS: f32 = (1 << 22) as f32;

/// Cell offsets of blades sorted by cell.
#[derive(Debug, Clone, PartialEq)]
pub struct BladeGrid {
    origin: Vec2,
    cell: f32,
    nx: usize,
    nz: usize,
    /// `starts[c]..starts[c + 1]` are the blades of cell `c`.
    starts: Vec<u32>,
}

impl BladeGrid {
    /// Builds a grid over `area` with cells of at least `cell` metres, for
    /// blades at `positions` (XZ). Returns the grid and the order in which
    /// blades must be stored: `order[k]` is the index in `positions` of the
    /// `k`-th stored blade. The sort is stable, so the order is deterministic.
    pub fn build(area: XzRect, cell: f32, positions: &[Vec2]) -> (Self, Vec<u32>) {
        let size = area.size();
        let cell = cell.max((size.x * size.y / MAX_CELLS).sqrt());
        let nx = ((size.x / cell).ceil() as usize).max(1);
        let nz = ((size.y / cell).ceil() as usize).max(1);
        let mut grid = Self {
            origin: area.min,
            cell,
            nx,
            nz,
            starts: vec![0; nx * nz + 1],
        };
        let cells: Vec<usize> = positions
            .iter()
            .map(|p| grid.cell_index(grid.cell_coords(*p)))
            .collect();
        for &c in &cells {
            grid.starts[c + 1] += 1;
        }
        for c in 0..nx * nz {
            grid.starts[c + 1] += grid.starts[c];
        }
        let mut next = grid.starts.clone();
        let mut order = vec![0u32; positions.len()];
        for (i, &c) in cells.iter().enumerate() {
            order[next[c] as usize] = i as u32;
            next[c] += 1;
        }
        (grid, order)
    }

    /// Edge length of a cell (metres).
    pub fn cell_size(&self) -> f32 {
        self.cell
    }

    /// Number of cells along X and Z.
    pub fn dims(&self) -> (usize, usize) {
        (self.nx, self.nz)
    }

    /// Cell (column, row) holding `p`, clamped to the grid.
    pub fn cell_coords(&self, p: Vec2) -> (usize, usize) {
        let g = (p - self.origin) / self.cell;
        let clamp = |v: f32, n: usize| (v.max(0.0) as usize).min(n - 1);
        (clamp(g.x, self.nx), clamp(g.y, self.nz))
    }

    fn cell_index(&self, (i, j): (usize, usize)) -> usize {
        j * self.nx + i
    }

    /// Ranges of stored blade indices near `centre`, one per grid row the
    /// disc of `radius` reaches: in each row, the cells overlapping the disc's
    /// chord over that row's Z extent. Every blade closer than `radius` to
    /// `centre` is in them; callers filter by exact distance.
    pub fn ranges_near(
        &self,
        centre: Vec2,
        radius: f32,
    ) -> impl Iterator<Item = Range<usize>> + '_ {
        let (_, j0) = self.cell_coords(centre - Vec2::splat(radius));
        let (_, j1) = self.cell_coords(centre + Vec2::splat(radius));
        (j0..=j1).filter_map(move |j| {
            // Distance from the centre to the row's Z band (0 inside it),
            // padded against rounding; the edge rows are open-ended (their
            // cells hold the blades clamped into the grid).
            let z0 = self.origin.y + j as f32 * self.cell;
            let pad = 1e-3 * self.cell;
            let below = if j == 0 { f32::NEG_INFINITY } else { z0 - pad };
            let above = if j + 1 == self.nz {
                f32::INFINITY
            } else {
                z0 + self.cell + pad
            };
            let dz = (below - centre.y).max(centre.y - above).max(0.0);
            if dz >= radius {
                return None;
            }
            let half = (radius * radius - dz * dz).sqrt();
            let (i0, _) = self.cell_coords(Vec2::new(centre.x - half, z0));
            let (i1, _) = self.cell_coords(Vec2::new(centre.x + half, z0));
            let a = self.starts[self.cell_index((i0, j))] as usize;
            let b = self.starts[self.cell_index((i1, j)) + 1] as usize;
            Some(a..b)
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use engine::rng::SplitMix64;

    #[test]
    fn query_finds_exactly_what_brute_force_finds() {
        let area = XzRect::new(Vec2::new(-3.0, 1.0), Vec2::new(4.0, 6.5));
        let mut rng = SplitMix64::new(42);
        let positions: Vec<Vec2> = (0..5000)
            .map(|_| {
                Vec2::new(
                    rng.range(area.min.x, area.max.x),
                    rng.range(area.min.y, area.max.y),
                )
            })
            .collect();
        let (grid, order) = BladeGrid::build(area, 0.4, &positions);
        let stored: Vec<Vec2> = order.iter().map(|&i| positions[i as usize]).collect();
        let mut sorted_order = order.clone();
        sorted_order.sort_unstable();
        assert_eq!(
            sorted_order,
            (0..5000).collect::<Vec<u32>>(),
            "a permutation"
        );
        for q in 0..200 {
            // Centres inside, on the edge and outside the area; radii around the cell size.
            let centre = Vec2::new(rng.range(-4.0, 5.0), rng.range(0.0, 7.5));
            let radius = 0.05 + 0.01 * q as f32;
            let mut from_grid: Vec<u32> = grid
                .ranges_near(centre, radius)
                .flatten()
                .filter(|&k| stored[k].distance(centre) < radius)
                .map(|k| order[k])
                .collect();
            let mut brute: Vec<u32> = (0..positions.len() as u32)
                .filter(|&i| positions[i as usize].distance(centre) < radius)
                .collect();
            from_grid.sort_unstable();
            brute.sort_unstable();
            assert_eq!(from_grid, brute, "query {q} at {centre} r {radius}");
        }
    }

    #[test]
    fn huge_area_gets_coarser_cells() {
        let area = XzRect::new(Vec2::ZERO, Vec2::splat(10_000.0));
        let (grid, _) = BladeGrid::build(area, 0.01, &[]);
        let (nx, nz) = grid.dims();
        assert!(nx * nz <= (1 << 22) + 2 * 2048 + 1, "{nx} x {nz}");
    }
}
