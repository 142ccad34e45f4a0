//! Settling (beyond the paper): disturbed ground steeper than its angle of
//! repose slides down, by pairwise mass-conserving transfers (Sumner 1999's erosion).

use engine::geom::GridRect;

use super::heightfield::{DISTURBED_SLUMPED, Heightfield, held_mask};
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
/// next sweep only revisits the changed samples grown by one; sweeps stop
/// when nothing moves (within [`SETTLE_TOLERANCE`]) or after
/// [`SETTLE_MAX_SWEEPS`].
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
    let w = window.intersect(&hf.grid().full_rect());
    if w.is_empty() {
        return GridRect::EMPTY;
    }
    let cell = hf.grid().cell_size();
    let parts = hf.parts_mut();
    let nx = parts.nx;
    let ww = w.width();
    let held = held_mask(&parts.changes.held, nx, w);
    // Steepest stable height difference per material over a side and a diagonal.
    let side = parts
        .table
        .per_material(|m| (m.repose_slope() + SETTLE_TOLERANCE) * cell);
    let diagonal = std::f32::consts::SQRT_2;
    let settle_to = SETTLE_TOLERANCE * cell;
    let mut changed = GridRect::EMPTY;
    let mut active = w;
    let mut transfers = 0;
    for _ in 0..SETTLE_MAX_SWEEPS {
        let mut sweep_changed = GridRect::EMPTY;
        for j in active.j0..active.j1 {
            let down = j + 1 < w.j1;
            for i in active.i0..active.i1 {
                let k = j * nx + i;
                let l = (j - w.j0) * ww + (i - w.i0);
                if held.contains(l) {
                    continue;
                }
                let right = i + 1 < w.i1;
                let left = i > w.i0;
                // (inside, grid offset, local offset, column of the neighbour, length factor)
                let neighbours = [
                    (right, 1, 1, i + 1, 1.0),
                    (down, nx, ww, i, 1.0),
                    (right && down, nx + 1, ww + 1, i + 1, diagonal),
                    (left && down, nx - 1, ww - 1, i.wrapping_sub(1), diagonal),
                ];
                for (inside, dk, dl, ib, factor) in neighbours {
                    if !inside {
                        continue;
                    }
                    let kb = k + dk;
                    if (parts.disturbed[k] == 0 && parts.disturbed[kb] == 0)
                        || held.contains(l + dl)
                    {
                        continue;
                    }
                    let (hi, lo) = if parts.heights[k] >= parts.heights[kb] {
                        (k, kb)
                    } else {
                        (kb, k)
                    };
                    let limit = side[parts.material[hi] as usize] * factor;
                    let excess = parts.heights[hi] - parts.heights[lo] - limit;
                    if excess > 0.0 {
                        let moved = 0.5 * (excess + settle_to * factor);
                        parts.heights[hi] -= moved;
                        parts.heights[lo] += moved;
                        parts.disturbed[k] = parts.disturbed[k].max(DISTURBED_SLUMPED);
                        parts.disturbed[kb] = parts.disturbed[kb].max(DISTURBED_SLUMPED);
                        let jb = if dk == 1 { j } else { j + 1 };
                        let pair = GridRect::new(i.min(ib), j, i.max(ib) + 1, jb + 1);
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
        active = sweep_changed.expand(1, nx, usize::MAX).intersect(&w);
    }
    parts.changes.settle_transfers += transfers;
    hf.mark_dirty(changed);
    changed
}
