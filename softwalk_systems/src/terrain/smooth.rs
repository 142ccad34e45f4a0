//! Smoothing: the paper's Gaussian filter of strength s_t, as conservative
//! diffusion restricted to a dirty window.

use engine::geom::GridRect;

use super::heightfield::{DISTURBED_SLUMPED, Heightfield, held_mask};

/// Diffusion rate per pass (stable below 0.25; each pass adds a Gaussian
/// variance of `2 * DIFFUSION_RATE` = 0.4 cell² per axis).
pub const DIFFUSION_RATE: f32 = 0.2;

/// How far smoothing reaches beyond the window it is given, in samples:
/// one sample per pass, `ceil(max s_t)` passes.
pub fn smoothing_radius(hf: &Heightfield) -> usize {
    hf.table().max_smoothness().ceil() as usize
}

/// Marks both samples of an edge that carried flux as (at least slightly) disturbed.
#[inline]
fn touch(disturbed: &mut [u8], ka: usize, kb: usize) {
    disturbed[ka] = disturbed[ka].max(DISTURBED_SLUMPED);
    disturbed[kb] = disturbed[kb].max(DISTURBED_SLUMPED);
}

/// Smooths the heights around `window`; returns the rectangle it worked in
/// (`window` grown by [`smoothing_radius`], clipped), which may have changed.
///
/// Each pass moves height across every 4-neighbour edge inside that rectangle
/// in flux form: `flux = DIFFUSION_RATE * (h_b - h_a)`, added to one sample and
/// taken from the other, so the volume is conserved (to float rounding); no
/// flux crosses the rectangle's border. An edge carries flux only if one of
/// its samples is disturbed (pressed or rim), so natural terrain is never
/// flattened (samples that change become slightly disturbed, so settling
/// can relax them), and not if one of its samples is held by a sole this step
/// (the foot occupies the print; its walls are smoothed once it lifts).
/// The edge between materials of smoothness s_a and s_b runs
/// `(s_a + s_b) / 2` passes (the last one fractional).
pub fn smooth(hf: &mut Heightfield, window: GridRect) -> GridRect {
    let full = hf.grid().full_rect();
    let passes = smoothing_radius(hf);
    let w = window
        .intersect(&full)
        .expand(passes, full.width(), full.height());
    if w.is_empty() || passes == 0 {
        return w;
    }
    let parts = hf.parts_mut();
    let smoothness = parts.table.per_material(|m| m.smoothness);
    let (nx, ww, wh) = (parts.nx, w.width(), w.height());
    let held = held_mask(&parts.changes.held, nx, w);
    let mut flux_x = vec![0.0f32; ww * wh];
    let mut flux_z = vec![0.0f32; ww * wh];
    let mut moved = false;
    for pass in 0..passes {
        let pass = pass as f32;
        let heights = &*parts.heights;
        let conductance = |ka: usize, la: usize, kb: usize, lb: usize| {
            if (parts.disturbed[ka] == 0 && parts.disturbed[kb] == 0)
                || held.contains(la)
                || held.contains(lb)
            {
                return 0.0;
            }
            let s = 0.5
                * (smoothness[parts.material[ka] as usize]
                    + smoothness[parts.material[kb] as usize]);
            DIFFUSION_RATE * (s - pass).clamp(0.0, 1.0)
        };
        for j in w.j0..w.j1 {
            let row_k = j * nx;
            let row_l = (j - w.j0) * ww;
            for i in w.i0..w.i1 {
                let (k, l) = (row_k + i, row_l + i - w.i0);
                flux_x[l] = if i + 1 < w.i1 {
                    conductance(k, l, k + 1, l + 1) * (heights[k + 1] - heights[k])
                } else {
                    0.0
                };
                flux_z[l] = if j + 1 < w.j1 {
                    conductance(k, l, k + nx, l + ww) * (heights[k + nx] - heights[k])
                } else {
                    0.0
                };
            }
        }
        for j in w.j0..w.j1 {
            let row_k = j * nx;
            let row_l = (j - w.j0) * ww;
            for i in w.i0..w.i1 {
                let (k, l) = (row_k + i, row_l + i - w.i0);
                let (fx, fz) = (flux_x[l], flux_z[l]);
                if fx != 0.0 {
                    parts.heights[k] += fx;
                    parts.heights[k + 1] -= fx;
                    touch(parts.disturbed, k, k + 1);
                    moved = true;
                }
                if fz != 0.0 {
                    parts.heights[k] += fz;
                    parts.heights[k + nx] -= fz;
                    touch(parts.disturbed, k, k + nx);
                    moved = true;
                }
            }
        }
    }
    if moved {
        hf.mark_dirty(w);
    }
    w
}
