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
/// sample moved by the previous sweep are revisited (a work list, kept as a
/// mask in row-major order). Sweeps stop when nothing moves (no slope above
/// repose by more than [`SETTLE_TOLERANCE`]) or after [`SETTLE_MAX_SWEEPS`].
/// Everything is in a fixed order, so the result is deterministic.
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
    let seeds = seeds.intersect(&w);
    if seeds.is_empty() {
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
    let local_seeds = GridRect::new(
        seeds.i0 - w.i0,
        seeds.j0 - w.j0,
        seeds.i1 - w.i0,
        seeds.j1 - w.j0,
    )
    .expand(1, w.width(), w.height());
    let mut relax = Relaxation::new(&mut patch, limit, SETTLE_TOLERANCE * cell);
    relax.run(local_seeds);
    let (changed, transfers, visits) = (relax.changed, relax.transfers, relax.visits);
    if !changed.is_empty() {
        relax.mark_slumped();
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

/// Flag of a sample that is disturbed (its edges may move).
const DISTURBED: u8 = 1;
/// Flag of a sample held by a sole (its edges never move).
const HELD: u8 = 2;
/// Flag of a sample moved by this call.
const MOVED: u8 = 4;

/// The relaxation sweeps of one [`settle_from`] call, on a [`Patch`]'s heights.
struct Relaxation<'p> {
    heights: &'p mut [f32],
    /// Trodden marks, written once at the end ([`Relaxation::mark_slumped`]).
    disturbed: &'p mut [u8],
    /// [`DISTURBED`], [`HELD`] and [`MOVED`] bits per sample.
    flags: Vec<u8>,
    /// Steepest stable side difference per sample, metres.
    limit: Vec<f32>,
    /// How far below the limit a transfer leaves a pair, per unit length, metres.
    settle_to: f32,
    width: usize,
    height: usize,
    /// Samples to visit in the running sweep, and in the next one.
    now: Vec<bool>,
    next: Vec<bool>,
    /// Bounds of the `next` marks (empty when none).
    next_rect: GridRect,
    /// Local rectangle of every sample moved so far.
    changed: GridRect,
    transfers: usize,
    visits: usize,
}

impl<'p> Relaxation<'p> {
    /// Relaxation of the heights of `patch` (their flags taken from it) with
    /// the steepest stable side difference `limit` per sample.
    fn new(patch: &'p mut Patch, limit: Vec<f32>, settle_to: f32) -> Self {
        let (width, height) = (patch.width, patch.rect.height());
        let flags = patch
            .disturbed
            .iter()
            .zip(&patch.held)
            .map(|(&d, &held)| {
                if held {
                    HELD
                } else {
                    u8::from(d != 0) * DISTURBED
                }
            })
            .collect();
        Relaxation {
            heights: &mut patch.heights,
            disturbed: &mut patch.disturbed,
            flags,
            limit,
            settle_to,
            width,
            height,
            now: vec![false; width * height],
            next: vec![false; width * height],
            next_rect: GridRect::EMPTY,
            changed: GridRect::EMPTY,
            transfers: 0,
            visits: 0,
        }
    }

    /// Sweeps until stable (or the sweep cap), the first sweep over every
    /// sample of `seeds` (local, non-empty).
    fn run(&mut self, seeds: GridRect) {
        for (c, r) in seeds.iter() {
            self.now[r * self.width + c] = true;
        }
        let mut rect = seeds;
        for _ in 0..SETTLE_MAX_SWEEPS {
            for r in rect.j0..rect.j1 {
                for c in rect.i0..rect.i1 {
                    let l = r * self.width + c;
                    if self.now[l] {
                        self.now[l] = false;
                        self.visits += 1;
                        self.relax_sample(c, r);
                    }
                }
            }
            if self.next_rect.is_empty() {
                break;
            }
            std::mem::swap(&mut self.now, &mut self.next);
            rect = std::mem::replace(&mut self.next_rect, GridRect::EMPTY);
        }
    }

    /// Marks every sample moved by the run as slumped.
    fn mark_slumped(&mut self) {
        for (d, &f) in self.disturbed.iter_mut().zip(&self.flags) {
            if f & MOVED != 0 {
                *d = (*d).max(DISTURBED_SLUMPED);
            }
        }
    }

    /// Relaxes the four forward edges of sample `(c, r)`.
    #[inline]
    fn relax_sample(&mut self, c: usize, r: usize) {
        let (w, l) = (self.width, r * self.width + c);
        if self.flags[l] & HELD != 0 {
            return;
        }
        let diagonal = std::f32::consts::SQRT_2;
        let right = c + 1 < w;
        if right {
            self.relax_edge(l, l + 1, 1.0);
        }
        if r + 1 < self.height {
            self.relax_edge(l, l + w, 1.0);
            if right {
                self.relax_edge(l, l + w + 1, diagonal);
            }
            if c > 0 {
                self.relax_edge(l, l + w - 1, diagonal);
            }
        }
    }

    /// Moves part of the excess across the edge between local samples `a`
    /// and `b` (`length` in cells) if it is steeper than repose.
    #[inline(always)]
    fn relax_edge(&mut self, a: usize, b: usize, length: f32) {
        // Moves only if one end is disturbed and neither is held.
        if (self.flags[a] | self.flags[b]) & (DISTURBED | HELD) != DISTURBED {
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
            let (c, r) = (l % self.width, l / self.width);
            self.changed = grow(self.changed, c, r, c + 1, r + 1);
            self.mark_owners(c, r);
        }
    }

    /// Marks for the next sweep every sample owning a forward edge that
    /// touches `(c, r)`: itself, its left neighbour and the three samples
    /// of the row above.
    #[inline]
    fn mark_owners(&mut self, c: usize, r: usize) {
        let w = self.width;
        let (c0, c1) = (c.saturating_sub(1), (c + 1).min(w - 1));
        self.next[r * w + c0] = true;
        self.next[r * w + c] = true;
        let r0 = r.saturating_sub(1);
        if r > 0 {
            self.next[r0 * w + c0] = true;
            self.next[r0 * w + c] = true;
            self.next[r0 * w + c1] = true;
        }
        self.next_rect = grow(self.next_rect, c0, r0, c1 + 1, r + 1);
    }
}

/// `rect` grown to hold the non-empty rectangle `i0..i1` x `j0..j1`.
#[inline]
fn grow(rect: GridRect, i0: usize, j0: usize, i1: usize, j1: usize) -> GridRect {
    if rect.is_empty() {
        return GridRect { i0, j0, i1, j1 };
    }
    GridRect {
        i0: rect.i0.min(i0),
        j0: rect.j0.min(j0),
        i1: rect.i1.max(i1),
        j1: rect.j1.max(j1),
    }
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
