//! Smoothing: the paper's Gaussian filter of strength s_t, as conservative
//! diffusion restricted to a dirty window, in metres and seconds.

use std::ops::Range;

use engine::geom::GridRect;

use super::heightfield::{DISTURBED_RIM, Heightfield};
use super::patch::{Patch, edge_moves};
use super::units::{REFERENCE_CELL_M, REFERENCE_RATE_HZ, cells_covering};
use super::waves::{ScratchPool, run_in_waves};

/// Diffusion rate of a full pass (stable below 0.25; a full pass adds a
/// Gaussian variance of `2 * DIFFUSION_RATE` = 0.4 cell² per axis).
pub const DIFFUSION_RATE: f32 = 0.2;

/// Most diffusion passes one [`smooth`] call runs. A step that needs more
/// (s_t = 16 on a grid finer than 1 cm at 20 Hz, far outside the presets:
/// snow needs 48 passes at 1024 samples over 10 m and 20 Hz) runs this many
/// full passes, so its variance is cut short; the cut is counted in
/// [`super::StepChanges::smoothing_capped`].
pub const MAX_SMOOTHING_PASSES: usize = 256;

/// Smallest trodden level (`Heightfield::disturbed`) through which smoothing
/// conducts. An edge's variance is scaled by the larger trodden level of its
/// two samples over [`DISTURBED_RIM`] (full on prints and rims), and a sample
/// that smoothing moves takes half its neighbours' largest level. So the
/// filter fades over the few samples around a rim (levels 64, 32, ... 2)
/// however many steps a stance lasts: the rim keeps the print's round shape
/// and tapers smoothly instead of spreading to the window's rectangular
/// border, and the darkening of disturbed ground fades with it.
pub const SMOOTHING_MIN_LEVEL: u8 = 2;

/// The Gaussian variance per second, m²/s (per axis), that smoothness `s_t`
/// adds to the ground it conducts through: the paper's s_t passes of 0.4
/// cell² per step at the reference grid and rate,
/// `s_t * 0.4 * REFERENCE_CELL_M² * REFERENCE_RATE_HZ`.
pub fn smoothing_variance_rate(s_t: f32) -> f32 {
    s_t * 2.0 * DIFFUSION_RATE * REFERENCE_CELL_M * REFERENCE_CELL_M * REFERENCE_RATE_HZ
}

/// How many full passes (of 0.4 cell² each) give the variance smoothness
/// `s_t` adds in a step of `dt` seconds on cells of `cell` metres:
/// `s_t * (REFERENCE_CELL_M / cell)² * REFERENCE_RATE_HZ * dt` (s_t itself
/// at the reference grid and rate). Fractional.
pub fn smoothing_pass_equivalent(s_t: f32, cell: f32, dt: f32) -> f32 {
    smoothing_variance_rate(s_t) * dt / (2.0 * DIFFUSION_RATE * cell * cell)
}

/// How far smoothing reaches beyond the window it is given, metres: the
/// largest s_t of the table in reference cells (its passes per step at the
/// reference grid, one cell each).
pub fn smoothing_reach_m(hf: &Heightfield) -> f32 {
    hf.table().max_smoothness() * REFERENCE_CELL_M
}

/// [`smoothing_reach_m`] in samples of this grid (rounded up).
pub fn smoothing_radius(hf: &Heightfield) -> usize {
    cells_covering(smoothing_reach_m(hf), hf.grid().cell_size())
}

/// How long a smoothing of `window` in a step of `dt` seconds lasts,
/// seconds: `dt`, or one reference step (1 / [`REFERENCE_RATE_HZ`]) when
/// `window` (clipped to the grid) lies in the prints released this step
/// ([`super::StepChanges::released`]). A print's walls are smoothed once,
/// when the sole lifts: an event, the same at any step rate, unlike the
/// smoothing of a rim around a planted sole, which goes on for the stance.
pub fn smoothing_duration(hf: &Heightfield, window: GridRect, dt: f32) -> f32 {
    let window = window.intersect(&hf.grid().full_rect());
    if hf.changes().released.contains_rect(&window) {
        1.0 / REFERENCE_RATE_HZ
    } else {
        dt
    }
}

/// Smooths the heights around `window` for a step of `dt` seconds; returns
/// the rectangle it worked in (`window` grown by [`smoothing_radius`],
/// clipped), which may have changed.
///
/// Each edge of the rectangle adds the Gaussian variance
/// [`smoothing_variance_rate`]`(s) * t` (m²), with `t` the
/// [`smoothing_duration`] (`dt`, or one reference step for a released
/// print), where `s` is the mean
/// smoothness of its two samples' materials, scaled by their trodden level
/// (see `SMOOTHING_MIN_LEVEL`). In cells that is
/// [`smoothing_pass_equivalent`] full passes; the call runs
/// `ceil(largest edge's passes)` passes (at most [`MAX_SMOOTHING_PASSES`]),
/// each edge at its share of [`DIFFUSION_RATE`], so every edge's variance
/// is exact. A pass moves height across every 4-neighbour edge in flux
/// form: `flux = rate * (h_b - h_a)`, added to one sample and taken from
/// the other (the same float on both sides), so the volume is conserved (to
/// float rounding); no flux crosses the rectangle's border. An edge never
/// takes more than a quarter of a sample's height above its firm floor in a
/// pass ([`Heightfield::firm_floor`]), so smoothing never takes a sample
/// below it. An edge carries flux only if one of its samples has a trodden
/// level of at least `SMOOTHING_MIN_LEVEL`, so natural terrain is never
/// flattened. It does not conduct either if one of its samples is held by a
/// sole this step (the foot occupies the print; its walls are smoothed once
/// it lifts).
///
/// Only the rectangle of samples that actually changed is marked dirty; the
/// window is recorded in [`super::StepChanges::smoothed`].
///
/// Works in fresh buffers; [`smooth_with`] reuses a caller's.
pub fn smooth(hf: &mut Heightfield, window: GridRect, dt: f32) -> GridRect {
    smooth_with(hf, &mut SmoothScratch::default(), window, dt)
}

/// The work buffers of [`smooth_with`], reused from call to call (they grow
/// to the largest window and are not reallocated after). Not part of any
/// terrain's state.
#[derive(Default)]
pub struct SmoothScratch {
    /// Patches to load windows into (a computed one travels with its result
    /// until it is written back, then returns here).
    spare: Vec<Patch>,
    buffers: SmoothBuffers,
}

/// What [`SmoothScratch::compute`] did in its patch, before it is written back.
struct Smoothed {
    patch: Patch,
    changed: GridRect,
    capped: bool,
}

impl std::fmt::Debug for SmoothScratch {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("SmoothScratch")
    }
}

/// [`smooth`] in the buffers of `scratch`.
pub fn smooth_with(
    hf: &mut Heightfield,
    scratch: &mut SmoothScratch,
    window: GridRect,
    dt: f32,
) -> GridRect {
    let (w, scale) = smoothing_plan(hf, window, dt);
    hf.parts_mut().changes.smoothed.push(w);
    if let Some(scale) = scale {
        let result = scratch.compute(hf, w, scale);
        scratch.commit(hf, result);
    }
    w
}

/// [`smooth`] around each of `windows`, with the result of calling it for
/// them in list order; calls whose grown windows are apart run in parallel
/// on the current rayon pool (the same bits on any number of threads).
/// `scratches` holds one set of buffers per parallel call, grown on demand.
pub fn smooth_each(
    hf: &mut Heightfield,
    scratches: &mut ScratchPool<SmoothScratch>,
    windows: &[GridRect],
    dt: f32,
) {
    let plans: Vec<(GridRect, Option<f32>)> = (windows.iter())
        .map(|&window| smoothing_plan(hf, window, dt))
        .collect();
    hf.parts_mut()
        .changes
        .smoothed
        .extend(plans.iter().map(|&(w, _)| w));
    let work: Vec<(GridRect, f32)> = (plans.into_iter())
        .filter_map(|(w, scale)| scale.map(|s| (w, s)))
        .collect();
    let grown: Vec<GridRect> = work.iter().map(|&(w, _)| w).collect();
    run_in_waves(
        hf,
        &grown,
        &mut scratches.0,
        |hf, scratch, k| scratch.compute(hf, work[k].0, work[k].1),
        |hf, scratch, _, result| scratch.commit(hf, result),
    );
}

/// The rectangle a smoothing of `window` works in (grown by
/// [`smoothing_radius`], clipped) and its passes per unit of smoothness
/// ([`smoothing_pass_equivalent`] of s_t = 1 over the [`smoothing_duration`]);
/// no scale when there is nothing to do.
fn smoothing_plan(hf: &Heightfield, window: GridRect, dt: f32) -> (GridRect, Option<f32>) {
    let full = hf.grid().full_rect();
    let radius = smoothing_radius(hf);
    let w = window
        .intersect(&full)
        .expand(radius, full.width(), full.height());
    if w.is_empty() || !(dt.is_finite() && dt > 0.0) || hf.table().max_smoothness() == 0.0 {
        return (w, None);
    }
    let duration = smoothing_duration(hf, window, dt);
    let scale = smoothing_pass_equivalent(1.0, hf.grid().cell_size(), duration);
    (w, Some(scale))
}

impl SmoothScratch {
    /// Smooths `w` (inside the grid) in a patch loaded from `hf` (nothing
    /// written back yet).
    fn compute(&mut self, hf: &Heightfield, w: GridRect, scale: f32) -> Smoothed {
        let mut patch = self.spare.pop().unwrap_or_default();
        patch.load(hf, w);
        let buffers = &mut self.buffers;
        buffers.smoothness.clear();
        (buffers.smoothness).extend(hf.table().materials().iter().map(|m| m.smoothness * scale));
        let (changed, capped) = buffers.run(&mut patch);
        Smoothed {
            patch,
            changed,
            capped,
        }
    }

    /// Writes what [`SmoothScratch::compute`] changed back into `hf`, marks
    /// it dirty and counts a capped call; keeps the patch for the next call.
    fn commit(&mut self, hf: &mut Heightfield, smoothed: Smoothed) {
        let mut parts = hf.parts_mut();
        parts.changes.smoothing_capped += usize::from(smoothed.capped);
        if !smoothed.changed.is_empty() {
            smoothed.patch.store(&mut parts, smoothed.changed);
            parts.changes.rects.add(smoothed.changed);
        }
        self.spare.push(smoothed.patch);
    }
}

/// Smoothing's buffers, reused from call to call.
#[derive(Default)]
pub(crate) struct SmoothBuffers {
    /// Full passes per step of each material id (smoothness scaled to this
    /// grid and step).
    smoothness: Vec<f32>,
    /// The same per local sample.
    sample: Vec<f32>,
    /// Full passes of the edge between local samples `l` and `l + 1` (0:
    /// none); then its rate per pass as a fraction of [`DIFFUSION_RATE`].
    edge_x: Vec<f32>,
    /// The same for the edge between local samples `l` and `l + stride`.
    edge_z: Vec<f32>,
    /// A quarter of each sample's height above its firm floor (the most one
    /// edge may take from it in a pass).
    give: Vec<f32>,
    /// Heights after the running pass.
    next: Vec<f32>,
    /// Per sample of the inner rows: 1 once a pass changed it.
    changed: Vec<u8>,
    /// The patch's trodden levels before this call marked the changed samples.
    levels: Vec<u8>,
}

impl SmoothBuffers {
    /// Runs the passes the edges need on `patch`; gives each sample they
    /// changed half the largest trodden level of its 4 neighbours (if that is
    /// more than its own) and returns their bounding rectangle (grid samples)
    /// and whether the passes were cut at [`MAX_SMOOTHING_PASSES`].
    fn run(&mut self, patch: &mut Patch) -> (GridRect, bool) {
        let needed = self.conducting_edges(patch);
        if needed == 0.0 {
            return (GridRect::EMPTY, false);
        }
        // A pass count a rounding error above a whole number is that number
        // (the rate below is then clamped to a full pass).
        let passes = ((needed - 1e-4).ceil() as usize).max(1);
        let capped = passes > MAX_SMOOTHING_PASSES;
        let passes = passes.min(MAX_SMOOTHING_PASSES);
        let per_pass = 1.0 / passes as f32;
        for e in self.edge_x.iter_mut().chain(&mut self.edge_z) {
            *e = DIFFUSION_RATE * (*e * per_pass).min(1.0);
        }
        let (s, len) = (patch.stride, patch.heights.len());
        // The inner rows (window rows with their frame columns): `s..len - s`.
        let n = len - 2 * s;
        self.next.clear();
        self.next.extend_from_slice(&patch.heights);
        self.changed.clear();
        self.changed.resize(n, 0);
        // Only the samples a conducting edge touches can move: the passes
        // run over their span of inner-row indices; the others keep their
        // bits (their fluxes would all be zero).
        let span = conducting_span(&self.edge_x, &self.edge_z, s, n);
        self.give.clear();
        self.give.resize(len, 0.0);
        for _ in 0..passes {
            self.pass(patch, span.clone());
        }
        let changed = &self.changed;
        let rect = patch.bounds_of(|l| changed[l - s] != 0);
        self.spread_trodden_levels(patch);
        (rect, capped)
    }

    /// One diffusion pass over the inner-row indices `span` of `patch`:
    /// each edge moves height between its two samples at its rate, limited
    /// by what each side may give; marks the samples it changed.
    fn pass(&mut self, patch: &mut Patch, span: std::ops::Range<usize>) {
        let (s, len) = (patch.stride, patch.heights.len());
        let n = len - 2 * s;
        // The give of the span and of its neighbours one row away.
        let near = span.start..(span.end + 2 * s).min(len);
        for ((g, &h), &f) in self.give[near.clone()]
            .iter_mut()
            .zip(&patch.heights[near.clone()])
            .zip(&patch.floor[near])
        {
            *g = 0.25 * (h - f).max(0.0);
        }
        let h = &patch.heights;
        let (up, down) = (&h[..n], &h[2 * s..2 * s + n]);
        let (left, centre, right) = (&h[s - 1..s - 1 + n], &h[s..s + n], &h[s + 1..s + 1 + n]);
        let g = &self.give;
        let (g_up, g_down) = (&g[..n], &g[2 * s..2 * s + n]);
        let (g_left, g_centre, g_right) =
            (&g[s - 1..s - 1 + n], &g[s..s + n], &g[s + 1..s + 1 + n]);
        let (ex_left, ex) = (&self.edge_x[s - 1..s - 1 + n], &self.edge_x[s..s + n]);
        let (ez_up, ez) = (&self.edge_z[..n], &self.edge_z[s..s + n]);
        let out = &mut self.next[s..s + n];
        let changed = &mut self.changed[..n];
        // The flux from `a` into `b` over an edge of rate `r`, limited by
        // what each side may give; the same float for both samples.
        // `max`/`min` rather than `clamp`: this form lets the loop vectorise.
        let flux = |r: f32, ha: f32, hb: f32, ga: f32, gb: f32| (r * (hb - ha)).max(-ga).min(gb);
        for k in span {
            let (hc, gc) = (centre[k], g_centre[k]);
            let flux_right = flux(ex[k], hc, right[k], gc, g_right[k]);
            let flux_left = flux(ex_left[k], left[k], hc, g_left[k], gc);
            let flux_down = flux(ez[k], hc, down[k], gc, g_down[k]);
            let flux_up = flux(ez_up[k], up[k], hc, g_up[k], gc);
            let v = hc + flux_right - flux_left + flux_down - flux_up;
            out[k] = v;
            changed[k] |= u8::from(v != hc);
        }
        std::mem::swap(&mut patch.heights, &mut self.next);
    }

    /// Gives each sample the passes changed half the largest trodden level
    /// of its 4 neighbours, if that is more than its own.
    fn spread_trodden_levels(&mut self, patch: &mut Patch) {
        let (s, len) = (patch.stride, patch.heights.len());
        let n = len - 2 * s;
        self.levels.clear();
        self.levels.extend_from_slice(&patch.disturbed);
        let t = &self.levels;
        let (up, down) = (&t[..n], &t[2 * s..2 * s + n]);
        let (left, right) = (&t[s - 1..s - 1 + n], &t[s + 1..s + 1 + n]);
        let neighbours = up.iter().zip(down).zip(left.iter().zip(right));
        for ((d, &c), ((&u, &dn), (&l, &r))) in patch.disturbed[s..len - s]
            .iter_mut()
            .zip(&self.changed)
            .zip(neighbours)
        {
            if c != 0 {
                *d = (*d).max(u.max(dn).max(l.max(r)) / 2);
            }
        }
    }

    /// Fills the full passes each edge of `patch` needs; returns the largest
    /// (0 when no edge conducts).
    fn conducting_edges(&mut self, patch: &Patch) -> f32 {
        let (s, len) = (patch.stride, patch.heights.len());
        let f = &patch.flags;
        let table = &self.smoothness;
        self.sample.clear();
        self.sample
            .extend(patch.material.iter().map(|&m| table[m as usize]));
        const RIM_LEVEL: f32 = DISTURBED_RIM as f32;
        let sm = &self.sample;
        let trodden = &patch.disturbed;
        let edges = |out: &mut Vec<f32>, d: usize| {
            out.clear();
            out.extend(
                (f[..len - d].iter().zip(&f[d..]))
                    .zip(trodden[..len - d].iter().zip(&trodden[d..]))
                    .zip(sm[..len - d].iter().zip(&sm[d..]))
                    .map(|(((&fa, &fb), (&ta, &tb)), (&sa, &sb))| {
                        let level = ta.max(tb);
                        if edge_moves(fa, fb) && level >= SMOOTHING_MIN_LEVEL {
                            let weight = f32::from(level.min(DISTURBED_RIM)) / RIM_LEVEL;
                            0.5 * (sa + sb) * weight
                        } else {
                            0.0
                        }
                    }),
            );
            out.resize(len, 0.0);
        };
        edges(&mut self.edge_x, 1);
        edges(&mut self.edge_z, s);
        self.edge_x
            .iter()
            .chain(&self.edge_z)
            .fold(0.0, |a, &e| a.max(e))
    }
}

/// The inner-row indices `k` (local sample `s + k`, `k < n`) of the samples
/// a conducting edge touches: an `edge_x[l]` joins local samples `l` and
/// `l + 1`, an `edge_z[l]` joins `l` and `l + stride`. Empty when no edge conducts.
fn conducting_span(edge_x: &[f32], edge_z: &[f32], stride: usize, n: usize) -> Range<usize> {
    let first = |e: &[f32]| e.iter().position(|&r| r != 0.0);
    let last = |e: &[f32]| e.iter().rposition(|&r| r != 0.0);
    let lo = match (first(edge_x), first(edge_z)) {
        (Some(a), Some(b)) => a.min(b),
        (Some(a), None) | (None, Some(a)) => a,
        (None, None) => return 0..0,
    };
    let hi = last(edge_x)
        .map(|l| l + 1)
        .max(last(edge_z).map(|l| l + stride))
        .unwrap_or(lo);
    let start = lo.saturating_sub(stride).min(n);
    let end = (hi + 1).saturating_sub(stride).min(n);
    start..end.max(start)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::terrain::generate::{GridSpec, flat, slope};
    use crate::terrain::{MaterialId, MaterialTable};
    use glam::Vec2;

    const DT: f32 = 1.0 / 60.0;

    fn field(grid: engine::geom::HeightGrid) -> Heightfield {
        Heightfield::from_grid(grid, MaterialTable::with_presets(), MaterialId(0)).unwrap()
    }

    #[test]
    fn natural_terrain_is_left_alone() {
        let grid = slope(GridSpec::square(1.0, 41), 1.0, 30.0, Vec2::X).unwrap();
        let mut hf = field(grid.clone());
        smooth(&mut hf, GridRect::new(10, 10, 20, 20), DT);
        assert_eq!(hf.grid(), &grid);
        assert!(hf.dirty().is_empty());
    }

    #[test]
    fn a_disturbed_spike_spreads_within_the_window_and_keeps_its_volume() {
        let mut hf = field(flat(GridSpec::square(1.0, 41), 1.0).unwrap());
        let before = hf.grid().volume();
        hf.grid_mut().set_height(20, 20, 1.1);
        let k = hf.grid().index(20, 20);
        hf.parts_mut().disturbed[k] = 255;
        let spiked = hf.grid().volume();
        let w = smooth(&mut hf, GridRect::new(20, 20, 21, 21), DT);
        assert_eq!(w, GridRect::new(16, 16, 25, 25));
        assert!(hf.grid().height(20, 20) < 1.1 && hf.grid().height(21, 20) > 1.0);
        assert!(((hf.grid().volume() - spiked) / spiked).abs() < 1e-7);
        for (i, j) in hf.grid().full_rect().iter() {
            if !w.contains(i, j) {
                assert_eq!(hf.grid().height(i, j), 1.0);
            }
        }
        assert!(spiked > before);
    }

    #[test]
    fn repeated_smoothing_stays_near_the_rim_and_fades_its_level() {
        // A stance smooths the same window every step. The filter must not
        // spread the rim to the window's border (a rectangular plateau) however
        // many calls run, and the trodden level must fall off with distance.
        // At the reference spacing and rate: 3 full passes (sand) per call.
        let spec = GridSpec {
            origin: Vec2::ZERO,
            cell: REFERENCE_CELL_M,
            nx: 81,
            nz: 81,
        };
        let mut hf = field(flat(spec, 1.0).unwrap());
        let rim = GridRect::new(38, 38, 43, 43);
        for (i, j) in rim.iter() {
            hf.grid_mut().set_height(i, j, 1.05);
            let k = hf.grid().index(i, j);
            hf.parts_mut().disturbed[k] = DISTURBED_RIM;
        }
        let window = rim.expand(12, 81, 81);
        for _ in 0..300 {
            smooth(&mut hf, window, DT);
        }
        let reach = (SMOOTHING_MIN_LEVEL.leading_zeros() as usize) + 1;
        let near = rim.expand(reach, 81, 81);
        let level = |i, j| hf.disturbed()[hf.grid().index(i, j)];
        for (i, j) in hf.grid().full_rect().iter() {
            if !near.contains(i, j) {
                assert_eq!(hf.grid().height(i, j), 1.0, "sample ({i}, {j}) moved");
                assert_eq!(level(i, j), 0);
            }
        }
        // Along a row leaving the rim the level halves sample by sample.
        let row: Vec<u8> = (43..43 + reach).map(|i| level(i, 40)).collect();
        assert!(row.windows(2).all(|w| w[1] <= w[0] / 2 + 1), "{row:?}");
        assert!(row[0] > 0 && row[0] < DISTURBED_RIM);
        // The rim's material tapers outward instead of ending in a step.
        let heights: Vec<f32> = (40..43 + reach).map(|i| hf.grid().height(i, 40)).collect();
        assert!(heights.windows(2).all(|w| w[1] <= w[0]), "{heights:?}");
    }

    /// A flat snow field `cells` samples square over 1 m, all trodden, with a
    /// 1 cm bump of 3 x 3 samples in the middle.
    fn bump(cells: usize) -> Heightfield {
        let grid = flat(GridSpec::square(1.0, cells), 1.0).unwrap();
        let mut hf =
            Heightfield::from_grid(grid, MaterialTable::with_presets(), MaterialId(3)).unwrap();
        hf.parts_mut().disturbed.fill(DISTURBED_RIM);
        let c = cells / 2;
        for (i, j) in GridRect::new(c - 1, c - 1, c + 2, c + 2).iter() {
            hf.grid_mut().set_height(i, j, 1.01);
        }
        hf
    }

    /// Second moment (m²) of the height above 1 m about the grid's centre.
    fn spread(hf: &Heightfield) -> f64 {
        let g = hf.grid();
        let (mut m, mut m2) = (0.0f64, 0.0f64);
        for (i, j) in g.full_rect().iter() {
            let p = g.sample_position(i, j);
            let h = f64::from(p.y - 1.0);
            let r2 = f64::from((p.x - 0.5).powi(2) + (p.z - 0.5).powi(2));
            m += h;
            m2 += h * r2;
        }
        m2 / m
    }

    #[test]
    fn the_variance_added_is_in_metres_and_seconds() {
        // Per axis, V * dt with V = s_t * 0.4 * REFERENCE_CELL_M² * 60, so the
        // second moment about the centre grows by 2 V dt at any spacing and dt.
        let expected = |dt: f32| 2.0 * f64::from(smoothing_variance_rate(4.0) * dt);
        for (cells, dt) in [(51, DT), (101, DT), (101, 1.0 / 20.0), (201, 1.0 / 120.0)] {
            let mut hf = bump(cells);
            let before = spread(&hf);
            // The whole grid: the window bounds the reach, not the variance.
            let window = hf.grid().full_rect();
            smooth(&mut hf, window, dt);
            let added = spread(&hf) - before;
            let want = expected(dt);
            assert!(
                ((added - want) / want).abs() < 1e-3,
                "{cells} samples, dt {dt}: {added:e} m² vs {want:e}"
            );
            assert_eq!(hf.changes().smoothing_capped, 0);
        }
        // At the reference spacing and rate, s_t is the number of full passes.
        let passes = smoothing_pass_equivalent(3.0, REFERENCE_CELL_M, DT);
        assert!((passes - 3.0).abs() < 1e-5);
    }

    #[test]
    fn smoothing_is_capped_and_the_cut_is_counted() {
        let mut hf = bump(101);
        let c = 50;
        // 4 * (0.0195 / 0.01)² * 60 * 20 s = 18 000 passes: capped.
        smooth(&mut hf, GridRect::new(c, c, c + 1, c + 1), 20.0);
        assert_eq!(hf.changes().smoothing_capped, 1);
        assert!(hf.grid().height(c, c) < 1.01);
    }

    #[test]
    fn smoothing_never_takes_a_sample_below_its_floor() {
        // A trodden sand step 10 cm high next to ground 20 cm lower: diffusion
        // would pour the upper side far down, but it keeps its floor (5 cm
        // under its initial height).
        let mut hf = field(flat(GridSpec::square(1.0, 41), 1.0).unwrap());
        for (i, j) in GridRect::new(21, 0, 41, 41).iter() {
            hf.grid_mut().set_height(i, j, 0.8);
        }
        hf.parts_mut().disturbed.fill(DISTURBED_RIM);
        let before = hf.grid().clone();
        for _ in 0..200 {
            smooth(&mut hf, GridRect::new(15, 15, 26, 26), DT);
        }
        // The lower side starts below its own floor: it only gains.
        for k in 0..41 * 41 {
            let (h, was) = (hf.grid().heights()[k], before.heights()[k]);
            assert!(h >= hf.firm_floor(k).min(was) - 1e-6, "sample {k}: {h}");
        }
        assert!(hf.grid().height(20, 20) < 1.0 && hf.grid().height(21, 20) > 0.8);
        let before = before.volume();
        assert!(((hf.grid().volume() - before) / before).abs() < 1e-6);
    }

    #[test]
    fn a_released_print_is_smoothed_for_one_reference_step_at_any_rate() {
        let mut hf = field(flat(GridSpec::square(1.0, 41), 1.0).unwrap());
        let print = GridRect::new(10, 10, 20, 20);
        assert_eq!(smoothing_duration(&hf, print, 1.0 / 120.0), 1.0 / 120.0);
        hf.parts_mut().changes.released.add(print);
        for dt in [1.0 / 30.0, 1.0 / 120.0] {
            assert_eq!(smoothing_duration(&hf, print, dt), 1.0 / REFERENCE_RATE_HZ);
            // A stance window reaching past the released print keeps its dt.
            let stance = GridRect::new(15, 15, 30, 30);
            assert_eq!(smoothing_duration(&hf, stance, dt), dt);
        }
    }
}
