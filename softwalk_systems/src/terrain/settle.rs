//! Settling (beyond the paper): disturbed ground steeper than its angle of
//! repose slides down, by pairwise mass-conserving transfers (Sumner 1999's erosion).

use engine::geom::GridRect;

use super::heightfield::{DISTURBED_SLUMPED, Heightfield};
use super::patch::Patch;
use super::smooth::smoothing_radius;

/// Settling stops when no slope exceeds the repose slope by more than this (m/m).
pub const SETTLE_TOLERANCE: f32 = 1e-3;
/// How far beyond the carve rectangle settling may move material, in samples:
/// room for a slump's runout on a slope (16 cm at the paper's 2 cm spacing).
pub const SETTLE_MARGIN_CELLS: usize = 8;

/// Upper bound on relaxation sweeps per call.
pub const SETTLE_MAX_SWEEPS: usize = 256;

/// The window the smoothing and settling stages of one step may change
/// around a carve rectangle: grown by the larger of the smoothing radius and
/// [`SETTLE_MARGIN_CELLS`], clipped to the grid (empty for an empty rectangle).
pub fn stage_window(hf: &Heightfield, carved: GridRect) -> GridRect {
    let g = hf.grid();
    let margin = smoothing_radius(hf).max(SETTLE_MARGIN_CELLS);
    carved
        .intersect(&g.full_rect())
        .expand(margin, g.nx(), g.nz())
}

/// Lets steep disturbed slopes inside `window` slump; returns the rectangle of
/// samples that changed (empty when already stable).
///
/// Sweeps run over the 8-neighbour edges in row-major order (Gauss-Seidel,
/// deterministic). When the higher sample of an edge is steeper than the
/// repose slope of its material by `excess` metres, half the excess moves to
/// the lower sample, which puts the pair exactly at the angle of repose. The
/// next sweep only revisits the samples changed by the last one, grown by
/// one; sweeps stop when nothing moves (no slope above repose by more than
/// [`SETTLE_TOLERANCE`]) or after [`SETTLE_MAX_SWEEPS`].
///
/// Guards against creeping over natural terrain:
/// - only edges with a disturbed sample move (a natural slope steeper than
///   repose, such as a dune's lee face, stays as it was; a sample that slumps
///   becomes disturbed, so a slump can propagate);
/// - nothing crosses the border of `window`, which never grows: a slump on a
///   steep dune stops at the window (in the usual chain, [`stage_window`]:
///   the carve rectangle grown by a fixed margin);
/// - samples held by a sole this step (see [`super::StepChanges::held`]) do
///   not move: the foot supports the walls, as Sumner's steeper in-contact angle.
pub fn settle(hf: &mut Heightfield, window: GridRect) -> GridRect {
    settle_from(hf, window, window)
}

/// [`settle`] inside `window`, with the first sweep only over `seeds` (grown
/// by one sample): the samples that changed since the window was last stable,
/// e.g. the rectangles carving and smoothing report. Everything else in the
/// window is assumed stable; slumps still spread anywhere in `window`.
pub fn settle_from(hf: &mut Heightfield, window: GridRect, seeds: GridRect) -> GridRect {
    let w = window.intersect(&hf.grid().full_rect());
    if w.is_empty() {
        return GridRect::EMPTY;
    }
    let cell = hf.grid().cell_size();
    let mut parts = hf.parts_mut();
    let mut patch = Patch::load(&parts, w);
    // Steepest stable height difference across a side, per sample (from its material).
    let side = parts
        .table
        .per_material(|m| (m.repose_slope() + SETTLE_TOLERANCE) * cell);
    let limit: Vec<f32> = patch.material.iter().map(|&m| side[m as usize]).collect();
    let (ww, wh) = (w.width(), w.height());
    let seeds = seeds.intersect(&w);
    if seeds.is_empty() {
        return GridRect::EMPTY;
    }
    let seeds = GridRect::new(
        seeds.i0 - w.i0,
        seeds.j0 - w.j0,
        seeds.i1 - w.i0,
        seeds.j1 - w.j0,
    )
    .expand(1, ww, wh);
    let settle_to = SETTLE_TOLERANCE * cell;
    let diagonal = std::f32::consts::SQRT_2;
    let p = &mut patch;
    let mut changed = GridRect::EMPTY;
    let mut active = seeds;
    let mut transfers = 0;
    let mut visits = 0;
    for _ in 0..SETTLE_MAX_SWEEPS {
        let mut sweep_changed = GridRect::EMPTY;
        visits += active.area();
        for r in active.j0..active.j1 {
            let down = r + 1 < wh;
            for c in active.i0..active.i1 {
                let l = r * ww + c;
                if p.held[l] {
                    continue;
                }
                let right = c + 1 < ww;
                let left = c > 0;
                // (inside, local offset, neighbour column, neighbour row, length factor)
                let neighbours = [
                    (right, 1, c + 1, r, 1.0),
                    (down, ww, c, r + 1, 1.0),
                    (right && down, ww + 1, c + 1, r + 1, diagonal),
                    (
                        left && down,
                        ww.wrapping_sub(1),
                        c.wrapping_sub(1),
                        r + 1,
                        diagonal,
                    ),
                ];
                for (inside, dl, cb, rb, factor) in neighbours {
                    if !inside {
                        continue;
                    }
                    let lb = l + dl;
                    if (p.disturbed[l] == 0 && p.disturbed[lb] == 0) || p.held[lb] {
                        continue;
                    }
                    let (hi, lo) = if p.heights[l] >= p.heights[lb] {
                        (l, lb)
                    } else {
                        (lb, l)
                    };
                    let excess = p.heights[hi] - p.heights[lo] - limit[hi] * factor;
                    if excess > 0.0 {
                        let moved = 0.5 * (excess + settle_to * factor);
                        p.heights[hi] -= moved;
                        p.heights[lo] += moved;
                        p.disturbed[l] = p.disturbed[l].max(DISTURBED_SLUMPED);
                        p.disturbed[lb] = p.disturbed[lb].max(DISTURBED_SLUMPED);
                        let pair = GridRect::new(c.min(cb), r, c.max(cb) + 1, rb + 1);
                        sweep_changed = sweep_changed.union(&pair);
                        transfers += 1;
                    }
                }
            }
        }
        if sweep_changed.is_empty() {
            break;
        }
        changed = changed.union(&sweep_changed);
        active = sweep_changed.expand(1, ww, wh);
    }
    parts.changes.settle_transfers += transfers;
    parts.changes.settle_visits += visits;
    if changed.is_empty() {
        return GridRect::EMPTY;
    }
    patch.store(&mut parts);
    let changed = patch.to_grid(changed);
    hf.mark_dirty(changed);
    changed
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::terrain::generate::{GridSpec, flat};
    use crate::terrain::{MaterialId, MaterialTable};

    fn pillar(material: u8) -> Heightfield {
        let grid = flat(GridSpec::square(1.0, 41), 1.0).unwrap();
        let mut hf =
            Heightfield::from_grid(grid, MaterialTable::with_presets(), MaterialId(material))
                .unwrap();
        hf.grid_mut().set_height(20, 20, 1.2);
        let k = hf.grid().index(20, 20);
        hf.parts_mut().disturbed[k] = 255;
        hf
    }

    #[test]
    fn a_sand_pillar_slumps_to_its_angle_of_repose_conserving_volume() {
        let mut hf = pillar(0);
        let before = hf.grid().volume();
        let changed = settle(&mut hf, GridRect::new(5, 5, 36, 36));
        assert!(!changed.is_empty());
        assert!(((hf.grid().volume() - before) / before).abs() < 1e-7);
        let g = hf.grid();
        let tan = 34f32.to_radians().tan();
        for (i, j) in GridRect::new(5, 5, 35, 35).iter() {
            let dx = (g.height(i + 1, j) - g.height(i, j)).abs() / g.cell_size();
            let dz = (g.height(i, j + 1) - g.height(i, j)).abs() / g.cell_size();
            assert!(
                dx <= tan + 2e-3 && dz <= tan + 2e-3,
                "({i}, {j}): {dx} {dz}"
            );
        }
        assert!(hf.changes().settle_transfers > 0);
    }

    #[test]
    fn snow_holds_a_steep_wall_and_held_samples_do_not_move() {
        let mut hf = pillar(3);
        hf.grid_mut().set_height(20, 20, 1.1);
        let snow = hf.grid().clone();
        // 0.1 m over one 2.5 cm cell is 76 degrees: below snow's 84.
        assert!(settle(&mut hf, GridRect::new(5, 5, 36, 36)).is_empty());
        assert_eq!(hf.grid(), &snow);
        let mut hf = pillar(0);
        let k = hf.grid().index(20, 20);
        hf.parts_mut().changes.held.push(k);
        let held = hf.grid().clone();
        assert!(settle(&mut hf, GridRect::new(5, 5, 36, 36)).is_empty());
        assert_eq!(hf.grid(), &held);
    }

    #[test]
    fn nothing_moves_outside_the_window() {
        let mut hf = pillar(0);
        let w = GridRect::new(19, 19, 22, 22);
        let changed = settle(&mut hf, w);
        assert_eq!(changed.intersect(&w), changed);
        for (i, j) in hf.grid().full_rect().iter() {
            if !w.contains(i, j) {
                assert_eq!(hf.grid().height(i, j), 1.0);
            }
        }
    }
}
