//! Settling (beyond the paper): disturbed ground steeper than its angle of
//! repose slides down, by pairwise mass-conserving transfers (Sumner 1999's erosion).

use std::ops::Range;

use engine::geom::GridRect;

use super::heightfield::{DISTURBED_SLUMPED, Heightfield, StageBuffers};
use super::material::TerrainMaterial;
use super::patch::{DISTURBED, FIXED, Patch, edge_moves};
use super::smooth::smoothing_radius;

/// Settling stops when no slope exceeds the repose slope by more than this (m/m).
pub const SETTLE_TOLERANCE: f32 = 1e-3;
/// How far beyond the carve rectangle settling may move material, in samples:
/// room for a slump's runout on a slope (16 cm at the paper's 2 cm spacing).
pub const SETTLE_MARGIN_CELLS: usize = 8;

/// Upper bound on relaxation sweeps per call.
pub const SETTLE_MAX_SWEEPS: usize = 256;

/// Over-relaxation of a settling transfer: a pair steeper than repose by
/// `excess` gives up `SETTLE_OVERRELAXATION / 2` of it instead of half, so it
/// ends up to `(SETTLE_OVERRELAXATION - 1) * excess` below the angle of
/// repose. Like a real avalanche, which stops at a slope a few degrees below
/// the steepest stable one, a slump runs a little past repose; the walls
/// then need about a third of the transfers and sweeps. In `[1, 2)`:
/// 1 puts every pair exactly at repose.
pub const SETTLE_OVERRELAXATION: f32 = 1.5;

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
/// Each sample relaxes its four forward 8-neighbour edges (right, down and
/// the two lower diagonals): when the higher sample of an edge is steeper
/// than the repose slope of its material by `excess` metres, the higher
/// sample gives the lower one [`SETTLE_OVERRELAXATION`] / 2 of the excess,
/// which puts the pair at or a little below the angle of repose. Sweeps run
/// in row-major order (Gauss-Seidel: each transfer is seen by the next edge).
/// After the first sweep only the samples owning an edge that touches a
/// sample moved by the previous sweep are revisited (a work list, sorted
/// into row-major order each sweep). Sweeps stop when nothing moves (no
/// slope above repose by more than [`SETTLE_TOLERANCE`]) or after
/// [`SETTLE_MAX_SWEEPS`]. Everything is in a fixed order, so the result is
/// deterministic.
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
    let full = hf.grid().full_rect();
    let w = window.intersect(&full);
    let seeds = seeds.intersect(&w);
    if seeds.is_empty() {
        return GridRect::EMPTY;
    }
    let first = seeds.expand(1, full.width(), full.height()).intersect(&w);
    let cell = hf.grid().cell_size();
    let mut buffers = hf.take_buffers();
    let changed = {
        let mut parts = hf.parts_mut();
        let StageBuffers { patch, settle, .. } = &mut buffers;
        patch.load(&parts, w);
        settle.limits(patch, parts.table.materials(), cell);
        let SettleBuffers {
            limit,
            steep,
            now,
            next,
            ..
        } = settle;
        let words = patch.flags.len().div_ceil(64);
        for set in [&mut *now, &mut *next] {
            set.clear();
            set.resize(words, 0);
        }
        let first_start = patch.local(first.i0, first.j0);
        let mut relax = Relaxation {
            heights: &mut patch.heights,
            flags: &mut patch.flags,
            limit,
            next,
            next_words: 0..0,
            stride: patch.stride,
            settle_to: SETTLE_TOLERANCE * cell,
            transfers: 0,
            visits: 0,
        };
        relax.run(first_start, first.width(), first.height(), steep, now);
        let (transfers, visits) = (relax.transfers, relax.visits);
        let changed = if transfers > 0 {
            mark_slumped(patch)
        } else {
            GridRect::EMPTY
        };
        parts.changes.settle_transfers += transfers;
        parts.changes.settle_visits += visits;
        if !changed.is_empty() {
            patch.store(&mut parts, changed);
        }
        changed
    };
    hf.return_buffers(buffers);
    if !changed.is_empty() {
        hf.mark_dirty(changed);
    }
    changed
}

/// Flag of a sample moved by this call.
const MOVED: u8 = 4;

/// Settling's buffers, reused from call to call.
#[derive(Default)]
pub(crate) struct SettleBuffers {
    /// Steepest stable side difference per material id, metres.
    side: Vec<f32>,
    /// The same per local sample of the patch.
    limit: Vec<f32>,
    /// Per sample of a row of the first sweep: 1 when one of its edges is too steep.
    steep: Vec<u8>,
    /// Local samples to visit in the running sweep, and in the next one,
    /// as bit sets (bit `l % 64` of word `l / 64`), so a sweep visits them in
    /// row-major order without sorting.
    now: Vec<u64>,
    next: Vec<u64>,
}

impl SettleBuffers {
    /// Fills the steepest stable side difference of every sample of `patch`
    /// (grid spacing `cell`).
    fn limits(&mut self, patch: &Patch, materials: &[TerrainMaterial], cell: f32) {
        self.side.clear();
        self.side.extend(
            materials
                .iter()
                .map(|m| (m.repose_slope() + SETTLE_TOLERANCE) * cell),
        );
        let side = &self.side;
        self.limit.clear();
        self.limit
            .extend(patch.material.iter().map(|&m| side[m as usize]));
    }
}

/// The relaxation sweeps of one [`settle_from`] call, on the local buffers
/// of a [`Patch`] (framed, so every neighbour of a window sample exists).
struct Relaxation<'p> {
    heights: &'p mut [f32],
    /// [`DISTURBED`], [`FIXED`] and [`MOVED`] bits per sample.
    flags: &'p mut [u8],
    /// Steepest stable side difference per sample, metres.
    limit: &'p [f32],
    /// Samples to visit in the next sweep (a bit set).
    next: &'p mut [u64],
    /// The words of `next` that may hold a set bit.
    next_words: Range<usize>,
    stride: usize,
    /// How far below the limit a transfer leaves a pair, per unit length, metres.
    settle_to: f32,
    transfers: usize,
    visits: usize,
}

impl Relaxation<'_> {
    /// Sweeps until stable (or the sweep cap). The first sweep goes over the
    /// `rows` x `width` local samples from `start` in row-major order,
    /// visiting the samples that own an edge steeper than repose when the
    /// sweep reaches their row (found by a branch-free scan of the row into
    /// `steep`); a sample made steep by a transfer is queued for the next
    /// sweep. `now` is the bit set of the running sweep (all clear).
    fn run(
        &mut self,
        start: usize,
        width: usize,
        rows: usize,
        steep: &mut Vec<u8>,
        now: &mut [u64],
    ) {
        for r in 0..rows {
            let row = start + r * self.stride;
            self.scan_row(row, width, steep);
            for (k, &is_steep) in steep.iter().enumerate() {
                if is_steep != 0 {
                    self.visit(row + k);
                }
            }
        }
        for _ in 1..SETTLE_MAX_SWEEPS {
            let words = std::mem::replace(&mut self.next_words, 0..0);
            if words.is_empty() {
                break;
            }
            now[words.clone()].copy_from_slice(&self.next[words.clone()]);
            self.next[words.clone()].fill(0);
            for w in words {
                let mut bits = std::mem::take(&mut now[w]);
                while bits != 0 {
                    self.visit(w * 64 + bits.trailing_zeros() as usize);
                    bits &= bits - 1;
                }
            }
        }
    }

    /// Sets `steep[k]` for the `width` samples from local `start` that own a
    /// moving edge steeper than repose (the test of [`Relaxation::relax_edge`]).
    fn scan_row(&self, start: usize, width: usize, steep: &mut Vec<u8>) {
        let s = self.stride;
        steep.clear();
        steep.resize(width, 0);
        let diagonal = std::f32::consts::SQRT_2;
        for (d, length) in [(1, 1.0), (s, 1.0), (s + 1, diagonal), (s - 1, diagonal)] {
            let a = start..start + width;
            let b = start + d..start + d + width;
            let (ha, hb) = (&self.heights[a.clone()], &self.heights[b.clone()]);
            let (la, lb) = (&self.limit[a.clone()], &self.limit[b.clone()]);
            let (fa, fb) = (&self.flags[a], &self.flags[b]);
            for k in 0..width {
                let drop = ha[k] - hb[k];
                let limit = if drop >= 0.0 { la[k] } else { lb[k] };
                let too_steep = drop.abs() - limit * length > 0.0;
                steep[k] |= u8::from(too_steep & edge_moves(fa[k], fb[k]));
            }
        }
    }

    /// Relaxes the four forward edges of local sample `l` (the frame
    /// guarantees every neighbour exists).
    #[inline]
    fn visit(&mut self, l: usize) {
        self.visits += 1;
        if self.flags[l] & FIXED != 0 {
            return;
        }
        let s = self.stride;
        let diagonal = std::f32::consts::SQRT_2;
        self.relax_edge(l, l + 1, 1.0);
        self.relax_edge(l, l + s, 1.0);
        self.relax_edge(l, l + s + 1, diagonal);
        self.relax_edge(l, l + s - 1, diagonal);
    }

    /// Moves part of the excess across the edge between local samples `a`
    /// and `b` (`length` in cells) if it is steeper than repose.
    #[inline(always)]
    fn relax_edge(&mut self, a: usize, b: usize, length: f32) {
        if !edge_moves(self.flags[a], self.flags[b]) {
            return;
        }
        let (ha, hb) = (self.heights[a], self.heights[b]);
        let (hi, lo, drop) = if ha >= hb {
            (a, b, ha - hb)
        } else {
            (b, a, hb - ha)
        };
        let excess = drop - self.limit[hi] * length;
        if excess > 0.0 {
            self.transfer(hi, lo, excess, length);
        }
    }

    /// Moves [`SETTLE_OVERRELAXATION`] / 2 of `excess` from `hi` to `lo` and
    /// queues the samples whose edges this touches.
    #[cold]
    fn transfer(&mut self, hi: usize, lo: usize, excess: f32, length: f32) {
        let moved = 0.5 * SETTLE_OVERRELAXATION * (excess + self.settle_to * length);
        self.heights[hi] -= moved;
        self.heights[lo] += moved;
        self.transfers += 1;
        for l in [hi, lo] {
            self.flags[l] |= DISTURBED | MOVED;
            self.queue_owners(l);
        }
    }

    /// Queues for the next sweep every sample owning a forward edge that
    /// touches `l`: itself, its left neighbour and the three samples of the
    /// row above (frame and held samples own no moving edge and are skipped).
    #[inline]
    fn queue_owners(&mut self, l: usize) {
        let s = self.stride;
        for owner in [l - s - 1, l - s, l - s + 1, l - 1, l] {
            if self.flags[owner] & FIXED == 0 {
                self.next[owner / 64] |= 1 << (owner % 64);
            }
        }
        let (first, last) = ((l - s - 1) / 64, l / 64 + 1);
        let words = &mut self.next_words;
        *words = if words.start >= words.end {
            first..last
        } else {
            words.start.min(first)..words.end.max(last)
        };
    }
}

/// Marks every sample of `patch` moved by a relaxation as slumped; returns
/// their bounding rectangle (grid samples).
fn mark_slumped(patch: &mut Patch) -> GridRect {
    let flags = &patch.flags;
    let rect = patch.bounds_of(|l| flags[l] & MOVED != 0);
    for j in rect.j0..rect.j1 {
        let start = patch.local(rect.i0, j);
        for l in start..start + rect.width() {
            if patch.flags[l] & MOVED != 0 {
                patch.disturbed[l] = patch.disturbed[l].max(DISTURBED_SLUMPED);
            }
        }
    }
    rect
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
    fn a_settled_window_is_stable_and_the_result_is_deterministic() {
        let window = GridRect::new(5, 5, 36, 36);
        let mut first = pillar(0);
        let mut second = pillar(0);
        settle(&mut first, window);
        settle(&mut second, window);
        assert_eq!(first.grid(), second.grid());
        assert_eq!(first.disturbed(), second.disturbed());
        // The work list stops only when no edge moves: a second call finds nothing.
        let transfers = first.changes().settle_transfers;
        assert!(settle(&mut first, window).is_empty());
        assert_eq!(first.changes().settle_transfers, transfers);
        assert_eq!(first.grid(), second.grid());
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
