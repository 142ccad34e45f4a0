//! Smoothing: the paper's Gaussian filter of strength s_t, as conservative
//! diffusion restricted to a dirty window.

use engine::geom::GridRect;

use super::heightfield::{DISTURBED_RIM, Heightfield, StageBuffers};
use super::patch::{Patch, edge_moves};

/// Diffusion rate per pass (stable below 0.25; each pass adds a Gaussian
/// variance of `2 * DIFFUSION_RATE` = 0.4 cell² per axis).
pub const DIFFUSION_RATE: f32 = 0.2;

/// Smallest trodden level (`Heightfield::disturbed`) through which smoothing
/// conducts. An edge runs its passes scaled by the larger trodden level of its
/// two samples over [`DISTURBED_RIM`] (full on prints and rims), and a sample
/// that smoothing moves takes half its neighbours' largest level. So the
/// filter fades over the few samples around a rim (levels 64, 32, ... 2)
/// however many steps a stance lasts: the rim keeps the print's round shape
/// and tapers smoothly instead of spreading to the window's rectangular
/// border, and the darkening of disturbed ground fades with it.
pub const SMOOTHING_MIN_LEVEL: u8 = 2;

/// How far smoothing reaches beyond the window it is given, in samples:
/// one sample per pass, `ceil(max s_t)` passes.
pub fn smoothing_radius(hf: &Heightfield) -> usize {
    hf.table().max_smoothness().ceil() as usize
}

/// Smooths the heights around `window`; returns the rectangle it worked in
/// (`window` grown by [`smoothing_radius`], clipped), which may have changed.
///
/// Each pass moves height across every 4-neighbour edge inside that rectangle
/// in flux form: `flux = DIFFUSION_RATE * (h_b - h_a)`, added to one sample and
/// taken from the other (the same float on both sides), so the volume is
/// conserved (to float rounding); no flux crosses the rectangle's border. An
/// edge carries flux only if one of its samples has a trodden level of at least
/// [`SMOOTHING_MIN_LEVEL`], so natural terrain is never flattened, and it runs
/// fewer passes the lower that level (see [`SMOOTHING_MIN_LEVEL`]), so the
/// filter stays on and around the deformed ground. It does not conduct either
/// if one of its samples is held by a sole this step (the foot occupies the
/// print; its walls are smoothed once it lifts). The edge between materials
/// of smoothness s_a and s_b runs `(s_a + s_b) / 2` passes (the last one
/// fractional).
///
/// Only the rectangle of samples that actually changed is marked dirty.
pub fn smooth(hf: &mut Heightfield, window: GridRect) -> GridRect {
    let full = hf.grid().full_rect();
    let passes = smoothing_radius(hf);
    let w = window
        .intersect(&full)
        .expand(passes, full.width(), full.height());
    if w.is_empty() || passes == 0 {
        return w;
    }
    let mut buffers = hf.take_buffers();
    let changed = {
        let mut parts = hf.parts_mut();
        let StageBuffers { patch, smooth, .. } = &mut buffers;
        patch.load(&parts, w);
        smooth.smoothness.clear();
        smooth
            .smoothness
            .extend(parts.table.materials().iter().map(|m| m.smoothness));
        let changed = smooth.run(patch, passes);
        if !changed.is_empty() {
            patch.store(&mut parts, changed);
        }
        changed
    };
    hf.return_buffers(buffers);
    if !changed.is_empty() {
        hf.mark_dirty(changed);
    }
    w
}

/// Smoothing's buffers, reused from call to call.
#[derive(Default)]
pub(crate) struct SmoothBuffers {
    /// Smoothness per material id.
    smoothness: Vec<f32>,
    /// Smoothness per local sample.
    sample: Vec<f32>,
    /// Passes of the edge between local samples `l` and `l + 1` (0: none).
    edge_x: Vec<f32>,
    /// Passes of the edge between local samples `l` and `l + stride`.
    edge_z: Vec<f32>,
    /// Heights after the running pass.
    next: Vec<f32>,
    /// Per sample of the inner rows: 1 once a pass changed it.
    changed: Vec<u8>,
    /// The patch's trodden levels before this call marked the changed samples.
    levels: Vec<u8>,
}

impl SmoothBuffers {
    /// Runs `passes` diffusion passes on `patch`; gives each sample they
    /// changed half the largest trodden level of its 4 neighbours (if that is
    /// more than its own) and returns their bounding rectangle (grid samples).
    fn run(&mut self, patch: &mut Patch, passes: usize) -> GridRect {
        if !self.conducting_edges(patch) {
            return GridRect::EMPTY;
        }
        let (s, len) = (patch.stride, patch.heights.len());
        // The inner rows (window rows with their frame columns): `s..len - s`.
        let n = len - 2 * s;
        self.next.clear();
        self.next.extend_from_slice(&patch.heights);
        self.changed.clear();
        self.changed.resize(n, 0);
        for pass in 0..passes {
            let pass = pass as f32;
            // `max`/`min` rather than `clamp`: the edges are finite, and this
            // form lets the loop below vectorise.
            #[allow(clippy::manual_clamp)]
            let rate = |edge: f32| DIFFUSION_RATE * (edge - pass).max(0.0).min(1.0);
            let h = &patch.heights;
            let (up, down) = (&h[..n], &h[2 * s..2 * s + n]);
            let (left, centre, right) = (&h[s - 1..s - 1 + n], &h[s..s + n], &h[s + 1..s + 1 + n]);
            let (ex_left, ex) = (&self.edge_x[s - 1..s - 1 + n], &self.edge_x[s..s + n]);
            let (ez_up, ez) = (&self.edge_z[..n], &self.edge_z[s..s + n]);
            let out = &mut self.next[s..s + n];
            let changed = &mut self.changed[..n];
            for k in 0..n {
                let hc = centre[k];
                // Each edge's flux is the same float for both of its samples.
                let flux_right = rate(ex[k]) * (right[k] - hc);
                let flux_left = rate(ex_left[k]) * (hc - left[k]);
                let flux_down = rate(ez[k]) * (down[k] - hc);
                let flux_up = rate(ez_up[k]) * (hc - up[k]);
                let v = hc + flux_right - flux_left + flux_down - flux_up;
                out[k] = v;
                changed[k] |= u8::from(v != hc);
            }
            std::mem::swap(&mut patch.heights, &mut self.next);
        }
        let changed = &self.changed;
        let rect = patch.bounds_of(|l| changed[l - s] != 0);
        self.levels.clear();
        self.levels.extend_from_slice(&patch.disturbed);
        let t = &self.levels;
        let (up, down) = (&t[..n], &t[2 * s..2 * s + n]);
        let (left, right) = (&t[s - 1..s - 1 + n], &t[s + 1..s + 1 + n]);
        let neighbours = up.iter().zip(down).zip(left.iter().zip(right));
        for ((d, &c), ((&u, &dn), (&l, &r))) in patch.disturbed[s..len - s]
            .iter_mut()
            .zip(changed)
            .zip(neighbours)
        {
            if c != 0 {
                *d = (*d).max(u.max(dn).max(l.max(r)) / 2);
            }
        }
        rect
    }

    /// Fills the per-edge pass counts of `patch`; false when no edge conducts.
    fn conducting_edges(&mut self, patch: &Patch) -> bool {
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
        self.edge_x.iter().chain(&self.edge_z).any(|&e| e > 0.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::terrain::generate::{GridSpec, flat, slope};
    use crate::terrain::{MaterialId, MaterialTable};
    use glam::Vec2;

    fn field(grid: engine::geom::HeightGrid) -> Heightfield {
        Heightfield::from_grid(grid, MaterialTable::with_presets(), MaterialId(0)).unwrap()
    }

    #[test]
    fn natural_terrain_is_left_alone() {
        let grid = slope(GridSpec::square(1.0, 41), 1.0, 30.0, Vec2::X).unwrap();
        let mut hf = field(grid.clone());
        smooth(&mut hf, GridRect::new(10, 10, 20, 20));
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
        let w = smooth(&mut hf, GridRect::new(20, 20, 21, 21));
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
        let mut hf = field(flat(GridSpec::square(1.0, 81), 1.0).unwrap());
        let rim = GridRect::new(38, 38, 43, 43);
        for (i, j) in rim.iter() {
            hf.grid_mut().set_height(i, j, 1.05);
            let k = hf.grid().index(i, j);
            hf.parts_mut().disturbed[k] = DISTURBED_RIM;
        }
        let window = rim.expand(12, 81, 81);
        for _ in 0..300 {
            smooth(&mut hf, window);
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
}
