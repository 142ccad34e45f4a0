//! The grass blade rasterizer: a blade is one y-monotone polygon (its whole
//! outline: root pair, middle pair, tip), or, when a row would meet that
//! outline twice (a blade folded towards the camera), two convex pieces (its
//! lower quad and its tip), each filled as one span per pixel row.
//!
//! A piece is set up once, in the parallel geometry stage, by walking its left
//! and right sides down from the top vertex together: its rows are cut at each
//! vertex into at most four runs, each bounded by one left and one right edge in
//! fixed point. `1/w` becomes a plane over the screen and the colour a
//! fixed-point ramp from the top vertex's colour to the bottom one's. A band then
//! fills each row with two integer edge steps, one colour and one depth test per
//! pixel, with `1/w` linear along the row.
//! There is no per-pixel edge function, no division and no float-to-integer
//! conversion per row.
//!
//! Coverage rule: a pixel centre `(x + 0.5, y + 0.5)` is covered when
//! `left(y) <= x + 0.5 < right(y)` and `top <= y + 0.5 < bottom`. An edge's
//! fixed-point line depends only on its two end points (taken top first), so two
//! pieces sharing an edge (a blade's quad and tip) step it identically and split
//! its pixels exactly: no gap, no pixel drawn twice.

use glam::{IVec3, Vec3, Vec3A};

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

/// Most vertices of a piece (a whole blade: root pair, middle pair, tip).
pub(crate) const MAX_VERTICES: usize = 5;
/// Most runs and edges a piece has.
const MAX_RUNS: usize = MAX_VERTICES - 1;
const MAX_EDGES: usize = MAX_VERTICES;

/// A y-monotone polygon of at most [`MAX_VERTICES`] vertices, set up for span
/// filling.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct BladePiece {
    /// First covered row (`i16` like [`RowRun::end`]).
    first_row: i16,
    /// Number of used entries in `runs`.
    run_count: u8,
    /// Row runs, top to bottom.
    runs: [RowRun; MAX_RUNS],
    /// The piece's edges (`k` from vertex `k` to the next); only those that
    /// bound a run are set.
    edges: [EdgeLine; MAX_EDGES],
    /// `1/w` at the screen origin, and its change per pixel right and down.
    depth: [f32; 3],
    /// Fixed-point colour at the centre of the first row.
    color: [i32; 3],
    /// Its change per row.
    color_step: [i32; 3],
}

/// The polygon given to [`BladePiece::setup`] is not y-monotone or crosses
/// itself: some row would meet it in more than one span.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct NotMonotone;

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

/// A display colour (channels in `[0, 1]`) as fixed-point bytes, the three
/// channels at once.
#[inline]
fn color_fixed(c: Vec3) -> IVec3 {
    let scaled = Vec3A::from(c).clamp(Vec3A::ZERO, Vec3A::ONE) * (255 << COLOR_BITS) as f32
        + (1 << (COLOR_BITS - 1)) as f32;
    scaled.as_ivec3()
}

/// The two sides of a blade outline in its usual shape ([`Side::of_blade`]),
/// walking forwards (`3 4 0`) and backwards (`3 2 1`), indexed by its bottom
/// root: the other root ends the side that reaches it first.
const USUAL_BLADE_SIDES: [[Side; 2]; 2] = [
    [
        Side::new([3, 4, 0, 3, 3], [3, 4, 0, 0, 0], 3),
        Side::new([3, 2, 1, 0, 3], [2, 1, 0, 0, 0], 4),
    ],
    [
        Side::new([3, 4, 0, 1, 3], [3, 4, 0, 0, 0], 4),
        Side::new([3, 2, 1, 3, 3], [2, 1, 0, 0, 0], 3),
    ],
];

/// One side of a polygon, from its top vertex down to its bottom one.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Side {
    /// Vertex indices, top first.
    vertices: [u8; MAX_VERTICES],
    /// `edges[k]`: the polygon edge from `vertices[k]` to `vertices[k + 1]`
    /// (polygon edge `e` joins vertex `e` to vertex `e + 1`).
    edges: [u8; MAX_VERTICES],
    /// Number of vertices on the side.
    len: usize,
}

impl Side {
    /// The side through `vertices[..len]` along `edges[..len - 1]`.
    const fn new(vertices: [u8; MAX_VERTICES], edges: [u8; MAX_VERTICES], len: usize) -> Side {
        Side {
            vertices,
            edges,
            len,
        }
    }

    /// The side of `v` from `top` to `bottom` walking forwards (vertex `k` to
    /// `k + 1`) or backwards; [`NotMonotone`] when it goes up again.
    #[inline(always)]
    fn walk(
        v: &[SpanVertex],
        top: usize,
        bottom: usize,
        forward: bool,
    ) -> Result<Side, NotMonotone> {
        let last = v.len() - 1;
        let mut side = Side {
            vertices: [top as u8; MAX_VERTICES],
            edges: [0; MAX_VERTICES],
            len: 1,
        };
        let mut k = top;
        while k != bottom && side.len < MAX_VERTICES {
            // Wrapped by a compare: no division.
            let next = match (forward, k) {
                (true, k) if k == last => 0,
                (true, k) => k + 1,
                (false, 0) => last,
                (false, k) => k - 1,
            };
            if v[next].y < v[k].y {
                return Err(NotMonotone);
            }
            side.edges[side.len - 1] = if forward { k } else { next } as u8;
            side.vertices[side.len] = next as u8;
            side.len += 1;
            k = next;
        }
        Ok(side)
    }

    /// Splits `v` at its top and bottom vertices into its left and right
    /// sides; [`NotMonotone`] when a side goes up again. A blade outline in
    /// its usual shape takes the shortcut of [`Side::of_blade`].
    #[inline(always)]
    fn of(v: &[SpanVertex]) -> Result<(Side, Side), NotMonotone> {
        // A constant-length slice: the test folds away for other lengths.
        match <&[SpanVertex; 5]>::try_from(v)
            .ok()
            .and_then(Side::of_blade)
        {
            Some(sides) => Ok(sides),
            None => Side::walked(v),
        }
    }

    /// [`Side::of`] for any polygon: the top and bottom vertices searched,
    /// both sides walked between them.
    #[inline(always)]
    fn walked(v: &[SpanVertex]) -> Result<(Side, Side), NotMonotone> {
        let (mut top, mut bottom) = (0, 0);
        for (k, p) in v.iter().enumerate().skip(1) {
            if p.y < v[top].y {
                top = k;
            }
            if p.y > v[bottom].y {
                bottom = k;
            }
        }
        let forward = Side::walk(v, top, bottom, true)?;
        let backward = Side::walk(v, top, bottom, false)?;
        Ok(Side::by_winding(v, forward, backward))
    }

    /// The left and right sides from the sides walked forwards and backwards:
    /// clockwise on screen (positive area), the forward side is the right one.
    #[inline(always)]
    fn by_winding(v: &[SpanVertex], forward: Side, backward: Side) -> (Side, Side) {
        let area: f32 = (1..v.len() - 1)
            .map(|k| double_area(&v[0], &v[k], &v[k + 1]))
            .sum();
        if area > 0.0 {
            (backward, forward)
        } else {
            (forward, backward)
        }
    }

    /// [`Side::of`] for a blade outline in its usual shape: root pair
    /// (vertices 0 and 1), middle pair (2 on the side of 1, 4 on the side of
    /// 0) and the tip (3) strictly above every other vertex, the lower root
    /// below both middle vertices, each middle vertex below the tip and above
    /// its root. Then the top is the tip, the bottom the lower root (the first
    /// one on a tie) and the sides are `3 4 0 (1)` and `3 2 1 (0)`: the same
    /// sides as the general walk gives, from five compares. `None` for any
    /// other shape (the general walk decides).
    #[inline(always)]
    fn of_blade(v: &[SpanVertex; 5]) -> Option<(Side, Side)> {
        let y = v.map(|p| p.y);
        let bottom = usize::from(y[1] > y[0]);
        let usual =
            y[3] < y[2].min(y[4]) && y[4] <= y[0] && y[2] <= y[1] && y[2].max(y[4]) <= y[bottom];
        if !usual {
            return None;
        }
        let [forward, backward] = USUAL_BLADE_SIDES[bottom];
        Some(Side::by_winding(v, forward, backward))
    }
}

/// Which side of the line from `a` to `b` the point `p` lies on (positive:
/// left of a downward line on a y-down screen).
#[inline]
fn side_of(a: &SpanVertex, b: &SpanVertex, p: &SpanVertex) -> f32 {
    (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x)
}

impl BladePiece {
    /// Sets up the simple polygon `v` (3 to [`MAX_VERTICES`] vertices in
    /// order, either winding) on a screen `height` pixels tall.
    ///
    /// `Ok(None)` when it covers no row of pixel centres on screen or is
    /// degenerate; [`NotMonotone`] when a row could meet it in two spans (a
    /// side that goes up again, or sides that cross), which a convex polygon
    /// never does.
    ///
    /// Inlined: the caller's `Vec::extend` then builds the piece in place
    /// instead of copying a returned `Result<Option<_>>`; the vertex count
    /// `N` is a constant, so the loops over the vertices unroll.
    #[inline]
    pub fn setup<const N: usize>(
        v: &[SpanVertex; N],
        height: i32,
    ) -> Result<Option<BladePiece>, NotMonotone> {
        const { assert!(3 <= N && N <= MAX_VERTICES) };
        if v.iter().any(|p| p.y.is_nan()) {
            return Ok(None);
        }
        let (left, right) = Side::of(v)?;
        let (top, bottom) = (
            &v[left.vertices[0] as usize],
            &v[left.vertices[left.len - 1] as usize],
        );
        // The first row at or below each vertex: `row(min(a, b))` is
        // `min(row(a), row(b))`, so the runs' ends come from these.
        let h = height as f32 + 1.0;
        let mut rows = [0i32; MAX_VERTICES];
        for (r, p) in rows.iter_mut().zip(v) {
            *r = first_centre(p.y.clamp(-1.0, h)).clamp(0, height);
        }
        let first_row = rows[left.vertices[0] as usize];
        let end_row = rows[left.vertices[left.len - 1] as usize];
        if first_row >= end_row {
            return Ok(None);
        }
        // Depth plane from the top, the bottom and the vertex farthest from
        // the line through them (the largest such triangle).
        let third = v
            .iter()
            .map(|p| double_area(top, bottom, p).abs())
            .enumerate()
            .max_by(|a, b| a.1.total_cmp(&b.1))
            .map_or(0, |(k, _)| k);
        let c = &v[third];
        let area = double_area(top, bottom, c);
        // Also rejects NaN.
        if area.abs().partial_cmp(&MIN_DOUBLE_AREA) != Some(std::cmp::Ordering::Greater) {
            return Ok(None);
        }
        let inv = 1.0 / area;
        let (bx, by, cx, cy) = (bottom.x - top.x, bottom.y - top.y, c.x - top.x, c.y - top.y);
        let (db, dc) = (bottom.inv_w - top.inv_w, c.inv_w - top.inv_w);
        let d_dx = (db * cy - dc * by) * inv;
        let d_dy = (dc * bx - db * cx) * inv;
        let depth = [top.inv_w - d_dx * top.x - d_dy * top.y, d_dx, d_dy];
        let (color, color_step) = color_ramp(top.color, bottom.color, end_row - 1 - first_row);

        let mut piece = BladePiece {
            first_row: first_row as i16,
            run_count: 0,
            runs: [RowRun::default(); MAX_RUNS],
            edges: [EdgeLine::default(); MAX_EDGES],
            depth,
            color,
            color_step,
        };
        // Walk both sides down together; a run ends at the next vertex of
        // either side.
        let (mut i, mut j, mut start) = (0, 0, first_row);
        // The edge each side built last: a side's edges bound consecutive
        // runs, and no edge lies on both sides.
        let (mut left_edge, mut right_edge) = (u8::MAX, u8::MAX);
        while i + 1 < left.len && j + 1 < right.len {
            let (l0, l1) = (left.vertices[i] as usize, left.vertices[i + 1] as usize);
            let (r0, r1) = (right.vertices[j] as usize, right.vertices[j + 1] as usize);
            let (pl0, pl1, pr0, pr1) = (&v[l0], &v[l1], &v[r0], &v[r1]);
            let end = rows[l1].min(rows[r1]);
            if end > start {
                let (el, er) = (left.edges[i], right.edges[j]);
                if el != left_edge {
                    piece.edges[el as usize] = EdgeLine::new(pl0, pl1);
                    left_edge = el;
                }
                if er != right_edge {
                    piece.edges[er as usize] = EdgeLine::new(pr0, pr1);
                    right_edge = er;
                }
                piece.runs[piece.run_count as usize] = RowRun {
                    end: end as i16,
                    left: el,
                    right: er,
                };
                piece.run_count += 1;
                start = end;
            }
            // The sides must not cross: a side's inner vertex lies on its
            // own side of the other's edge.
            let (advance_left, advance_right) = (pl1.y <= pr1.y, pr1.y <= pl1.y);
            if advance_left && i + 2 < left.len && side_of(pr0, pr1, pl1) < 0.0 {
                return Err(NotMonotone);
            }
            if advance_right && j + 2 < right.len && side_of(pl0, pl1, pr1) > 0.0 {
                return Err(NotMonotone);
            }
            i += usize::from(advance_left);
            j += usize::from(advance_right);
        }
        Ok((piece.run_count > 0).then_some(piece))
    }

    /// First and last pixel rows the piece covers.
    #[inline]
    pub fn rows(&self) -> (i32, i32) {
        (
            i32::from(self.first_row),
            i32::from(self.runs[self.run_count as usize - 1].end) - 1,
        )
    }

    /// Writes pixel `k` (of the band's colour buffer, in pixels) of row `y`
    /// in the piece's colour. Out of line: in a dense meadow drawn front to
    /// back few depth tests pass, and the row loop keeps its registers.
    #[cold]
    #[inline(never)]
    fn write_color(&self, color: &mut [u8], k: usize, y: i32) {
        let dy = y - i32::from(self.first_row);
        let channel = |c: usize| ((self.color[c] + dy * self.color_step[c]) >> COLOR_BITS) as u8;
        color[4 * k..4 * k + 4].copy_from_slice(&[channel(0), channel(1), channel(2), 255]);
    }

    /// Draws the piece's rows inside the band: depth test `1/w` greater than
    /// stored, one colour per row.
    ///
    /// The band's rows are clipped once per run; a row then costs two edge
    /// steps, two shifts and clamps, one depth start and a compare per pixel.
    #[inline(always)]
    pub fn draw(&self, band: &mut Band<'_>) {
        let width = band.width as usize;
        let [d0, d_dx, d_dy] = self.depth;
        let mut start = i32::from(self.first_row);
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

/// A piece's colour as a fixed-point ramp down its rows: from `top` (the top
/// vertex's colour, used for the first row) to `bottom` (the bottom vertex's,
/// reached `rows` rows later). A blade is a few pixels wide: its colour varies
/// along it, one colour per row is enough.
fn color_ramp(top: Vec3, bottom: Vec3, rows: i32) -> ([i32; 3], [i32; 3]) {
    let top = color_fixed(top);
    // Truncated towards zero, so the last row stays between both ends.
    let per_row = 1.0 / rows.max(1) as f32;
    let step = ((color_fixed(bottom) - top).as_vec3a() * per_row).as_ivec3();
    (top.to_array(), step.to_array())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_piece_stays_small() {
        // A whole blade in 136 bytes: less than half of its quad and tip (2 x 128).
        assert!(std::mem::size_of::<BladePiece>() <= 136);
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

    /// A tapered, bent blade with sub-pixel vertices, either winding: root
    /// pair, middle pair, tip.
    fn random_blade(next: &mut impl FnMut() -> f32) -> [SpanVertex; 5] {
        let (rx, ry) = (10.0 + 20.0 * next(), 40.0 + 20.0 * next());
        let half = 0.3 + 3.0 * next();
        let (mx, my) = (rx + 8.0 * (next() - 0.5), ry - 10.0 - 15.0 * next());
        let (tx, ty) = (mx + 16.0 * (next() - 0.5), my - 5.0 - 20.0 * next());
        let s = if next() < 0.5 { 1.0 } else { -1.0 };
        [
            vertex(rx - s * half, ry, 0.5),
            vertex(rx + s * half, ry + 0.3, 0.5),
            vertex(mx - s * 0.6 * half, my, 0.5),
            vertex(mx + s * 0.6 * half, my + 0.2, 0.5),
            vertex(tx, ty, 0.5),
        ]
    }

    fn lcg(mut seed: u32) -> impl FnMut() -> f32 {
        move || {
            seed = seed.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            (seed >> 8) as f32 / (1u32 << 24) as f32
        }
    }

    /// Whether the pixel centre `(px, py)` lies inside the convex polygon
    /// `poly` (either winding) by more than a small margin.
    fn inside_convex(poly: &[SpanVertex], px: f32, py: f32) -> bool {
        let n = poly.len();
        let sides: Vec<f32> = (0..n)
            .map(|k| {
                let (a, b) = (poly[k], poly[(k + 1) % n]);
                (b.x - a.x) * (py - a.y) - (b.y - a.y) * (px - a.x)
            })
            .collect();
        let margin = 1e-3;
        sides.iter().all(|&e| e > margin) || sides.iter().all(|&e| e < -margin)
    }

    /// Checks that `pieces` of blade `v` cover every pixel centre inside its
    /// quad or tip once and none twice.
    fn assert_covers_blade_once(pieces: &[BladePiece], v: &[SpanVertex; 5]) {
        let writes = coverage(pieces, 64, 64, 7);
        let (quad, tip) = ([v[0], v[1], v[3], v[2]], [v[2], v[3], v[4]]);
        for y in 0..64 {
            for x in 0..64 {
                let (px, py) = (x as f32 + 0.5, y as f32 + 0.5);
                let count = writes[y * 64 + x];
                assert!(count <= 1, "pixel ({x}, {y}) drawn {count} times");
                if inside_convex(&quad, px, py) || inside_convex(&tip, px, py) {
                    assert_eq!(count, 1, "pixel ({x}, {y}) inside but missed");
                }
            }
        }
    }

    #[test]
    fn a_blade_quad_and_tip_cover_each_pixel_centre_once() {
        let mut next = lcg(0x2545_f491);
        for _ in 0..200 {
            let v = random_blade(&mut next);
            let pieces: Vec<BladePiece> = [
                BladePiece::setup(&[v[0], v[1], v[3], v[2]], 64),
                BladePiece::setup(&[v[2], v[3], v[4]], 64),
            ]
            .into_iter()
            .filter_map(|p| p.expect("convex pieces are monotone"))
            .collect();
            assert_covers_blade_once(&pieces, &v);
        }
    }

    #[test]
    fn a_blade_outline_covers_its_quad_and_tip_once_or_is_refused() {
        let mut next = lcg(0x9e37_79b9);
        let (mut whole, mut refused) = (0, 0);
        for _ in 0..400 {
            let v = random_blade(&mut next);
            match BladePiece::setup(&[v[0], v[1], v[3], v[4], v[2]], 64) {
                Ok(piece) => {
                    whole += 1;
                    let pieces: Vec<BladePiece> = piece.into_iter().collect();
                    assert_covers_blade_once(&pieces, &v);
                    // No pixel outside the outline either (same test, with
                    // the outline split into the quad and the tip).
                    let writes = coverage(&pieces, 64, 64, 7);
                    let outline = [v[0], v[1], v[3], v[4], v[2]];
                    for (k, &count) in writes.iter().enumerate() {
                        let (px, py) = ((k % 64) as f32 + 0.5, (k / 64) as f32 + 0.5);
                        if count > 0 {
                            assert!(
                                crossings(&outline, px, py) % 2 == 1 || near_edge(&outline, px, py),
                                "pixel ({px}, {py}) outside the outline"
                            );
                        }
                    }
                }
                Err(NotMonotone) => refused += 1,
            }
        }
        // Upright blades (tip above middle above root) are drawn whole.
        assert!(whole > 380, "{whole} whole, {refused} refused");
    }

    /// How many edges of `poly` a ray from `(px, py)` towards +x crosses.
    fn crossings(poly: &[SpanVertex], px: f32, py: f32) -> usize {
        let n = poly.len();
        (0..n)
            .filter(|&k| {
                let (a, b) = (poly[k], poly[(k + 1) % n]);
                (a.y > py) != (b.y > py) && px < a.x + (py - a.y) * (b.x - a.x) / (b.y - a.y)
            })
            .count()
    }

    /// Whether `(px, py)` lies within a thousandth of a pixel of an edge.
    fn near_edge(poly: &[SpanVertex], px: f32, py: f32) -> bool {
        let n = poly.len();
        (0..n).any(|k| {
            let (a, b) = (poly[k], poly[(k + 1) % n]);
            let (dx, dy) = (b.x - a.x, b.y - a.y);
            let t = (((px - a.x) * dx + (py - a.y) * dy) / (dx * dx + dy * dy)).clamp(0.0, 1.0);
            (a.x + t * dx - px).hypot(a.y + t * dy - py) < 1e-3
        })
    }

    #[test]
    fn the_blade_shortcut_finds_the_sides_the_walk_finds() {
        let mut next = lcg(0x0bad_5eed);
        let mut taken = 0;
        for k in 0..2000 {
            // Blades in the drawn order, then any pentagons (with exact ties
            // among the heights now and then).
            let v: [SpanVertex; 5] = if k % 2 == 0 {
                let b = random_blade(&mut next);
                [b[0], b[1], b[3], b[4], b[2]]
            } else {
                std::array::from_fn(|_| {
                    let y = (8.0 * next()).floor() * if next() < 0.5 { 1.0 } else { 1.37 };
                    vertex(20.0 * next(), y, 0.5)
                })
            };
            if let Some(sides) = Side::of_blade(&v) {
                taken += 1;
                assert_eq!(Ok(sides), Side::walked(&v), "{v:?}");
            }
        }
        assert!(taken > 1000, "shortcut taken {taken} times");
    }

    #[test]
    fn a_folded_or_crossed_outline_is_refused() {
        // The tip folded back down over the root: the left side goes up again.
        let folded = [
            vertex(10.0, 40.0, 0.5),
            vertex(14.0, 40.0, 0.5),
            vertex(13.0, 20.0, 0.5),
            vertex(12.0, 30.0, 0.5),
            vertex(11.0, 20.0, 0.5),
        ];
        assert_eq!(BladePiece::setup(&folded, 64), Err(NotMonotone));
        // Both sides go down, but they cross between y = 10 and y = 15.
        let crossed = [
            vertex(15.0, 0.0, 0.5),
            vertex(25.0, 10.0, 0.5),
            vertex(10.0, 20.0, 0.5),
            vertex(30.0, 15.0, 0.5),
            vertex(5.0, 5.0, 0.5),
        ];
        assert_eq!(BladePiece::setup(&crossed, 64), Err(NotMonotone));
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
        let piece = BladePiece::setup(&v, 32).unwrap().expect("covers pixels");
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
        assert_eq!(BladePiece::setup(&line, 32), Ok(None));
        let below = [
            vertex(1.0, 40.0, 0.5),
            vertex(5.0, 40.0, 0.5),
            vertex(3.0, 50.0, 0.5),
        ];
        assert_eq!(BladePiece::setup(&below, 32), Ok(None));
        let between = [
            vertex(1.0, 3.6, 0.5),
            vertex(9.0, 3.6, 0.5),
            vertex(3.0, 4.4, 0.5),
        ];
        assert_eq!(
            BladePiece::setup(&between, 32),
            Ok(None),
            "no row centre inside"
        );
        let nan = [
            vertex(f32::NAN, 3.0, 0.5),
            vertex(9.0, 3.6, 0.5),
            vertex(3.0, 9.4, 0.5),
        ];
        assert_eq!(BladePiece::setup(&nan, 32), Ok(None));
    }
}
