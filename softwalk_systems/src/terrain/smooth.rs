//! Smoothing: the paper's Gaussian filter of strength s_t, as conservative
//! diffusion restricted to a dirty window.

use engine::geom::GridRect;

use super::heightfield::{DISTURBED_SLUMPED, Heightfield};
use super::patch::Patch;

/// Diffusion rate per pass (stable below 0.25; each pass adds a Gaussian
/// variance of `2 * DIFFUSION_RATE` = 0.4 cell² per axis).
pub const DIFFUSION_RATE: f32 = 0.2;

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
    let mut parts = hf.parts_mut();
    let mut patch = Patch::load(&parts, w);
    let smoothness = parts.table.per_material(|m| m.smoothness);
    let (ww, wh) = (w.width(), w.height());
    // Smoothness of each edge that may carry flux (0 for none), fixed for the call:
    // x edges join l and l + 1, z edges join l and l + ww.
    let edge = |la: usize, lb: usize| {
        let p = &patch;
        if (p.disturbed[la] == 0 && p.disturbed[lb] == 0) || p.held[la] || p.held[lb] {
            0.0
        } else {
            0.5 * (smoothness[p.material[la] as usize] + smoothness[p.material[lb] as usize])
        }
    };
    let mut edge_x = vec![0.0f32; ww * wh];
    let mut edge_z = vec![0.0f32; ww * wh];
    for r in 0..wh {
        for c in 0..ww {
            let l = r * ww + c;
            if c + 1 < ww {
                edge_x[l] = edge(l, l + 1);
            }
            if r + 1 < wh {
                edge_z[l] = edge(l, l + ww);
            }
        }
    }
    let mut flux_x = vec![0.0f32; ww * wh];
    let mut flux_z = vec![0.0f32; ww * wh];
    let mut touched = vec![false; ww * wh];
    let mut moved = false;
    for pass in 0..passes {
        let pass = pass as f32;
        let h = &patch.heights;
        for l in 0..ww * wh {
            let cx = DIFFUSION_RATE * (edge_x[l] - pass).clamp(0.0, 1.0);
            flux_x[l] = if cx > 0.0 {
                cx * (h[l + 1] - h[l])
            } else {
                0.0
            };
            let cz = DIFFUSION_RATE * (edge_z[l] - pass).clamp(0.0, 1.0);
            flux_z[l] = if cz > 0.0 {
                cz * (h[l + ww] - h[l])
            } else {
                0.0
            };
        }
        let h = &mut patch.heights;
        for l in 0..ww * wh {
            let (fx, fz) = (flux_x[l], flux_z[l]);
            if fx != 0.0 {
                h[l] += fx;
                h[l + 1] -= fx;
                touched[l] = true;
                touched[l + 1] = true;
                moved = true;
            }
            if fz != 0.0 {
                h[l] += fz;
                h[l + ww] -= fz;
                touched[l] = true;
                touched[l + ww] = true;
                moved = true;
            }
        }
    }
    if moved {
        for (d, &t) in patch.disturbed.iter_mut().zip(&touched) {
            if t {
                *d = (*d).max(DISTURBED_SLUMPED);
            }
        }
        patch.store(&mut parts);
        hf.mark_dirty(w);
    }
    w
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
}
