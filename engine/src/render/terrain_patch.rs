//! A rectangle of terrain cells drawn as one batch, at levels of detail:
//! each level a sub-grid of the patch's samples, with how far its heights
//! and its colours miss the samples'.

use std::ops::{Add, Mul, Sub};

use glam::Vec3;

use super::shade_pyramid::ShadePyramid;
use crate::geom::{GridRect, HeightGrid};

/// One level of detail of a patch: a sub-grid of its samples.
#[derive(Debug, Clone)]
pub(crate) struct PatchLevel {
    /// Sample offsets (from the patch corner) of the level's columns.
    pub cols: Vec<usize>,
    /// Sample offsets of the level's rows.
    pub rows: Vec<usize>,
    /// Heights of the level's vertices, row-major.
    pub heights: Vec<f32>,
    /// Largest height difference between the level and the full-resolution samples.
    pub error: f32,
    /// Largest difference of a display colour component between the level
    /// (interpolated between its vertices) and the samples, as far as
    /// measured: at least the first that passes `TerrainStyle::max_color_error`.
    pub color_error: f32,
}

/// A rectangle of cells drawn as one batch.
#[derive(Debug, Clone)]
pub(crate) struct Patch {
    /// First sample (corner) of the patch.
    pub i0: usize,
    pub j0: usize,
    /// Cells along X and Z (samples are `i0..=i0 + cells_x`).
    pub cells_x: usize,
    pub cells_z: usize,
    pub levels: Vec<PatchLevel>,
    pub min_h: f32,
    pub max_h: f32,
}

impl Patch {
    /// A patch of `cells_x` x `cells_z` cells from sample `(i0, j0)`, not
    /// yet meshed.
    pub fn new(i0: usize, j0: usize, cells_x: usize, cells_z: usize) -> Patch {
        Patch {
            i0,
            j0,
            cells_x,
            cells_z,
            levels: Vec::new(),
            min_h: 0.0,
            max_h: 0.0,
        }
    }

    /// World-space bounding box of the patch's surface.
    pub fn bounds(&self, origin: glam::Vec2, cell: f32) -> (Vec3, Vec3) {
        let x0 = origin.x + self.i0 as f32 * cell;
        let z0 = origin.y + self.j0 as f32 * cell;
        (
            Vec3::new(x0, self.min_h, z0),
            Vec3::new(
                x0 + self.cells_x as f32 * cell,
                self.max_h,
                z0 + self.cells_z as f32 * cell,
            ),
        )
    }

    /// Rebuilds every level's heights and height error from the grid.
    pub fn remesh(&mut self, grid: &HeightGrid, patch_cells: usize) {
        let rect = GridRect::new(
            self.i0,
            self.j0,
            self.i0 + self.cells_x + 1,
            self.j0 + self.cells_z + 1,
        );
        (self.min_h, self.max_h) = grid.min_max_in(&rect);
        let (i0, j0) = (self.i0, self.j0);
        self.levels = level_steps(patch_cells)
            .map(|step| {
                let cols = offsets(self.cells_x, step);
                let rows = offsets(self.cells_z, step);
                let heights: Vec<f32> = rows
                    .iter()
                    .flat_map(|&r| cols.iter().map(move |&c| (c, r)))
                    .map(|(c, r)| grid.height(i0 + c, j0 + r))
                    .collect();
                let m = cols.len();
                let error = largest_miss(
                    &cols,
                    &rows,
                    |c, r| heights[r * m + c],
                    |a, b| grid.height(i0 + a, j0 + b),
                    f32::abs,
                    f32::INFINITY,
                );
                PatchLevel {
                    cols,
                    rows,
                    heights,
                    error,
                    color_error: 0.0,
                }
            })
            .collect();
    }

    /// Measures how far each level's colours stray from the samples', up
    /// to the first stray larger than `enough`.
    pub fn measure_colors(&mut self, shades: &ShadePyramid, enough: f32) {
        let fine = shades.level(0);
        let (i0, j0) = (self.i0, self.j0);
        for (l, level) in self.levels.iter_mut().enumerate() {
            let coarse = shades.level(l);
            let (cols, rows) = (&level.cols, &level.rows);
            level.color_error = largest_miss(
                cols,
                rows,
                |c, r| coarse.at_sample(i0 + cols[c], j0 + rows[r]).lit,
                |a, b| fine.at_sample(i0 + a, j0 + b).lit,
                |miss: Vec3| miss.abs().max_element(),
                enough,
            );
        }
    }
}

/// The largest `size` of the difference between the samples (`sample` at
/// offsets from the patch corner) and the surface a level draws through its
/// vertices (`vertex` at the level's column and row), interpolated over the
/// level's triangles; zero at full resolution, where they are the samples.
/// Stops at the first difference larger than `enough`.
fn largest_miss<T>(
    cols: &[usize],
    rows: &[usize],
    vertex: impl Fn(usize, usize) -> T,
    sample: impl Fn(usize, usize) -> T,
    size: impl Fn(T) -> f32,
    enough: f32,
) -> f32
where
    T: Copy + Add<Output = T> + Sub<Output = T> + Mul<f32, Output = T>,
{
    let full = |offsets: &[usize]| offsets.windows(2).all(|p| p[1] - p[0] == 1);
    if full(cols) && full(rows) {
        return 0.0;
    }
    let mut largest = 0.0f32;
    for (r, pair_r) in rows.windows(2).enumerate() {
        for (c, pair_c) in cols.windows(2).enumerate() {
            let (v00, v10) = (vertex(c, r), vertex(c + 1, r));
            let (v01, v11) = (vertex(c, r + 1), vertex(c + 1, r + 1));
            let (w, d) = (
                (pair_c[1] - pair_c[0]) as f32,
                (pair_r[1] - pair_r[0]) as f32,
            );
            for b in pair_r[0]..=pair_r[1] {
                for a in pair_c[0]..=pair_c[1] {
                    let fx = (a - pair_c[0]) as f32 / w;
                    let fz = (b - pair_r[0]) as f32 / d;
                    // Same diagonal as the triangles: (c, r) to (c + 1, r + 1).
                    let surface = if fx >= fz {
                        v00 + (v10 - v00) * fx + (v11 - v10) * fz
                    } else {
                        v00 + (v01 - v00) * fz + (v11 - v01) * fx
                    };
                    largest = largest.max(size(sample(a, b) - surface));
                    if largest > enough {
                        return largest;
                    }
                }
            }
        }
    }
    largest
}

/// Sample steps of the levels of detail of a patch: 1, 2, 4 ... `patch_cells`.
pub(crate) fn level_steps(patch_cells: usize) -> impl Iterator<Item = usize> {
    (0..=patch_cells.trailing_zeros()).map(|l| 1 << l)
}

/// Offsets `0, step, 2 step, ...` below `cells`, then `cells` itself.
pub(crate) fn offsets(cells: usize, step: usize) -> Vec<usize> {
    let mut v: Vec<usize> = (0..cells).step_by(step).collect();
    v.push(cells);
    v
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn offsets_end_on_the_border() {
        assert_eq!(offsets(8, 4), vec![0, 4, 8]);
        assert_eq!(offsets(5, 4), vec![0, 4, 5]);
        assert_eq!(offsets(3, 8), vec![0, 3]);
        assert_eq!(level_steps(8).collect::<Vec<_>>(), vec![1, 2, 4, 8]);
    }

    #[test]
    fn a_level_misses_a_print_its_vertices_skip() {
        // One sample of a 4-cell row dips: the full level follows it, the
        // coarsest (vertices at 0 and 4) misses it by its depth, the middle
        // one (at 0, 2 and 4) the samples beside it by half of it.
        let heights = [0.0, 0.0, -0.5, 0.0, 0.0];
        let cols = [0, 1, 2, 3, 4];
        let miss = |cols: &[usize]| {
            largest_miss(
                cols,
                &[0, 1],
                |c, _| heights[cols[c]],
                |a, _| heights[a],
                f32::abs,
                f32::INFINITY,
            )
        };
        assert_eq!(miss(&cols), 0.0);
        assert_eq!(miss(&[0, 4]), 0.5);
        assert_eq!(miss(&[0, 2, 4]), 0.25);
    }
}
