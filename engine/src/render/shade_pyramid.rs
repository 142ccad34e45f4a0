//! The terrain's display colours at every level of detail, as one pyramid
//! over the whole grid. Level 0 holds each sample's colour; a vertex of a
//! coarser level is the average, in linear light and weighted `[1 2 1]` by
//! `[1 2 1]`, of the finer level's vertices around it, across patch borders.
//! So a vertex has one colour whichever patch draws it, and a far patch shows
//! what its cells hold on average: a trail of prints reads as a trail, not as
//! the few prints that happen to lie under its coarse vertices. Only the
//! windows whose light or colour changed are recomputed, level by level.

use glam::Vec3;

use super::shading::encode_display;
use super::window_spans::WindowSpans;
use crate::geom::GridRect;

/// A vertex's display colours with the sun and with a shadow caster hiding it.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct Shade {
    /// Display colour in the sun (and under the terrain's own shadows).
    pub lit: Vec3,
    /// Display colour with the sun hidden.
    pub shaded: Vec3,
}

/// One level: vertices every `step` samples along each axis, and on the
/// grid's last column and row.
#[derive(Debug, Clone)]
pub(crate) struct ShadeLevel {
    /// Samples between vertices.
    step: usize,
    /// Samples along X and Z of the grid.
    samples: (usize, usize),
    /// Vertices along X.
    cols: usize,
    /// Vertices along Z.
    rows: usize,
    /// Colours per vertex, row-major.
    shades: Vec<Shade>,
}

impl ShadeLevel {
    fn new(nx: usize, nz: usize, step: usize) -> ShadeLevel {
        let (cols, rows) = ((nx - 1).div_ceil(step) + 1, (nz - 1).div_ceil(step) + 1);
        ShadeLevel {
            step,
            samples: (nx, nz),
            cols,
            rows,
            shades: vec![Shade::default(); cols * rows],
        }
    }

    /// The colours of the vertex on sample `(i, j)` (which must be one of
    /// the level's: a multiple of its step, or the grid's last).
    #[inline]
    pub fn at_sample(&self, i: usize, j: usize) -> Shade {
        self.shades[j.div_ceil(self.step) * self.cols + i.div_ceil(self.step)]
    }

    /// The colours at sample `(i, j)` interpolated between the level's
    /// vertices around it (linearly along a line of vertices, as the level's
    /// triangles show it there).
    pub fn between(&self, i: usize, j: usize) -> Shade {
        let (c, tc) = self.cell_of(i, self.samples.0, self.cols);
        let (r, tr) = self.cell_of(j, self.samples.1, self.rows);
        let at = |c: usize, r: usize| self.shades[r * self.cols + c];
        let mix = |a: Shade, b: Shade, t: f32| Shade {
            lit: a.lit.lerp(b.lit, t),
            shaded: a.shaded.lerp(b.shaded, t),
        };
        let near = mix(at(c, r), at(c + 1, r), tc);
        let far = mix(at(c, r + 1), at(c + 1, r + 1), tc);
        mix(near, far, tr)
    }

    /// The first of the two vertices around sample `i` along an axis of `n`
    /// samples and `count` vertices, and how far `i` lies towards the second.
    fn cell_of(&self, i: usize, n: usize, count: usize) -> (usize, f32) {
        let c = (i / self.step).min(count - 2);
        let (x0, x1) = (c * self.step, ((c + 1) * self.step).min(n - 1));
        (c, (i - x0) as f32 / (x1 - x0) as f32)
    }

    /// Sets the vertices `spans` cover to `shade(column, row)`.
    fn fill(&mut self, spans: &WindowSpans, shade: impl Fn(usize, usize) -> Shade + Sync) {
        spans.par_fill(&mut self.shades, self.cols, shade);
    }

    /// The colours of vertex `(c, r)` of the next coarser level: this
    /// level's vertex under it and its eight neighbours (those inside the
    /// grid), weighted `[1 2 1]` by `[1 2 1]` and averaged in linear light.
    fn filtered(&self, c: usize, r: usize) -> Shade {
        let (cc, cr) = ((2 * c).min(self.cols - 1), (2 * r).min(self.rows - 1));
        let weight = |k: usize, centre: usize| if k == centre { 2.0 } else { 1.0 };
        let (mut lit, mut shaded, mut total) = (Vec3::ZERO, Vec3::ZERO, 0.0);
        for k in cr.saturating_sub(1)..=(cr + 1).min(self.rows - 1) {
            for i in cc.saturating_sub(1)..=(cc + 1).min(self.cols - 1) {
                let w = weight(k, cr) * weight(i, cc);
                let s = self.shades[k * self.cols + i];
                // Display values are the square roots of linear ones.
                lit += w * s.lit * s.lit;
                shaded += w * s.shaded * s.shaded;
                total += w;
            }
        }
        Shade {
            lit: encode_display(lit / total),
            shaded: encode_display(shaded / total),
        }
    }
}

/// The terrain's vertex colours at each level of detail.
#[derive(Debug, Clone)]
pub(crate) struct ShadePyramid {
    /// Level `l` has vertices every `2^l` samples.
    levels: Vec<ShadeLevel>,
}

impl ShadePyramid {
    /// A pyramid of `count` levels over a grid of `nx` x `nz` samples, all
    /// black until [`ShadePyramid::update`].
    pub fn new(nx: usize, nz: usize, count: usize) -> ShadePyramid {
        ShadePyramid {
            levels: (0..count)
                .map(|l| ShadeLevel::new(nx, nz, 1 << l))
                .collect(),
        }
    }

    /// Level `l`.
    #[inline]
    pub fn level(&self, l: usize) -> &ShadeLevel {
        &self.levels[l]
    }

    /// Recomputes the samples `windows` cover with `shade(i, j)`, then, level
    /// by level, the coarser vertices that read them. Each vertex is a
    /// function of the samples alone, so the result does not depend on the
    /// windows' order or overlap, nor on the thread count.
    pub fn update(&mut self, windows: &[GridRect], shade: impl Fn(usize, usize) -> Shade + Sync) {
        let Some((first, coarser)) = self.levels.split_first_mut() else {
            return;
        };
        let mut windows = windows.to_vec();
        first.fill(&WindowSpans::new(windows.iter().copied()), shade);
        let mut finer: &ShadeLevel = first;
        for level in coarser {
            for window in &mut windows {
                *window = coarser_window(window, level);
            }
            let spans = WindowSpans::new(windows.iter().copied());
            level.fill(&spans, |c, r| finer.filtered(c, r));
            finer = level;
        }
    }
}

/// The vertices of level `coarser` whose colours read the vertices of
/// `window` of the level below it (a few more at its edges).
fn coarser_window(window: &GridRect, coarser: &ShadeLevel) -> GridRect {
    let low = |v: usize| v.saturating_sub(1) / 2;
    let high = |v: usize, count: usize| ((v + 3) / 2).min(count);
    GridRect::new(
        low(window.i0),
        low(window.j0),
        high(window.i1, coarser.cols),
        high(window.j1, coarser.rows),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A field with a dark print on every sample where `dark` says so.
    fn shades(dark: impl Fn(usize, usize) -> bool + Sync) -> impl Fn(usize, usize) -> Shade + Sync {
        move |i, j| {
            let v = if dark(i, j) { 0.2 } else { 0.8 };
            Shade {
                lit: Vec3::splat(v),
                shaded: Vec3::splat(0.5 * v),
            }
        }
    }

    /// A pyramid of `count` levels over `nx` x `nz` samples, built whole.
    fn built(
        nx: usize,
        nz: usize,
        count: usize,
        shade: impl Fn(usize, usize) -> Shade + Sync,
    ) -> ShadePyramid {
        let mut pyramid = ShadePyramid::new(nx, nz, count);
        pyramid.update(&[GridRect::new(0, 0, nx, nz)], shade);
        pyramid
    }

    #[test]
    fn a_lone_print_under_a_coarse_vertex_does_not_colour_it() {
        let pyramid = built(37, 33, 5, shades(|i, j| (i, j) == (16, 16)));
        // Level 0 holds the print itself; the vertex over it at level 4
        // (every 16 samples) is nearly the ground around it.
        assert_eq!(pyramid.level(0).at_sample(16, 16).lit, Vec3::splat(0.2));
        let coarse = pyramid.level(4).at_sample(16, 16).lit.x;
        assert!(coarse > 0.79 && coarse < 0.8, "{coarse}");
        // The last column (36, not a multiple of 16) has its own vertices.
        let last = pyramid.level(4).at_sample(36, 32).lit;
        assert!(
            (last - Vec3::splat(0.8)).abs().max_element() < 1e-6,
            "{last}"
        );
    }

    #[test]
    fn a_trail_stays_a_trail_at_every_level() {
        // A dark trail two samples wide along row 32.
        let pyramid = built(65, 65, 5, shades(|_, j| j == 32 || j == 33));
        for l in 1..5 {
            let level = pyramid.level(l);
            let on = level.at_sample(32, 32).lit.x;
            let off = level.at_sample(32, 64).lit.x;
            assert!(on < off - 0.02, "level {l}: trail {on}, ground {off}");
            // Along the trail, every vertex is the same.
            assert_eq!(
                level.at_sample(16, 32),
                level.at_sample(48, 32),
                "level {l}"
            );
        }
    }

    #[test]
    fn updating_windows_gives_what_building_all_gives() {
        let (nx, nz) = (70, 41);
        let before = shades(|i, j| (i * 7 + j * 3) % 11 == 0);
        let after = shades(|i, j| (i * 7 + j * 3) % 11 == 0 || (20..30).contains(&i) && j < 9);
        let mut updated = built(nx, nz, 6, &before);
        // The change lies in columns 20..30, rows 0..9; report it in two
        // overlapping windows.
        updated.update(
            &[
                GridRect::new(20, 0, 27, 9),
                GridRect::new(25, 2, 30, 9),
                GridRect::new(22, 0, 30, 3),
            ],
            &after,
        );
        let fresh = built(nx, nz, 6, &after);
        for (a, b) in updated.levels.iter().zip(&fresh.levels) {
            assert_eq!(a.shades, b.shades, "level of step {}", a.step);
        }
    }

    #[test]
    fn between_vertices_the_colour_is_interpolated() {
        let pyramid = built(17, 17, 4, shades(|i, _| i >= 8));
        let level = pyramid.level(3);
        let (a, b) = (level.at_sample(8, 8).lit, level.at_sample(16, 8).lit);
        assert_eq!(level.between(8, 8).lit, a);
        let mid = level.between(12, 8).lit;
        assert!((mid - 0.5 * (a + b)).abs().max_element() < 1e-6);
    }
}
