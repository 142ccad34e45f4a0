//! The grass blade rasterizer: a blade's pieces (its lower quad and its tip
//! triangle) are small convex polygons filled as one span per pixel row.
//!
//! A piece is set up once, in the parallel geometry stage: its rows are cut at
//! its vertices into at most three runs, each bounded by one left and one right
//! edge in fixed point, and its attributes (`1/w`, display colour) become planes
//! over the screen. A band then fills each row with two integer edge steps, one
//! colour (stepped in fixed point along the run's centre line: a blade is a few
//! pixels wide) and one depth test per pixel, with `1/w` linear along the row.
//! There is no per-pixel edge function, no division and no float-to-integer
//! conversion per row.
//!
//! Coverage rule: a pixel centre `(x + 0.5, y + 0.5)` is covered when
//! `left(y) <= x + 0.5 < right(y)` and `top <= y + 0.5 < bottom`. An edge's
//! fixed-point line depends only on its two end points (taken top first), so two
//! pieces sharing an edge (a blade's quad and tip) step it identically and split
//! its pixels exactly: no gap, no pixel drawn twice.

use glam::Vec3;

use super::raster::Band;

/// Fractional bits of the fixed-point edge positions.
const FRAC_BITS: u32 = 24;
/// One pixel in edge fixed point.
const ONE: i64 = 1 << FRAC_BITS;
/// Edges steeper than this many pixels per row are clamped to it: they span a
/// millionth of a row, so no row centre can tell the difference, and the
/// products stay far inside `i64` for any screen up to 16384 rows.
const MAX_SLOPE: f64 = (1 << 20) as f32 as f64;

/// Fractional bits of the colour channels stepped along a run.
const COLOR_BITS: u32 = 16;

/// A projected vertex: pixel position (y down, pixel centres at `.5`), `1/w`
/// and display colour.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct SpanVertex {
    /// X in pixels.
    pub x: f32,
    /// Y in pixels, down.
    pub y: f32,
    /// Reciprocal of clip `w` (the depth, larger is nearer).
    pub inv_w: f32,
    /// Display-encoded colour.
    pub color: Vec3,
}

/// An edge as a fixed-point line over pixel rows: its x at the centre of row
/// `y` is `(at_row0 + y * step) / ONE`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
struct EdgeLine {
    at_row0: i64,
    step: i64,
}

impl EdgeLine {
    /// The line through `a` and `b` (not horizontal).
    fn new(a: &SpanVertex, b: &SpanVertex) -> EdgeLine {
        let (top, bottom) = if a.y < b.y { (a, b) } else { (b, a) };
        let (tx, ty) = (f64::from(top.x), f64::from(top.y));
        let slope =
            ((f64::from(bottom.x) - tx) / (f64::from(bottom.y) - ty)).clamp(-MAX_SLOPE, MAX_SLOPE);
        let one = ONE as f64;
        EdgeLine {
            // Truncated (no libm call); a fraction of 2^-24 pixel either way.
            at_row0: ((tx + (0.5 - ty) * slope) * one) as i64,
            step: (slope * one) as i64,
        }
    }

    /// Fixed-point x at the centre of row `y`.
    #[inline]
    fn at(&self, y: i32) -> i64 {
        self.at_row0 + i64::from(y) * self.step
    }
}

/// Rows up to `end` (exclusive) bounded by edges `left` and `right` of the
/// piece (`i16`: screens have at most 16384 rows; keeps a piece under 128
/// bytes, which the compiler copies inline).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
struct RowRun {
    end: i16,
    left: u8,
    right: u8,
}

/// Most runs and edges a piece of at most four vertices has.
const MAX_RUNS: usize = 3;
const MAX_EDGES: usize = 4;

/// A convex polygon of at most four vertices, set up for span filling.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct BladePiece {
    /// First covered row.
    first_row: i32,
    /// Number of used entries in `runs`.
    run_count: u8,
    /// Row runs, top to bottom.
    runs: [RowRun; MAX_RUNS],
    /// The piece's non-horizontal edges.
    edges: [EdgeLine; MAX_EDGES],
    /// `1/w` at the screen origin, and its change per pixel right and down.
    depth: [f32; 3],
    /// Fixed-point colour at the centre of the first row.
    color: [i32; 3],
    /// Its change per row.
    color_step: [i32; 3],
}

/// Triangles with less than this doubled area (pixels²) are degenerate: no
/// attribute plane, dropped.
const MIN_DOUBLE_AREA: f32 = 1e-6;

/// The first pixel (row or column) whose centre is at or after `v`, in pixels.
#[inline]
fn first_centre(v: f32) -> i32 {
    // `v - 0.5` rounded up; `as` saturates, and callers clamp the result.
    let u = v - 0.5;
    let t = u as i32;
    t + i32::from((t as f32) < u)
}

/// Added to a fixed-point edge position so that shifting out the fraction
/// gives the first pixel column whose centre is at or after it.
const COLUMN_BIAS: i64 = ONE / 2 - 1;

/// Twice the signed area of triangle `a b c` (positive: clockwise on a y-down screen).
#[inline]
fn double_area(a: &SpanVertex, b: &SpanVertex, c: &SpanVertex) -> f32 {
    (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y)
}

/// A display value in `[0, 1]` as a fixed-point byte.
#[inline]
fn color_fixed(v: f32) -> i32 {
    (v.clamp(0.0, 1.0) * (255 << COLOR_BITS) as f32 + (1 << (COLOR_BITS - 1)) as f32) as i32
}

impl BladePiece {
    /// Sets up the convex polygon `v` (3 or 4 vertices in order, either
    /// winding) on a screen `height` pixels tall. `None` when it covers no row
    /// of pixel centres on screen or is degenerate.
    pub fn setup(v: &[SpanVertex], height: i32) -> Option<BladePiece> {
        debug_assert!((3..=MAX_EDGES).contains(&v.len()));
        let row = |y: f32| first_centre(y.clamp(-1.0, height as f32 + 1.0)).clamp(0, height);
        let mut cuts = [0.0f32; MAX_EDGES];
        for (cut, p) in cuts.iter_mut().zip(v) {
            *cut = p.y;
        }
        let cuts = &mut cuts[..v.len()];
        if cuts.iter().any(|y| y.is_nan()) {
            return None;
        }
        cuts.sort_unstable_by(f32::total_cmp);
        let first_row = row(cuts[0]);
        if first_row >= row(cuts[cuts.len() - 1]) {
            return None;
        }
        // Attribute planes from the vertex triangle of largest area.
        let (a, b, c) = if v.len() == 4
            && double_area(&v[0], &v[2], &v[3]).abs() > double_area(&v[0], &v[1], &v[2]).abs()
        {
            (&v[0], &v[2], &v[3])
        } else {
            (&v[0], &v[1], &v[2])
        };
        let area = double_area(a, b, c);
        // Also rejects NaN.
        if area.abs().partial_cmp(&MIN_DOUBLE_AREA) != Some(std::cmp::Ordering::Greater) {
            return None;
        }
        let inv = 1.0 / area;
        let (bx, by, cx, cy) = (b.x - a.x, b.y - a.y, c.x - a.x, c.y - a.y);
        let plane = |fa: Vec3, fb: Vec3, fc: Vec3| {
            let (db, dc) = (fb - fa, fc - fa);
            let dx = (db * cy - dc * by) * inv;
            let dy = (dc * bx - db * cx) * inv;
            [fa - dx * a.x - dy * a.y, dx, dy]
        };
        let color = plane(a.color, b.color, c.color);
        let last_row = row(cuts[cuts.len() - 1]) - 1;
        let x_of = |y: f32| v.iter().find(|p| p.y == y).map_or(0.0, |p| p.x);
        let ends = [
            (first_row, x_of(cuts[0])),
            (last_row, x_of(cuts[cuts.len() - 1])),
        ];
        let (color, color_step) = color_ramp(color, ends);
        let [d0, d_dx, d_dy] = plane(
            Vec3::splat(a.inv_w),
            Vec3::splat(b.inv_w),
            Vec3::splat(c.inv_w),
        );
        let depth = [d0.x, d_dx.x, d_dy.x];

        // Cut the rows at every vertex height; in each run the two edges that
        // span it are its bounds.
        let mut piece = BladePiece {
            first_row,
            run_count: 0,
            runs: [RowRun::default(); MAX_RUNS],
            edges: [EdgeLine::default(); MAX_EDGES],
            depth,
            color,
            color_step,
        };
        let mut start = first_row;
        for pair in cuts.windows(2) {
            let (y0, y1) = (pair[0], pair[1]);
            let end = row(y1);
            if end <= start {
                continue;
            }
            let mid = 0.5 * (y0 + y1);
            let mut spanning = (0..v.len()).filter(|&k| {
                let (p, q) = (&v[k], &v[(k + 1) % v.len()]);
                p.y.min(q.y) <= y0 && p.y.max(q.y) >= y1
            });
            let (Some(e0), Some(e1)) = (spanning.next(), spanning.next()) else {
                continue;
            };
            let x_at = |k: usize| {
                let (p, q) = (&v[k], &v[(k + 1) % v.len()]);
                p.x + (q.x - p.x) * ((mid - p.y) / (q.y - p.y))
            };
            let (left, right) = if x_at(e0) <= x_at(e1) {
                (e0, e1)
            } else {
                (e1, e0)
            };
            for k in [left, right] {
                piece.edges[k] = EdgeLine::new(&v[k], &v[(k + 1) % v.len()]);
            }
            piece.runs[piece.run_count as usize] = RowRun {
                end: end as i16,
                left: left as u8,
                right: right as u8,
            };
            piece.run_count += 1;
            start = end;
        }
        (piece.run_count > 0).then_some(piece)
    }

    /// First and last pixel rows the piece covers.
    #[inline]
    pub fn rows(&self) -> (i32, i32) {
        (
            self.first_row,
            i32::from(self.runs[self.run_count as usize - 1].end) - 1,
        )
    }

    /// Writes pixel `k` (of the band's colour buffer, in pixels) of row `y`
    /// in the piece's colour. Out of line: in a dense meadow drawn front to
    /// back few depth tests pass, and the row loop keeps its registers.
    #[cold]
    #[inline(never)]
    fn write_color(&self, color: &mut [u8], k: usize, y: i32) {
        let dy = y - self.first_row;
        let channel = |c: usize| ((self.color[c] + dy * self.color_step[c]) >> COLOR_BITS) as u8;
        color[4 * k..4 * k + 4].copy_from_slice(&[channel(0), channel(1), channel(2), 255]);
    }

    /// Draws the piece's rows inside the band: depth test `1/w` greater than
    /// stored, one colour per row.
    ///
    /// The band's rows are clipped once per run; a row then costs two edge
    /// steps, two shifts and clamps, one depth start and a compare per pixel.
    #[inline]
    pub fn draw(&self, band: &mut Band<'_>) {
        let width = band.width as usize;
        let [d0, d_dx, d_dy] = self.depth;
        let mut start = self.first_row;
        for run in &self.runs[..self.run_count as usize] {
            let end = i32::from(run.end);
            let (y0, y1) = (start.max(band.y0), end.min(band.y1));
            start = end;
            if y0 >= y1 {
                continue;
            }
            let (left, right) = (
                &self.edges[run.left as usize],
                &self.edges[run.right as usize],
            );
            // Biased so that a shift gives the first column at or after the edge.
            let (mut lx, mut rx) = (left.at(y0) + COLUMN_BIAS, right.at(y0) + COLUMN_BIAS);
            // `1/w` at the row's left screen edge, stepped down the rows.
            let mut row_depth = d0 + d_dy * (y0 as f32 + 0.5) + d_dx * 0.5;
            let mut row_start = (y0 - band.y0) as usize * width;
            for y in y0..y1 {
                let x0 = (lx >> FRAC_BITS).max(0);
                let x1 = (rx >> FRAC_BITS).min(width as i64);
                if x0 < x1 {
                    // From `i64`: a single conversion instruction, unlike `usize`.
                    let mut depth = row_depth + d_dx * x0 as f32;
                    let first = row_start + x0 as usize;
                    let stored = &mut band.depth[first..row_start + x1 as usize];
                    for (k, stored) in (first..).zip(stored) {
                        if depth > *stored {
                            *stored = depth;
                            self.write_color(band.color, k, y);
                        }
                        depth += d_dx;
                    }
                }
                lx += left.step;
                rx += right.step;
                row_depth += d_dy;
                row_start += width;
            }
        }
    }
}

/// A piece's colour as a fixed-point ramp down its rows: the colour plane
/// `[at origin, per pixel right, per pixel down]` evaluated at `ends` (first
/// row and the x of the top vertex, last row and the x of the bottom vertex),
/// clamped there so that every row in between stays in range. A blade is a
/// few pixels wide: its colour varies along it, one colour per row is enough.
fn color_ramp(plane: [Vec3; 3], ends: [(i32, f32); 2]) -> ([i32; 3], [i32; 3]) {
    let [c0, c_dx, c_dy] = plane;
    let at = |(y, x): (i32, f32)| c0 + c_dx * x + c_dy * (y as f32 + 0.5);
    let (first, last) = (ends[0].0, ends[1].0);
    let (top, bottom) = (at(ends[0]), at(ends[1]));
    let top = [color_fixed(top.x), color_fixed(top.y), color_fixed(top.z)];
    let bottom = [
        color_fixed(bottom.x),
        color_fixed(bottom.y),
        color_fixed(bottom.z),
    ];
    // Truncated towards zero, so the last row stays between both ends.
    let per_row = 1.0 / (last - first).max(1) as f32;
    let step = |k: usize| ((bottom[k] - top[k]) as f32 * per_row) as i32;
    (top, [step(0), step(1), step(2)])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_piece_fits_in_128_bytes() {
        assert!(std::mem::size_of::<BladePiece>() <= 128);
    }

    fn vertex(x: f32, y: f32, inv_w: f32) -> SpanVertex {
        SpanVertex {
            x,
            y,
            inv_w,
            color: Vec3::new(0.2, 0.6, 0.1),
        }
    }

    /// Draws each of `pieces` into a cleared `w` x `h` frame cut into bands of
    /// `band_rows` rows; returns how many pieces wrote each pixel.
    fn coverage(pieces: &[BladePiece], w: usize, h: usize, band_rows: usize) -> Vec<u32> {
        let mut color = vec![0u8; w * h * 4];
        let mut depth = vec![0.0f32; w * h];
        let mut writes = vec![0u32; w * h];
        for (b, (color, depth)) in color
            .chunks_mut(w * 4 * band_rows)
            .zip(depth.chunks_mut(w * band_rows))
            .enumerate()
        {
            let y0 = (b * band_rows) as i32;
            let mut band = Band {
                y1: y0 + (depth.len() / w) as i32,
                color,
                depth,
                width: w as i32,
                y0,
            };
            for piece in pieces {
                // Each piece at a fresh, larger depth: every covered pixel is written.
                band.depth.fill(0.0);
                piece.draw(&mut band);
                for (k, d) in band.depth.iter().enumerate() {
                    writes[y0 as usize * w + k] += u32::from(*d > 0.0);
                }
            }
        }
        writes
    }

    #[test]
    fn a_blade_quad_and_tip_cover_each_pixel_centre_once() {
        let mut seed = 0x2545_f491_u32;
        let mut next = move || {
            seed = seed.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            (seed >> 8) as f32 / (1u32 << 24) as f32
        };
        for _ in 0..200 {
            // A tapered, bent blade with sub-pixel vertices, either winding.
            let (rx, ry) = (10.0 + 20.0 * next(), 40.0 + 20.0 * next());
            let half = 0.3 + 3.0 * next();
            let (mx, my) = (rx + 8.0 * (next() - 0.5), ry - 10.0 - 15.0 * next());
            let (tx, ty) = (mx + 16.0 * (next() - 0.5), my - 5.0 - 20.0 * next());
            let s = if next() < 0.5 { 1.0 } else { -1.0 };
            let v = [
                vertex(rx - s * half, ry, 0.5),
                vertex(rx + s * half, ry + 0.3, 0.5),
                vertex(mx - s * 0.6 * half, my, 0.5),
                vertex(mx + s * 0.6 * half, my + 0.2, 0.5),
                vertex(tx, ty, 0.5),
            ];
            let pieces: Vec<BladePiece> = [
                BladePiece::setup(&[v[0], v[1], v[3], v[2]], 64),
                BladePiece::setup(&[v[2], v[3], v[4]], 64),
            ]
            .into_iter()
            .flatten()
            .collect();
            let writes = coverage(&pieces, 64, 64, 7);
            // Reference: pixel centres inside the quad or the tip (same-side test).
            let inside = |poly: &[SpanVertex], px: f32, py: f32| {
                let n = poly.len();
                let sides: Vec<f32> = (0..n)
                    .map(|k| {
                        let (a, b) = (poly[k], poly[(k + 1) % n]);
                        (b.x - a.x) * (py - a.y) - (b.y - a.y) * (px - a.x)
                    })
                    .collect();
                let margin = 1e-3;
                (
                    sides.iter().all(|&e| e > margin),
                    sides.iter().all(|&e| e < -margin),
                )
            };
            for y in 0..64 {
                for x in 0..64 {
                    let (px, py) = (x as f32 + 0.5, y as f32 + 0.5);
                    let count = writes[y * 64 + x];
                    assert!(count <= 1, "pixel ({x}, {y}) drawn {count} times");
                    let (q1, q2) = inside(&[v[0], v[1], v[3], v[2]], px, py);
                    let (t1, t2) = inside(&[v[2], v[3], v[4]], px, py);
                    if q1 || q2 || t1 || t2 {
                        assert_eq!(count, 1, "pixel ({x}, {y}) inside but missed");
                    }
                }
            }
        }
    }

    #[test]
    fn depth_and_colour_follow_the_planes() {
        // A quad whose depth grows to the right and colour darkens downwards.
        let mut v = [
            vertex(2.0, 2.0, 0.2),
            vertex(30.0, 2.0, 0.8),
            vertex(30.0, 30.0, 0.8),
            vertex(2.0, 30.0, 0.2),
        ];
        for p in &mut v[2..] {
            p.color = Vec3::ZERO;
        }
        for p in &mut v[..2] {
            p.color = Vec3::ONE;
        }
        let piece = BladePiece::setup(&v, 32).expect("covers pixels");
        assert_eq!(piece.rows(), (2, 29));
        let mut color = vec![0u8; 32 * 32 * 4];
        let mut depth = vec![0.0f32; 32 * 32];
        depth[16 * 32 + 16] = 0.9; // nearer than the quad there
        let mut band = Band {
            color: &mut color,
            depth: &mut depth,
            width: 32,
            y0: 0,
            y1: 32,
        };
        piece.draw(&mut band);
        let expect = |x: f32| 0.2 + 0.6 * (x - 2.0) / 28.0;
        for (x, y) in [(2usize, 2usize), (10, 20), (29, 29)] {
            let d = depth[y * 32 + x];
            assert!((d - expect(x as f32 + 0.5)).abs() < 1e-5, "({x}, {y}): {d}");
        }
        assert_eq!(depth[16 * 32 + 16], 0.9, "the nearer pixel is kept");
        assert_eq!(color[4 * (16 * 32 + 16)], 0, "and not recoloured");
        // One colour per row, from white at the top to black at the bottom.
        let grey = |y: usize| color[4 * (y * 32 + 10)];
        assert!(grey(2) > 240 && grey(29) < 15, "{} {}", grey(2), grey(29));
        assert!((3..30).all(|y| grey(y) <= grey(y - 1)));
        assert_eq!(color[4 * (20 * 32 + 5)], color[4 * (20 * 32 + 25)]);
        assert_eq!(depth[32 + 10], 0.0, "row 1 lies above the quad");
    }

    #[test]
    fn degenerate_and_off_screen_pieces_are_dropped() {
        let line = [
            vertex(1.0, 1.0, 0.5),
            vertex(5.0, 5.0, 0.5),
            vertex(9.0, 9.0, 0.5),
        ];
        assert!(BladePiece::setup(&line, 32).is_none());
        let below = [
            vertex(1.0, 40.0, 0.5),
            vertex(5.0, 40.0, 0.5),
            vertex(3.0, 50.0, 0.5),
        ];
        assert!(BladePiece::setup(&below, 32).is_none());
        let between = [
            vertex(1.0, 3.6, 0.5),
            vertex(9.0, 3.6, 0.5),
            vertex(3.0, 4.4, 0.5),
        ];
        assert!(
            BladePiece::setup(&between, 32).is_none(),
            "no row centre inside"
        );
        let nan = [
            vertex(f32::NAN, 3.0, 0.5),
            vertex(9.0, 3.6, 0.5),
            vertex(3.0, 9.4, 0.5),
        ];
        assert!(BladePiece::setup(&nan, 32).is_none());
    }
}
