//! Per-sample light visibility of a height grid: sky-view factor (horizon
//! ambient occlusion) and soft sun shadows, recomputed only in dirty windows.

use glam::Vec3;
use rayon::prelude::*;

use super::window_spans::WindowSpans;
use crate::geom::{GridRect, HeightGrid};

/// Horizon distances (in samples) probed by the sky-view factor, roughly geometric.
const SKY_STEPS: [usize; 10] = [1, 2, 3, 4, 6, 8, 11, 15, 20, 27];
/// The eight probe directions of the sky-view factor.
const SKY_DIRS: [(isize, isize); 8] = [
    (1, 0),
    (1, 1),
    (0, 1),
    (-1, 1),
    (-1, 0),
    (-1, -1),
    (0, -1),
    (1, -1),
];
/// Samples of travel away from the sun per strip re-lit after a change.
const SHADOW_STRIP: usize = 4;
/// Half-width of the shadow penumbra, as the tangent of an angle (about 3 degrees).
const PENUMBRA: f32 = 0.05;

/// Sky and sun visibility of every sample.
#[derive(Debug, Clone, Default)]
pub(crate) struct TerrainLight {
    /// Sky-view factor per sample, `1 - mean(sin(horizon elevation))`.
    pub sky_view: Vec<f32>,
    /// Sun visibility per sample, 0 (shadow) to 1 (lit).
    pub sun_visible: Vec<f32>,
    /// Highest height seen so far (shadow rays stop above it).
    pub max_height: f32,
    /// Lowest height seen so far (bounds how far a shadow can fall).
    pub min_height: f32,
}

/// How far the light probes reach, in samples.
#[derive(Debug, Clone, Copy)]
pub(crate) struct LightReach {
    /// Sky-view probe radius.
    pub sky: usize,
    /// Shadow ray length.
    pub shadow: usize,
}

impl TerrainLight {
    /// Light for a grid of `n` samples, all lit, to be filled by [`TerrainLight::recompute`].
    pub fn new(grid: &HeightGrid) -> TerrainLight {
        let n = grid.nx() * grid.nz();
        let (min_height, max_height) = grid.min_max_in(&grid.full_rect());
        TerrainLight {
            sky_view: vec![1.0; n],
            sun_visible: vec![1.0; n],
            max_height,
            min_height,
        }
    }

    /// Widens the known height range by the (new) heights of `rect`. The range
    /// only grows, so it stays conservative for heights that have since changed.
    pub fn note_heights(&mut self, grid: &HeightGrid, rect: &GridRect) {
        if rect.is_empty() {
            return;
        }
        let (lo, hi) = grid.min_max_in(rect);
        self.min_height = self.min_height.min(lo);
        self.max_height = self.max_height.max(hi);
    }

    /// Re-lights what changes of heights in `rects` can reach: both terms
    /// within the sky radius of each, every sample once however many of
    /// those windows cover it; then, away from the sun, the sun visibility
    /// strip by strip ([`SHADOW_STRIP`] samples of travel each) until a strip
    /// outside that radius keeps every value, or the longest shadow is
    /// reached. Returns the windows re-lit.
    pub fn relight(
        &mut self,
        grid: &HeightGrid,
        rects: &[GridRect],
        sun_dir: Vec3,
        reach: LightReach,
    ) -> Vec<GridRect> {
        let (nx, nz) = (grid.nx(), grid.nz());
        let near: Vec<GridRect> = rects
            .iter()
            .map(|r| r.expand(reach.sky + 1, nx, nz))
            .collect();
        self.recompute(grid, &near, sun_dir, reach);
        let mut windows = near.clone();
        for (rect, near) in rects.iter().zip(&near) {
            if near.area() < nx * nz {
                self.relight_shadow_strips(grid, rect, near, sun_dir, reach, &mut windows);
            }
        }
        windows
    }

    /// Re-lights the sun visibility away from the sun of a change in `rect`
    /// (whose `near` window is already re-lit), pushing each strip re-lit
    /// onto `windows`.
    fn relight_shadow_strips(
        &mut self,
        grid: &HeightGrid,
        rect: &GridRect,
        near: &GridRect,
        sun_dir: Vec3,
        reach: LightReach,
        windows: &mut Vec<GridRect>,
    ) {
        let (nx, nz) = (grid.nx(), grid.nz());
        let away = Vec3::new(-sun_dir.x, 0.0, -sun_dir.z).normalize_or_zero();
        if sun_dir.y <= 0.0 || away == Vec3::ZERO {
            return;
        }
        let shifted = |d: usize| {
            let (di, dj) = (
                (away.x * d as f32).round() as isize,
                (away.z * d as f32).round() as isize,
            );
            let at =
                |v: usize, by: isize, n: usize| (v as isize + by).clamp(0, n as isize) as usize;
            GridRect::new(
                at(rect.i0, di, nx),
                at(rect.j0, dj, nz),
                at(rect.i1, di, nx),
                at(rect.j1, dj, nz),
            )
        };
        let mut travelled = 0;
        while travelled < reach.shadow {
            let next = (travelled + SHADOW_STRIP).min(reach.shadow);
            let strip = shifted(travelled).union(&shifted(next)).expand(1, nx, nz);
            if strip.is_empty() {
                break;
            }
            let changed = self.recompute_sun(grid, &strip, near, sun_dir, reach);
            windows.push(strip);
            if changed == 0 && travelled > 0 {
                break;
            }
            travelled = next;
        }
    }

    /// Recomputes the sun visibility of the samples of `rect`; returns how
    /// many outside `skip` changed.
    fn recompute_sun(
        &mut self,
        grid: &HeightGrid,
        rect: &GridRect,
        skip: &GridRect,
        sun_dir: Vec3,
        reach: LightReach,
    ) -> usize {
        let nx = grid.nx();
        let max_height = self.max_height;
        self.sun_visible
            .par_chunks_mut(nx)
            .enumerate()
            .filter(|(j, _)| *j >= rect.j0 && *j < rect.j1)
            .map(|(j, row)| {
                let mut changed = 0;
                for (i, old) in row.iter_mut().enumerate().take(rect.i1).skip(rect.i0) {
                    let new = sun_visibility(grid, i, j, sun_dir, max_height, reach.shadow);
                    changed += usize::from(new != *old && !skip.contains(i, j));
                    *old = new;
                }
                changed
            })
            .sum()
    }

    /// Recomputes both terms for the samples `windows` cover, each sample
    /// once (a sample's light depends on the heights alone, so the result
    /// is the same whatever the windows' order or overlap).
    pub fn recompute(
        &mut self,
        grid: &HeightGrid,
        windows: &[GridRect],
        sun_dir: Vec3,
        reach: LightReach,
    ) {
        let spans = WindowSpans::new(windows.iter().copied());
        for window in windows {
            self.note_heights(grid, window);
        }
        let nx = grid.nx();
        let max_height = self.max_height;
        spans.par_fill(&mut self.sky_view, nx, |i, j| {
            sky_view(grid, i, j, reach.sky)
        });
        spans.par_fill(&mut self.sun_visible, nx, |i, j| {
            sun_visibility(grid, i, j, sun_dir, max_height, reach.shadow)
        });
    }
}

/// Sky-view factor of sample `(i, j)` over horizons within `radius` samples.
pub(crate) fn sky_view(grid: &HeightGrid, i: usize, j: usize, radius: usize) -> f32 {
    let h0 = grid.height(i, j);
    let cell = grid.cell_size();
    let (nx, nz) = (grid.nx() as isize, grid.nz() as isize);
    let mut sum = 0.0;
    for (di, dj) in SKY_DIRS {
        let unit = cell * ((di * di + dj * dj) as f32).sqrt();
        let mut max_tan = 0.0f32;
        for &k in SKY_STEPS.iter().take_while(|&&k| k <= radius) {
            let (si, sj) = (i as isize + di * k as isize, j as isize + dj * k as isize);
            if si < 0 || sj < 0 || si >= nx || sj >= nz {
                break;
            }
            let t = (grid.height(si as usize, sj as usize) - h0) / (unit * k as f32);
            max_tan = max_tan.max(t);
        }
        sum += max_tan / (1.0 + max_tan * max_tan).sqrt();
    }
    1.0 - sum / SKY_DIRS.len() as f32
}

/// Soft sun visibility of sample `(i, j)`: marches towards the sun over at most
/// `max_steps` samples, stopping once nothing below `max_height` can dim it.
pub(crate) fn sun_visibility(
    grid: &HeightGrid,
    i: usize,
    j: usize,
    sun_dir: Vec3,
    max_height: f32,
    max_steps: usize,
) -> f32 {
    let horizontal = (sun_dir.x * sun_dir.x + sun_dir.z * sun_dir.z).sqrt();
    if sun_dir.y <= 0.0 {
        return 0.0;
    }
    if horizontal < 1e-6 {
        return 1.0;
    }
    let (dx, dz) = (sun_dir.x / horizontal, sun_dir.z / horizontal);
    let rise = sun_dir.y / horizontal * grid.cell_size();
    let h0 = grid.height(i, j);
    let (mx, mz) = ((grid.nx() - 1) as f32, (grid.nz() - 1) as f32);
    let mut min_margin = f32::INFINITY;
    for k in 1..=max_steps {
        let ray = h0 + rise * k as f32;
        // Past this point every margin is at least the penumbra: the result is
        // settled, whatever (conservative) `max_height` was given.
        if ray - max_height >= PENUMBRA * k as f32 * grid.cell_size() {
            break;
        }
        let (u, v) = (i as f32 + dx * k as f32, j as f32 + dz * k as f32);
        if !(u >= 0.0 && v >= 0.0 && u <= mx && v <= mz) {
            break;
        }
        let ground = bilinear(grid, u, v);
        min_margin = min_margin.min((ray - ground) / (k as f32 * grid.cell_size()));
    }
    (0.5 + 0.5 * min_margin / PENUMBRA).clamp(0.0, 1.0)
}

/// Bilinear height at grid coordinates `(u, v)` inside the grid.
#[inline]
fn bilinear(grid: &HeightGrid, u: f32, v: f32) -> f32 {
    let i = (u as usize).min(grid.nx() - 2);
    let j = (v as usize).min(grid.nz() - 2);
    let (fx, fz) = (u - i as f32, v - j as f32);
    let a = grid.height(i, j) + (grid.height(i + 1, j) - grid.height(i, j)) * fx;
    let b = grid.height(i, j + 1) + (grid.height(i + 1, j + 1) - grid.height(i, j + 1)) * fx;
    a + (b - a) * fz
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec2;

    fn pit() -> HeightGrid {
        HeightGrid::from_fn(Vec2::ZERO, 0.02, 64, 64, |x, z| {
            let d = ((x - 0.64).powi(2) + (z - 0.64).powi(2)).sqrt();
            if d < 0.08 { -0.04 } else { 0.0 }
        })
        .unwrap()
    }

    #[test]
    fn re_lighting_windows_that_overlap_gives_what_lighting_all_gives() {
        let g = pit();
        let sun = Vec3::new(0.3, 0.5, -1.0).normalize();
        let reach = LightReach {
            sky: 15,
            shadow: 64,
        };
        let mut whole = TerrainLight::new(&g);
        whole.recompute(&g, &[g.full_rect()], sun, reach);
        let mut parts = TerrainLight::new(&g);
        let windows = [
            GridRect::new(0, 0, 40, 50),
            GridRect::new(20, 10, 64, 64),
            GridRect::new(0, 40, 30, 64),
        ];
        parts.recompute(&g, &windows, sun, reach);
        assert_eq!(parts.sky_view, whole.sky_view);
        assert_eq!(parts.sun_visible, whole.sun_visible);
    }

    #[test]
    fn a_pit_sees_less_sky_than_flat_ground() {
        let g = pit();
        assert!((sky_view(&g, 5, 5, 15) - 1.0).abs() < 1e-6);
        assert!(sky_view(&g, 32, 32, 15) < 0.8);
    }

    #[test]
    fn the_sunward_wall_shades_the_pit_floor() {
        let g = pit();
        let sun = Vec3::new(0.0, 0.45, -1.0).normalize();
        assert_eq!(sun_visibility(&g, 5, 5, sun, 0.0, 64), 1.0);
        // Near the wall on the sun side (smaller z) the floor is in shadow.
        assert!(sun_visibility(&g, 32, 30, sun, 0.0, 64) < 0.2);
        // Far from that wall it is lit again.
        assert!(sun_visibility(&g, 32, 35, sun, 0.0, 64) > 0.8);
    }
}
