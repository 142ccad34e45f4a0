//! Settling (beyond the paper): disturbed ground steeper than its angle of
//! repose slides down, by pairwise mass-conserving transfers (Sumner 1999's erosion).

use std::ops::Range;

use engine::geom::GridRect;

use super::heightfield::{DISTURBED_SLUMPED, Heightfield};
use super::material::TerrainMaterial;
use super::patch::{DISTURBED, FIXED, Patch, edge_moves};
use super::pending_settle::{PendingSettle, Start};
use super::smooth::smoothing_radius;
use super::units::{REFERENCE_CELL_M, REFERENCE_RATE_HZ, cells_covering};
use super::waves::{ScratchPool, run_in_waves};

/// Settling stops when no slope exceeds the repose slope by more than this
/// (a slope, m/m: times the cell size, the height difference it allows
/// between neighbours at any spacing).
pub const SETTLE_TOLERANCE: f32 = 1e-3;
/// How far beyond the carve rectangle settling may move material, metres:
/// room for a slump's runout on a slope (8 reference cells, about 16 cm).
pub const SETTLE_MARGIN_M: f32 = 8.0 * REFERENCE_CELL_M;

/// Upper bound on relaxation sweeps per call at the reference spacing
/// ([`REFERENCE_CELL_M`]): a sweep carries a slump about one sample, so the
/// bound is a reach of 256 reference cells (5 m), converted to sweeps on
/// each grid by [`settle_max_sweeps`].
pub const SETTLE_MAX_SWEEPS: usize = 256;

/// [`SETTLE_MAX_SWEEPS`] on this grid: 256 reference cells in samples.
pub fn settle_max_sweeps(hf: &Heightfield) -> usize {
    cells_covering(
        SETTLE_MAX_SWEEPS as f32 * REFERENCE_CELL_M,
        hf.grid().cell_size(),
    )
    .max(1)
}

/// Over-relaxation of a settling transfer: a pair steeper than repose by
/// `excess` gives up `SETTLE_OVERRELAXATION / 2` of it instead of half, so it
/// ends up to `(SETTLE_OVERRELAXATION - 1) * excess` below the angle of
/// repose. Like a real avalanche, which stops at a slope a few degrees below
/// the steepest stable one, a slump runs a little past repose; the walls
/// then need about a third of the transfers and sweeps. In `[1, 2)`:
/// 1 puts every pair exactly at repose. The run past repose is at most
/// [`SETTLE_RUNOUT_SLOPE`].
pub const SETTLE_OVERRELAXATION: f32 = 1.5;

/// The furthest a settling transfer leaves a pair below the angle of repose,
/// as a slope (m/m; 0.1 is about 4 degrees below sand's 34): the same at
/// any grid spacing, where [`SETTLE_OVERRELAXATION`]'s share of the excess
/// alone would leave coarse grids' walls shallower (their excesses are
/// larger in metres per pair).
pub const SETTLE_RUNOUT_SLOPE: f32 = 0.1;

/// [`SETTLE_MARGIN_M`] in samples of this grid (rounded up).
pub fn settle_margin_cells(hf: &Heightfield) -> usize {
    cells_covering(SETTLE_MARGIN_M, hf.grid().cell_size())
}

/// The window the smoothing and settling stages of one step may change
/// around a carve rectangle: grown by the larger of the smoothing radius and
/// the settling margin (both in metres, converted to this grid's samples),
/// clipped to the grid (empty for an empty rectangle).
pub fn stage_window(hf: &Heightfield, carved: GridRect) -> GridRect {
    let g = hf.grid();
    let margin = smoothing_radius(hf).max(settle_margin_cells(hf));
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
/// [`settle_max_sweeps`]. Everything is in a fixed order, so the result is
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
///   not move: the foot supports the walls, as Sumner's steeper in-contact angle;
/// - a transfer never takes a sample below its firm floor
///   ([`Heightfield::firm_floor`]): firm ground holds any slope, and material
///   may still slide onto it.
pub fn settle(hf: &mut Heightfield, window: GridRect) -> GridRect {
    settle_from(hf, window, window)
}

/// The work buffers of the settling calls (`*_with`), reused from call to
/// call (they grow to the largest window and are not reallocated after).
/// Not part of any terrain's state.
#[derive(Default)]
pub struct SettleScratch {
    /// Patches to load windows into (a relaxed one travels with its result
    /// until it is written back, then returns here).
    spare: Vec<Patch>,
    buffers: SettleBuffers,
}

impl std::fmt::Debug for SettleScratch {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("SettleScratch")
    }
}

/// [`settle`] inside `window`, with the first sweep only over `seeds` (grown
/// by one sample): the samples that changed since the window was last stable,
/// e.g. the rectangles carving and smoothing report. Everything else in the
/// window is assumed stable; slumps still spread anywhere in `window`.
pub fn settle_from(hf: &mut Heightfield, window: GridRect, seeds: GridRect) -> GridRect {
    match first_sweep(hf, window, seeds) {
        Some((w, first)) => {
            let scratch = &mut SettleScratch::default();
            relax_window(hf, scratch, w, &Start::Scan(first), usize::MAX, 0).changed
        }
        None => GridRect::EMPTY,
    }
}

/// [`settle_from`] for one fixed step of `dt` seconds: stops once the step's
/// sample visits reach [`settle_step_visits`] (or at the end of the row of
/// the first sweep that reaches it) and leaves the rest of the work pending in the terrain, for
/// [`settle_pending`] to continue in the next steps. Returns the rectangle
/// of samples that changed.
///
/// A released print slumps over a few steps instead of in one (a real sand
/// wall takes a moment to run down too), so no single step pays for a whole
/// print. When `seeds` meet a print released this step
/// ([`super::StepChanges::released`]), the whole run, first sweep included,
/// waits for the next step: the release step already pays for smoothing the
/// whole print. The end state meets the same stopping rule as [`settle_from`]
/// (no moving slope above repose by more than [`SETTLE_TOLERANCE`]); the
/// order of the transfers differs slightly when a sweep is cut.
///
/// Works in fresh buffers; [`settle_step_with`] reuses a caller's.
pub fn settle_step(hf: &mut Heightfield, window: GridRect, seeds: GridRect, dt: f32) -> GridRect {
    settle_step_with(hf, &mut SettleScratch::default(), window, seeds, dt)
}

/// [`settle_step`] in the buffers of `scratch`.
pub fn settle_step_with(
    hf: &mut Heightfield,
    scratch: &mut SettleScratch,
    window: GridRect,
    seeds: GridRect,
    dt: f32,
) -> GridRect {
    let Some((work, deferred)) = step_work(hf, window, seeds) else {
        return GridRect::EMPTY;
    };
    if deferred {
        hf.pending_settle_mut().push(work);
        return GridRect::EMPTY;
    }
    let budget = settle_step_visits(hf, dt);
    let outcome = relax_window(hf, scratch, work.window, &work.start, budget, 0);
    hf.pending_settle_mut().extend(outcome.left);
    outcome.changed
}

/// The work of a [`settle_step`] call over `window` from `seeds`, and
/// whether it waits for the next step (its seeds meet a print released this
/// step); `None` when there are no seeds.
fn step_work(hf: &Heightfield, window: GridRect, seeds: GridRect) -> Option<(PendingSettle, bool)> {
    let (w, first) = first_sweep(hf, window, seeds)?;
    let work = PendingSettle {
        window: w,
        start: Start::Scan(first),
        sweeps: 0,
    };
    Some((work, hf.changes().released.intersects(&seeds)))
}

/// The visit budget of pending `work` in a step of `visits`: half of them
/// for a released print's first sweep ([`release_scan_visits`]).
fn pending_budget(work: &PendingSettle, visits: usize) -> usize {
    match work.start {
        Start::Scan(_) => release_scan_visits(visits),
        Start::Queued(_) => visits,
    }
}

/// Continues the settling work that earlier [`settle_step`] calls left
/// pending, each window for up to [`settle_step_visits`] sample visits in
/// this step of `dt` seconds (half as many for a released print's first
/// sweep); returns the rectangle of samples that changed. Call it once per
/// step (the terrain systems and [`super::step_foot`] do).
///
/// Works in fresh buffers; [`settle_pending_with`] reuses a caller's.
pub fn settle_pending(hf: &mut Heightfield, dt: f32) -> GridRect {
    settle_pending_with(hf, &mut SettleScratch::default(), dt)
}

/// [`settle_pending`] in the buffers of `scratch`.
pub fn settle_pending_with(hf: &mut Heightfield, scratch: &mut SettleScratch, dt: f32) -> GridRect {
    let pending = std::mem::take(hf.pending_settle_mut());
    let mut changed = GridRect::EMPTY;
    let visits = settle_step_visits(hf, dt);
    for work in pending {
        let budget = pending_budget(&work, visits);
        let outcome = relax_window(hf, scratch, work.window, &work.start, budget, work.sweeps);
        changed = changed.union(&outcome.changed);
        hf.pending_settle_mut().extend(outcome.left);
    }
    changed
}

/// [`settle_pending_with`] and then [`settle_step_with`] for each
/// `(window, seeds)` of `windows`, with the result of those calls in that
/// order; calls whose windows are apart run in parallel on the current rayon
/// pool (the same bits on any number of threads). `scratches` holds one set
/// of buffers per parallel call, grown on demand.
pub fn settle_each(
    hf: &mut Heightfield,
    scratches: &mut ScratchPool<SettleScratch>,
    windows: &[(GridRect, GridRect)],
    dt: f32,
) {
    let visits = settle_step_visits(hf, dt);
    // What each call leaves pending, in call order; the runs fill their slots.
    let mut slots: Vec<Option<PendingSettle>> = Vec::new();
    // (slot, visit budget, work)
    let mut runs: Vec<(usize, usize, PendingSettle)> = Vec::new();
    for work in std::mem::take(hf.pending_settle_mut()) {
        runs.push((slots.len(), pending_budget(&work, visits), work));
        slots.push(None);
    }
    for &(window, seeds) in windows {
        let Some((work, deferred)) = step_work(hf, window, seeds) else {
            continue;
        };
        if deferred {
            slots.push(Some(work));
        } else {
            runs.push((slots.len(), visits, work));
            slots.push(None);
        }
    }
    let run_windows: Vec<GridRect> = runs.iter().map(|(_, _, work)| work.window).collect();
    run_in_waves(
        hf,
        &run_windows,
        &mut scratches.0,
        |hf, scratch, k| {
            let (_, budget, work) = &runs[k];
            scratch.relax(hf, work.window, &work.start, *budget, work.sweeps)
        },
        |hf, scratch, k, relaxed| slots[runs[k].0] = scratch.commit(hf, relaxed).left,
    );
    hf.pending_settle_mut().extend(slots.into_iter().flatten());
}

/// The ground area settling may visit per second, m²/s: 96 sample visits
/// per step at the reference grid and rate (about 2.2 m²/s). A released
/// dry-sand print at the reference spacing (the heaviest case: the whole
/// print's walls slump at once) needs about 500 visits, so it slumps in about
/// 0.1 s.
pub const SETTLE_AREA_RATE_M2_S: f32 =
    96.0 * REFERENCE_RATE_HZ * REFERENCE_CELL_M * REFERENCE_CELL_M;

/// Sample visits after which a [`settle_step`] or [`settle_pending`] call in
/// a step of `dt` seconds stops (a row of the first sweep is finished
/// first) and leaves the rest for the next step: [`SETTLE_AREA_RATE_M2_S`]
/// × `dt` in this grid's cells (at least 1). So a slump takes the same time
/// at any resolution and step rate (96 visits at the reference grid and rate).
pub fn settle_step_visits(hf: &Heightfield, dt: f32) -> usize {
    let cell = hf.grid().cell_size();
    let visits = SETTLE_AREA_RATE_M2_S * dt.max(0.0) / (cell * cell);
    if visits.is_finite() {
        (visits.round() as usize).max(1)
    } else {
        usize::MAX
    }
}

/// Sample visits of the step that starts settling a print released in the
/// step before (see [`settle_step`]), out of a step's `visits`: half of
/// them, as that step also scans the whole print for its first sweep.
fn release_scan_visits(visits: usize) -> usize {
    (visits / 2).max(1)
}

/// The window clipped to the grid and the first sweep's rectangle (the
/// seeds grown by one sample, inside the window); `None` when there are no seeds.
fn first_sweep(
    hf: &Heightfield,
    window: GridRect,
    seeds: GridRect,
) -> Option<(GridRect, GridRect)> {
    let full = hf.grid().full_rect();
    let w = window.intersect(&full);
    let seeds = seeds.intersect(&w);
    if seeds.is_empty() {
        return None;
    }
    Some((
        w,
        seeds.expand(1, full.width(), full.height()).intersect(&w),
    ))
}

/// What one [`relax_window`] call did.
struct Outcome {
    /// The rectangle of samples that changed.
    changed: GridRect,
    /// The work left when the visit budget ran out.
    left: Option<PendingSettle>,
}

/// What [`SettleScratch::relax`] computed in its patch, before it is written back.
struct Relaxed {
    patch: Patch,
    outcome: Outcome,
    transfers: usize,
    visits: usize,
}

/// Relaxes `w` (inside the grid) from `start` until stable, the sweep cap
/// (counting `sweeps_done` earlier sweeps) or the sweep that reaches
/// `budget` visits.
fn relax_window(
    hf: &mut Heightfield,
    scratch: &mut SettleScratch,
    w: GridRect,
    start: &Start,
    budget: usize,
    sweeps_done: usize,
) -> Outcome {
    let relaxed = scratch.relax(hf, w, start, budget, sweeps_done);
    scratch.commit(hf, relaxed)
}

impl SettleScratch {
    /// The sweeps of [`relax_window`] in the scratch's patch, reading `hf`
    /// (nothing written back yet).
    fn relax(
        &mut self,
        hf: &Heightfield,
        w: GridRect,
        start: &Start,
        budget: usize,
        sweeps_done: usize,
    ) -> Relaxed {
        let cell = hf.grid().cell_size();
        let max_sweeps = settle_max_sweeps(hf);
        let mut patch = self.spare.pop().unwrap_or_default();
        patch.load(hf, w);
        let settle = &mut self.buffers;
        settle.limits(&patch, hf.table().materials(), cell);
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
        let (first, queued) = match start {
            Start::Scan(r) => (
                Some((patch.local(r.i0, r.j0), r.width(), r.height())),
                &[][..],
            ),
            Start::Queued(q) => (None, &q[..]),
        };
        let nx = hf.grid().nx();
        let queued_local: Vec<usize> = queued
            .iter()
            .map(|&k| patch.local(k % nx, k / nx))
            .collect();
        let stride = patch.stride;
        let mut relax = Relaxation {
            heights: &mut patch.heights,
            floor: &patch.floor,
            flags: &mut patch.flags,
            limit,
            next,
            next_words: 0..0,
            stride,
            settle_to: SETTLE_TOLERANCE * cell,
            runout: SETTLE_RUNOUT_SLOPE * cell,
            transfers: 0,
            visits: 0,
        };
        for l in queued_local {
            relax.queue(l);
        }
        let cap = max_sweeps.saturating_sub(sweeps_done);
        let sweeps = relax.run(first, steep, now, cap, budget);
        let left = relax.queued();
        let (transfers, visits) = (relax.transfers, relax.visits);
        let changed = if transfers > 0 {
            mark_slumped(&mut patch)
        } else {
            GridRect::EMPTY
        };
        let sweeps = sweeps_done + sweeps;
        let left = (!left.is_empty() && sweeps < max_sweeps).then(|| PendingSettle {
            window: w,
            start: Start::Queued(left.into_iter().map(|l| patch.grid_index(l, nx)).collect()),
            sweeps,
        });
        Relaxed {
            patch,
            outcome: Outcome { changed, left },
            transfers,
            visits,
        }
    }

    /// Writes what [`SettleScratch::relax`] changed back into `hf`, marks it
    /// dirty and counts the work; keeps the patch for the next call.
    fn commit(&mut self, hf: &mut Heightfield, relaxed: Relaxed) -> Outcome {
        let mut parts = hf.parts_mut();
        parts.changes.settle_transfers += relaxed.transfers;
        parts.changes.settle_visits += relaxed.visits;
        let changed = relaxed.outcome.changed;
        if !changed.is_empty() {
            relaxed.patch.store(&mut parts, changed);
            parts.changes.rects.add(changed);
        }
        self.spare.push(relaxed.patch);
        relaxed.outcome
    }
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
    /// Firm floor per sample: a transfer never takes a sample below it.
    floor: &'p [f32],
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
    /// The most a transfer leaves a pair below the limit, per unit length, metres.
    runout: f32,
    transfers: usize,
    visits: usize,
}

impl Relaxation<'_> {
    /// Sweeps until stable, for at most `max_sweeps` sweeps, or until the
    /// visits reach `budget` (checked before each visit, and between the rows
    /// of the first sweep); the samples a cut sweep did not visit are queued
    /// for the next sweep. Returns the sweeps made.
    /// With `first` = `(start, width, rows)`, the first sweep goes over those
    /// local samples in row-major order, visiting the samples that own an
    /// edge steeper than repose when the sweep reaches their row (found by a
    /// branch-free scan of the row into `steep`); a sample made steep by a
    /// transfer is queued for the next sweep. Without, the first sweep visits
    /// the queued samples. `now` is the bit set of the running sweep (all clear).
    fn run(
        &mut self,
        first: Option<(usize, usize, usize)>,
        steep: &mut Vec<u8>,
        now: &mut [u64],
        max_sweeps: usize,
        budget: usize,
    ) -> usize {
        let mut sweeps = 0;
        if let Some((start, width, rows)) = first {
            for r in 0..rows {
                let row = start + r * self.stride;
                self.scan_row(row, width, steep);
                // Out of budget: the rest of the sweep is queued for the next
                // one (only the samples steep now: an edge that is not gets
                // steep only when a transfer touches it, which queues its owner).
                let in_budget = self.visits < budget;
                for (k, &is_steep) in steep.iter().enumerate() {
                    match (is_steep != 0, in_budget) {
                        (true, true) => self.visit(row + k),
                        (true, false) => self.queue(row + k),
                        _ => {}
                    }
                }
            }
            sweeps = 1;
        }
        while sweeps < max_sweeps && self.visits < budget {
            let words = std::mem::replace(&mut self.next_words, 0..0);
            if words.is_empty() {
                break;
            }
            now[words.clone()].copy_from_slice(&self.next[words.clone()]);
            self.next[words.clone()].fill(0);
            for w in words {
                let mut bits = std::mem::take(&mut now[w]);
                while bits != 0 {
                    if self.visits >= budget {
                        // Out of budget: the rest of the sweep joins the next one.
                        self.next[w] |= bits;
                        self.cover_words(w, w + 1);
                        break;
                    }
                    self.visit(w * 64 + bits.trailing_zeros() as usize);
                    bits &= bits - 1;
                }
            }
            sweeps += 1;
        }
        sweeps
    }

    /// The samples queued for the next sweep (local indices, ascending).
    fn queued(&self) -> Vec<usize> {
        let mut out = Vec::new();
        for w in self.next_words.clone() {
            let mut bits = self.next[w];
            while bits != 0 {
                out.push(w * 64 + bits.trailing_zeros() as usize);
                bits &= bits - 1;
            }
        }
        out
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
            let heights = self.heights[a.clone()].iter().zip(&self.heights[b.clone()]);
            let limits = self.limit[a.clone()].iter().zip(&self.limit[b.clone()]);
            let flags = self.flags[a].iter().zip(&self.flags[b]);
            for (((out, (&ha, &hb)), (&la, &lb)), (&fa, &fb)) in
                steep.iter_mut().zip(heights).zip(limits).zip(flags)
            {
                let drop = ha - hb;
                let limit = if drop >= 0.0 { la } else { lb };
                let too_steep = drop.abs() - limit * length > 0.0;
                *out |= u8::from(too_steep & edge_moves(fa, fb));
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

    /// Moves [`SETTLE_OVERRELAXATION`] / 2 of `excess` from `hi` to `lo` (its
    /// run past repose capped at [`SETTLE_RUNOUT_SLOPE`]), or
    /// what `hi` has above its firm floor if less, and queues the samples
    /// whose edges this touches.
    #[cold]
    fn transfer(&mut self, hi: usize, lo: usize, excess: f32, length: f32) {
        let base = excess + self.settle_to * length;
        let past = ((SETTLE_OVERRELAXATION - 1.0) * base).min(self.runout * length);
        let wanted = 0.5 * (base + past);
        let moved = wanted.min(self.heights[hi] - self.floor[hi]);
        // `moved` is finite: heights and floors are.
        if moved <= 0.0 {
            return;
        }
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
    /// row above.
    #[inline]
    fn queue_owners(&mut self, l: usize) {
        let s = self.stride;
        for owner in [l - s - 1, l - s, l - s + 1, l - 1, l] {
            self.set_queued(owner);
        }
        self.cover_words((l - s - 1) / 64, l / 64 + 1);
    }

    /// Queues local sample `l` for the next sweep.
    fn queue(&mut self, l: usize) {
        self.set_queued(l);
        self.cover_words(l / 64, l / 64 + 1);
    }

    /// Sets the bit of local sample `l` in the next sweep's set (frame and
    /// held samples own no moving edge and are skipped).
    #[inline(always)]
    fn set_queued(&mut self, l: usize) {
        let not_fixed = u64::from(self.flags[l] & FIXED == 0);
        self.next[l / 64] |= not_fixed << (l % 64);
    }

    /// Grows the range of words of the next sweep's set to hold `first..end`.
    #[inline(always)]
    fn cover_words(&mut self, first: usize, end: usize) {
        let words = &mut self.next_words;
        *words = if words.start >= words.end {
            first..end
        } else {
            words.start.min(first)..words.end.max(end)
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

    const DT: f32 = 1.0 / 60.0;

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
        hf.parts_mut()
            .changes
            .held
            .push_group(GridRect::new(20, 20, 21, 21), &[k]);
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

    /// A disturbed 5 x 5 block of sand standing 0.3 m above flat ground.
    fn block() -> Heightfield {
        let mut hf = pillar(0);
        for (i, j) in GridRect::new(18, 18, 23, 23).iter() {
            hf.grid_mut().set_height(i, j, 1.3);
            let k = hf.grid().index(i, j);
            hf.parts_mut().disturbed[k] = 255;
        }
        hf
    }

    /// The step whose settling budget on `hf`'s grid is 96 visits, as at
    /// the reference grid and rate.
    fn budget_dt(hf: &Heightfield) -> f32 {
        let cell = hf.grid().cell_size();
        96.0 * cell * cell / SETTLE_AREA_RATE_M2_S
    }

    /// Runs [`settle_step`] then [`settle_pending`] step by step until
    /// nothing is pending; returns the number of steps.
    fn settle_in_steps(hf: &mut Heightfield, window: GridRect) -> usize {
        let dt = budget_dt(hf);
        assert_eq!(settle_step_visits(hf, dt), 96);
        hf.begin_step();
        settle_step(hf, window, GridRect::new(18, 18, 23, 23), dt);
        let mut steps = 1;
        while hf.settling_pending() {
            // Each step stays within the budget (plus the rest of the row of
            // the first sweep that reaches it).
            assert!(hf.changes().settle_visits <= settle_step_visits(hf, dt) + window.width());
            hf.begin_step();
            settle_pending(hf, dt);
            steps += 1;
        }
        steps
    }

    #[test]
    fn budgeted_settling_spreads_over_steps_and_ends_stable() {
        let window = GridRect::new(5, 5, 36, 36);
        let mut budgeted = block();
        let before = budgeted.grid().volume();
        let steps = settle_in_steps(&mut budgeted, window);
        assert!(steps > 3, "{steps} steps");
        assert!(((budgeted.grid().volume() - before) / before).abs() < 1e-7);
        // Stable by the same rule as the unbudgeted run: nothing more moves.
        assert!(settle(&mut budgeted, window).is_empty());
        // The same slump as in one go, to within a centimetre (of a 30 cm block).
        let mut whole = block();
        settle(&mut whole, window);
        for (i, j) in window.iter() {
            let d = budgeted.grid().height(i, j) - whole.grid().height(i, j);
            assert!(d.abs() < 1e-2, "({i}, {j}): {d}");
        }
        // Deterministic.
        let mut again = block();
        settle_in_steps(&mut again, window);
        assert_eq!(again.grid(), budgeted.grid());
    }

    #[test]
    fn a_print_released_this_step_starts_settling_in_the_next_step() {
        let window = GridRect::new(5, 5, 36, 36);
        let seeds = GridRect::new(18, 18, 23, 23);
        let mut deferred = block();
        let before = deferred.grid().clone();
        deferred.begin_step();
        deferred.parts_mut().changes.released.add(seeds);
        assert!(settle_step(&mut deferred, window, seeds, DT).is_empty());
        assert_eq!(deferred.grid(), &before);
        assert_eq!(deferred.changes().settle_visits, 0);
        assert!(deferred.settling_pending());
        // The next step scans the print and relaxes it on a smaller budget.
        deferred.begin_step();
        assert!(!settle_pending(&mut deferred, DT).is_empty());
        let visits = deferred.changes().settle_visits;
        let budget = release_scan_visits(settle_step_visits(&deferred, DT));
        assert!(visits > 0 && visits <= budget + window.width());
        while deferred.settling_pending() {
            deferred.begin_step();
            settle_pending(&mut deferred, DT);
        }
        // It ends stable, as a settling started in the release step would.
        assert!(settle(&mut deferred, window).is_empty());
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

    #[test]
    fn settling_never_takes_a_sample_below_its_floor() {
        // Trodden sand at its initial height beside ground cut 30 cm lower
        // (below its own floor): without a floor the edge would slump far
        // down; with it, the loose 5 cm slide and firm ground holds the step.
        let mut hf = pillar(0);
        hf.grid_mut().set_height(20, 20, 1.0);
        for (i, j) in GridRect::new(20, 0, 41, 41).iter() {
            hf.grid_mut().set_height(i, j, 0.7);
        }
        hf.parts_mut().disturbed.fill(255);
        let before = hf.grid().clone();
        settle(&mut hf, GridRect::new(5, 5, 36, 36));
        for k in 0..41 * 41 {
            let (h, was) = (hf.grid().heights()[k], before.heights()[k]);
            assert!(h >= hf.firm_floor(k).min(was) - 1e-6, "sample {k}: {h}");
        }
        // The loose layer did slide onto the lower ground.
        assert!(hf.grid().height(19, 20) < 1.0 && hf.grid().height(20, 20) > 0.7);
        assert!(((hf.grid().volume() - before.volume()) / before.volume()).abs() < 1e-6);
    }

    #[test]
    fn the_budget_is_an_area_per_second() {
        let at = |cells: usize, dt: f32| {
            let grid = flat(GridSpec::square(10.0, cells), 1.0).unwrap();
            let hf =
                Heightfield::from_grid(grid, MaterialTable::with_presets(), MaterialId(0)).unwrap();
            settle_step_visits(&hf, dt)
        };
        assert_eq!(at(513, DT), 96);
        assert_eq!(at(1025, DT), 384);
        assert_eq!(at(257, DT), 24);
        assert_eq!(at(513, 1.0 / 120.0), 48);
        assert_eq!(at(513, 1.0 / 20.0), 288);
    }
}
