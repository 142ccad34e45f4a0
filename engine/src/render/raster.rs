//! The triangle rasterizer: integer edge functions with 8 sub-pixel bits, the
//! top-left fill rule, a `1/w` depth buffer and perspective-correct colours.
//!
//! A triangle is set up once, in the (parallel) geometry stage, into a
//! [`Triangle`]: its pixel box, the planes of its attributes, and either the bit
//! mask of the pixel centres it covers (small boxes, the common case for terrain
//! cells, set up by [`super::small_triangle`]) or its edge functions (larger
//! boxes, [`BigTriangle`]), so that the bands only fill. A triangle covering a
//! single pixel centre becomes a [`Dot`].

use glam::{Vec3, Vec4};

/// Sub-pixel bits of screen coordinates (16.8 fixed point, as D3D11).
pub(crate) const SUBPIXEL_BITS: u32 = 8;
/// One pixel in fixed point.
pub(crate) const ONE: i64 = 1 << SUBPIXEL_BITS;
/// Half a pixel in fixed point.
pub(crate) const HALF: i64 = ONE / 2;

/// Pixel boxes at most this many pixels wide and tall store their coverage as a
/// 64-bit mask (bit `8 * row + column`).
pub(crate) const MASK_SIDE: i32 = 8;

/// ... when their vertices also span less than this (fixed point) per axis:
/// then an edge value at any pixel centre inside their bounding box, at most
/// `2 * MASK_EXTENT^2 + 1` in magnitude, is exact in `f32`.
pub(crate) const MASK_EXTENT: i32 = 11 << SUBPIXEL_BITS;
const _: () =
    assert!(2 * (MASK_EXTENT as i64) * (MASK_EXTENT as i64) + 1 < 1 << f32::MANTISSA_DIGITS);

/// A vertex after projection: fixed-point pixel position (y down), `1/w`, colour / w.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct ScreenVertex {
    /// X in pixels, fixed point.
    pub x: i32,
    /// Y in pixels (down), fixed point.
    pub y: i32,
    /// Reciprocal of clip `w`: linear in screen space, larger is nearer (the depth).
    pub inv_w: f32,
    /// Colour divided by `w`, for perspective-correct interpolation.
    pub color_w: Vec3,
}

impl ScreenVertex {
    /// The interpolated attributes: `1/w` then colour / w.
    #[inline]
    fn attributes(&self) -> Vec4 {
        Vec4::new(self.inv_w, self.color_w.x, self.color_w.y, self.color_w.z)
    }
}

/// The pixel range a triangle's bounding box covers: first/last pixel columns
/// and rows whose centres lie inside the box (may be empty: first > last).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct PixelSpan {
    pub x0: i32,
    pub x1: i32,
    pub y0: i32,
    pub y1: i32,
}

/// First pixel index whose centre is at or after fixed coordinate `v` (vertices
/// inside the guard band keep these sums far from `i32` overflow).
#[inline]
pub(crate) fn first_centre(v: i32) -> i32 {
    // Arithmetic shifts floor, also for negative values.
    (v - HALF as i32 + ONE as i32 - 1) >> SUBPIXEL_BITS
}

/// Last pixel index whose centre is at or before fixed coordinate `v`.
#[inline]
pub(crate) fn last_centre(v: i32) -> i32 {
    (v - HALF as i32) >> SUBPIXEL_BITS
}

/// The fixed-point bounding box of a triangle's vertices: the reference the
/// renderer's pixel spans ([`super::centre_box`]) and small-triangle extent
/// tests are checked against.
#[cfg(test)]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct ScreenBox {
    pub min_x: i32,
    pub max_x: i32,
    pub min_y: i32,
    pub max_y: i32,
}

#[cfg(test)]
impl ScreenBox {
    /// The bounding box of `v` (in any order).
    #[inline(always)]
    pub fn of(v: [&ScreenVertex; 3]) -> ScreenBox {
        ScreenBox {
            min_x: v[0].x.min(v[1].x).min(v[2].x),
            max_x: v[0].x.max(v[1].x).max(v[2].x),
            min_y: v[0].y.min(v[1].y).min(v[2].y),
            max_y: v[0].y.max(v[1].y).max(v[2].y),
        }
    }

    /// The span of pixel centres inside the box, clipped to a `width` x
    /// `height` screen.
    pub fn span(&self, width: i32, height: i32) -> PixelSpan {
        PixelSpan {
            x0: first_centre(self.min_x).max(0),
            x1: last_centre(self.max_x).min(width - 1),
            y0: first_centre(self.min_y).max(0),
            y1: last_centre(self.max_y).min(height - 1),
        }
    }
}

impl PixelSpan {
    /// Its numbers of columns and rows (of a span holding a pixel centre).
    #[inline(always)]
    pub fn size(&self) -> (u32, u32) {
        (
            (self.x1 - self.x0 + 1) as u32,
            (self.y1 - self.y0 + 1) as u32,
        )
    }

    /// True when no pixel centre is covered.
    #[cfg(test)]
    pub fn is_empty(&self) -> bool {
        self.x0 > self.x1 || self.y0 > self.y1
    }
}

/// Twice the signed area of the triangle in fixed point squared; positive when
/// the vertices run clockwise on a y-down screen (the rasterizer's winding).
#[inline]
pub(crate) fn signed_area(a: &ScreenVertex, b: &ScreenVertex, c: &ScreenVertex) -> i64 {
    (b.x as i64 - a.x as i64) * (c.y as i64 - a.y as i64)
        - (b.y as i64 - a.y as i64) * (c.x as i64 - a.x as i64)
}

/// A horizontal band of the frame: colour (RGBA8) and depth rows `y0..y1`.
pub(crate) struct Band<'a> {
    /// RGBA8 pixels of the band's rows.
    pub color: &'a mut [u8],
    /// `1/w` per pixel; 0 is empty (infinitely far).
    pub depth: &'a mut [f32],
    /// Frame width in pixels.
    pub width: i32,
    /// First row of the band.
    pub y0: i32,
    /// One past the last row of the band.
    pub y1: i32,
}

/// One edge function `E(p) = dx * (py - ay) - dy * (px - ax)` with its top-left bias.
#[derive(Debug, Clone, Copy)]
struct Edge {
    step_x: i64,
    step_y: i64,
    /// Value at the first pixel centre, bias included: covered when `>= 0`.
    start: i64,
}

impl Edge {
    #[inline]
    fn new(a: &ScreenVertex, b: &ScreenVertex, px: i64, py: i64) -> Edge {
        let dx = b.x as i64 - a.x as i64;
        let dy = b.y as i64 - a.y as i64;
        Edge {
            step_x: -dy * ONE,
            step_y: dx * ONE,
            start: edge_value(dx, dy, a, px, py),
        }
    }

    /// Narrows the pixel run `lo..=hi` (offsets from the row's first pixel, where
    /// the edge value is `value`) to where this edge covers.
    #[inline]
    fn covered_run(&self, value: i64, lo: i32, hi: i32) -> (i32, i32) {
        if self.step_x > 0 {
            // value + k * step >= 0  <=>  k >= ceil(-value / step)
            let first =
                (-value).div_euclid(self.step_x) + i64::from((-value).rem_euclid(self.step_x) != 0);
            (lo.max(first.clamp(0, i32::MAX as i64) as i32), hi)
        } else if self.step_x < 0 {
            // value + k * step >= 0  <=>  k <= floor(value / -step)
            let last = value.div_euclid(-self.step_x);
            (lo, hi.min(last.clamp(-1, i32::MAX as i64) as i32))
        } else if value < 0 {
            (lo, -1)
        } else {
            (lo, hi)
        }
    }
}

/// The value at fixed point `(px, py)` of the edge from `a` by `(dx, dy)`, with
/// its top-left bias: covered when `>= 0`.
#[inline]
fn edge_value(dx: i64, dy: i64, a: &ScreenVertex, px: i64, py: i64) -> i64 {
    // Interior is E > 0 (clockwise on a y-down screen). Pixels exactly on an
    // edge belong to it only when it is a top edge (horizontal, going right)
    // or a left edge (going up), so shared edges are drawn exactly once.
    let top_left = dy < 0 || (dy == 0 && dx > 0);
    let bias = if top_left { 0 } else { -1 };
    dx * (py - a.y as i64) - dy * (px - a.x as i64) + bias
}

/// The barycentric weights of a triangle's vertices 1 and 2 (edge values
/// over twice the area) at its box's first pixel centre, and their change per
/// pixel right and down.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct VertexWeights {
    /// At the first centre.
    pub start: [f32; 2],
    /// Per pixel to the right.
    pub step_x: [f32; 2],
    /// Per pixel down.
    pub step_y: [f32; 2],
}

impl VertexWeights {
    /// The weights of a triangle with positive [`signed_area`] `area` (exact
    /// in `f32` for small triangles) from the values of its edges 1 and 2
    /// (opposite vertices 1 and 2) in lanes 1 and 2 of `start` (at the box's
    /// first centre, top-left bias included: at most 1 unit, negligible in
    /// the weights), `step_x` (per pixel right) and `step_y` (per pixel down).
    #[inline(always)]
    pub fn from_edges(area: f32, start: Vec4, step_x: Vec4, step_y: Vec4) -> VertexWeights {
        let inv_area = 1.0 / area;
        let weights = |e: Vec4| {
            let w = e * inv_area;
            [w.y, w.z]
        };
        VertexWeights {
            start: weights(start),
            step_x: weights(step_x),
            step_y: weights(step_y),
        }
    }
}

/// The planes of a triangle's attributes (`1/w`, colour / w) over the pixel
/// centres.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Planes {
    /// Attributes at the centre of the box's first pixel.
    base: Vec4,
    /// Attribute change per pixel to the right.
    step_x: Vec4,
    /// Attribute change per pixel down.
    step_y: Vec4,
}

impl Planes {
    /// The planes of triangle `v` from the weights of its vertices 1 and 2.
    #[inline(always)]
    pub fn from_weights(v: [&ScreenVertex; 3], weights: VertexWeights) -> Planes {
        let a0 = v[0].attributes();
        let (d1, d2) = (v[1].attributes() - a0, v[2].attributes() - a0);
        let blend = |[w1, w2]: [f32; 2]| d1 * w1 + d2 * w2;
        Planes {
            base: a0 + blend(weights.start),
            step_x: blend(weights.step_x),
            step_y: blend(weights.step_y),
        }
    }

    /// The attributes `column` pixels right of and `row` pixels below the box's
    /// first centre (the same sums as filling that row's run from its first pixel).
    #[inline]
    fn at(&self, column: i32, row: i32) -> Vec4 {
        self.base + self.step_y * row as f32 + self.step_x * column as f32
    }
}

/// The three edge functions of a triangle whose box is too big for a mask.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Edges([Edge; 3]);

/// Which pixel centres of its box a [`Triangle`] covers.
#[derive(Debug, Clone, Copy)]
enum Coverage {
    /// Bit `8 * row + column` (relative to the box corner) per covered centre.
    Mask(u64),
    /// Index of the triangle's [`Edges`] in its batch.
    Edges(u32),
}

/// A triangle set up for filling: its pixel box, coverage, and the planes of its
/// attributes (`1/w`, colour / w) over the pixel centres.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Triangle {
    planes: Planes,
    /// The covered pixel box (clipped to the screen).
    span: PixelSpan,
    coverage: Coverage,
}

impl Triangle {
    /// A triangle covering the centres of `mask` (bit `8 * row + column`,
    /// relative to the corner of `span`, a box at most [`MASK_SIDE`] pixels per side).
    #[inline]
    pub fn masked(planes: Planes, span: PixelSpan, mask: u64) -> Triangle {
        Triangle {
            planes,
            span,
            coverage: Coverage::Mask(mask),
        }
    }
}

/// A triangle too big for a [`super::small_triangle::SmallTriangle`]: its
/// edge functions, walked row by row when filling.
#[derive(Debug, Clone, Copy)]
pub(crate) struct BigTriangle {
    /// Edge functions at the box's first pixel centre; edge `k` is opposite vertex `k`.
    edges: [Edge; 3],
    /// The covered pixel box (clipped to the screen).
    span: PixelSpan,
}

impl BigTriangle {
    /// The edge functions of a triangle (clockwise on screen) whose non-empty
    /// screen box is `span`.
    #[inline]
    pub fn of(v: [&ScreenVertex; 3], span: PixelSpan) -> BigTriangle {
        let px = span.x0 as i64 * ONE + HALF;
        let py = span.y0 as i64 * ONE + HALF;
        let edges = [
            Edge::new(v[1], v[2], px, py),
            Edge::new(v[2], v[0], px, py),
            Edge::new(v[0], v[1], px, py),
        ];
        BigTriangle { edges, span }
    }

    /// The triangle set up for filling (positive [`signed_area`] `area`); its
    /// edge functions are pushed to `edges`.
    #[inline]
    pub fn triangle(&self, v: [&ScreenVertex; 3], area: i64, edges: &mut Vec<Edges>) -> Triangle {
        let lanes = |f: fn(&Edge) -> i64| {
            let e = &self.edges;
            Vec4::new(0.0, f(&e[1]) as f32, f(&e[2]) as f32, 0.0)
        };
        let weights = VertexWeights::from_edges(
            area as f32,
            lanes(|e| e.start),
            lanes(|e| e.step_x),
            lanes(|e| e.step_y),
        );
        let planes = Planes::from_weights(v, weights);
        edges.push(Edges(self.edges));
        Triangle {
            planes,
            span: self.span,
            coverage: Coverage::Edges(edges.len() as u32 - 1),
        }
    }
}

/// A triangle that covers a single pixel centre, kept as that pixel: 16 bytes
/// instead of a [`Triangle`]'s 80, its colour already converted to bytes.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Dot {
    /// Pixel column.
    x: i32,
    /// Pixel row.
    y: i32,
    /// `1/w` at the pixel centre.
    depth: f32,
    /// Display colour.
    rgba: [u8; 4],
}

impl Dot {
    /// The dot of a triangle with attribute planes `planes` over box `span`
    /// whose coverage `mask` (see [`Triangle::masked`]) has a single bit.
    #[inline]
    pub fn in_box(planes: &Planes, span: PixelSpan, mask: u64) -> Dot {
        let bit = mask.trailing_zeros() as i32;
        let (column, row) = (bit % 8, bit / 8);
        Dot::at((span.x0 + column, span.y0 + row), planes.at(column, row))
    }

    /// The dot at `pixel` with attributes `a` (`1/w`, colour / w).
    #[inline]
    fn at(pixel: (i32, i32), a: Vec4) -> Dot {
        Dot {
            x: pixel.0,
            y: pixel.1,
            depth: a.x,
            rgba: display_rgba(a),
        }
    }

    /// The dot's pixel row.
    #[inline]
    pub fn row(&self) -> i32 {
        self.y
    }

    /// Writes the pixel if it lies in the band and is nearer than what is there
    /// (the same test and value as filling its triangle).
    #[inline(always)]
    pub fn draw(&self, band: &mut Band<'_>) {
        if self.y < band.y0 || self.y >= band.y1 {
            return;
        }
        let k = (self.y - band.y0) as usize * band.width as usize + self.x as usize;
        if self.depth > band.depth[k] {
            band.depth[k] = self.depth;
            band.color[4 * k..4 * k + 4].copy_from_slice(&self.rgba);
        }
    }
}

impl Triangle {
    /// Calls `run` for every row in `rows` where the triangle covers pixel
    /// centres, with the covered columns (contiguous: the triangle is convex).
    #[inline(always)]
    pub fn for_each_run(
        &self,
        edges: &[Edges],
        rows: std::ops::Range<i32>,
        mut run: impl FnMut(Run),
    ) {
        let span = self.span;
        let y0 = span.y0.max(rows.start);
        let y1 = span.y1.min(rows.end - 1);
        let row = |y: i32, lo: i32, hi: i32| Run {
            y,
            x0: span.x0 + lo,
            x1: span.x0 + hi,
            start: self.planes.at(lo, y - span.y0),
            step: self.planes.step_x,
        };
        match self.coverage {
            Coverage::Mask(mask) => {
                for y in y0..=y1 {
                    let bits = (mask >> (8 * (y - span.y0))) as u8;
                    if bits != 0 {
                        let lo = bits.trailing_zeros() as i32;
                        let hi = 7 - bits.leading_zeros() as i32;
                        run(row(y, lo, hi));
                    }
                }
            }
            Coverage::Edges(k) => {
                let e = &edges[k as usize].0;
                let last = span.x1 - span.x0;
                // Wide boxes (thin slanted triangles such as grass blades) get each
                // row's covered run solved from the edge equations; narrow ones are
                // scanned for their first and last covered centre.
                let solve = last >= NARROW_MIN_WIDTH;
                for y in y0..=y1 {
                    let r = (y - span.y0) as i64;
                    let w = e.map(|e| e.start + r * e.step_y);
                    let (mut lo, mut hi) = (0, last);
                    if solve {
                        for (edge, &value) in e.iter().zip(&w) {
                            (lo, hi) = edge.covered_run(value, lo, hi);
                        }
                    } else {
                        let covered = |c: i32| {
                            e.iter()
                                .zip(&w)
                                .all(|(edge, &v)| v + c as i64 * edge.step_x >= 0)
                        };
                        while lo <= hi && !covered(lo) {
                            lo += 1;
                        }
                        while hi >= lo && !covered(hi) {
                            hi -= 1;
                        }
                    }
                    if lo <= hi {
                        run(row(y, lo, hi));
                    }
                }
            }
        }
    }

    /// Draws the triangle into the band: depth test `1/w` greater than stored,
    /// perspective-correct colour.
    #[inline(always)]
    pub fn draw(&self, edges: &[Edges], band: &mut Band<'_>) {
        let width = band.width as usize;
        let y0 = band.y0;
        let (depth, color) = (&mut *band.depth, &mut *band.color);
        self.for_each_run(edges, band.y0..band.y1, |run| {
            let first = (run.y - y0) as usize * width + run.x0 as usize;
            let end = first + (run.x1 - run.x0) as usize + 1;
            let pixels = depth[first..end]
                .iter_mut()
                .zip(color[4 * first..4 * end].chunks_exact_mut(4));
            for (c, (depth, color)) in pixels.enumerate() {
                let a = run.attributes(c);
                if a.x > *depth {
                    *depth = a.x;
                    color.copy_from_slice(&display_rgba(a));
                }
            }
        });
    }
}

/// The covered pixel centres of one row of a triangle, `x0..=x1` on row `y`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Run {
    /// The row.
    pub y: i32,
    /// First covered column.
    pub x0: i32,
    /// Last covered column.
    pub x1: i32,
    /// Attributes (`1/w`, colour / w) at the centre of pixel `(x0, y)`.
    start: Vec4,
    /// Attribute change per pixel to the right.
    step: Vec4,
}

impl Run {
    /// The attributes `c` pixels right of `x0`.
    #[inline]
    pub fn attributes(&self, c: usize) -> Vec4 {
        self.start + self.step * c as f32
    }
}

/// Bounding boxes at least this many pixels wide solve each row's covered run.
const NARROW_MIN_WIDTH: i32 = 6;

/// A display value in `[0, 1]` to 8 bits (rounded, clamped; NaN gives 0).
#[inline]
pub(crate) fn to_u8(v: f32) -> u8 {
    (v * 255.0 + 0.5).clamp(0.0, 255.0) as u8
}

/// The opaque RGBA8 pixel of interpolated attributes (`1/w`, colour / w), with
/// `1/w > 0`: per channel exactly [`to_u8`] of colour / w, in one vector.
///
/// The truncation to an integer avoids float-to-int casts: adding `2^23` to a
/// value in `[0, 255]` leaves its nearest integer in the low mantissa bits,
/// and one compare turns that rounding into the floor.
#[inline]
fn display_rgba(a: Vec4) -> [u8; 4] {
    const MANTISSA_ONE: f32 = (1u32 << (f32::MANTISSA_DIGITS - 1)) as f32;
    let v =
        (Vec4::new(a.y, a.z, a.w, a.x) / a.x * 255.0 + 0.5).clamp(Vec4::ZERO, Vec4::splat(255.0));
    let rounded = v + MANTISSA_ONE;
    let floor = Vec4::select((rounded - MANTISSA_ONE).cmpgt(v), rounded - 1.0, rounded);
    let [r, g, b, _] = floor.to_array().map(|c| c.to_bits() as u8);
    [r, g, b, 255]
}

#[cfg(test)]
mod tests {
    use glam::{Mat4, Vec2, Vec3, Vec4};

    use super::*;
    use crate::render::Camera;
    use crate::render::batch::{
        BAND_ROWS, ClipVertexList, CullMode, ScreenBatch, TriangleGroup, Viewport,
    };
    use crate::render::clip::ClipVertex;
    use crate::render::kernels::Kernels;
    use crate::render::project::ClipPositions;
    use crate::render::small_triangle::SmallTriangle;
    use crate::rng::SplitMix64;

    fn sv(x: f32, y: f32) -> ScreenVertex {
        ScreenVertex {
            x: (x * ONE as f32).round() as i32,
            y: (y * ONE as f32).round() as i32,
            inv_w: 1.0,
            color_w: Vec3::ZERO,
        }
    }

    /// A clockwise triangle with positive `area` set up as the batches do
    /// (small ones through [`SmallTriangle`], as a masked triangle even when
    /// they cover one centre), or always through [`BigTriangle`] with
    /// `big_only`; `None` when a small one covers no centre.
    fn set_up(
        v: [&ScreenVertex; 3],
        area: i64,
        span: PixelSpan,
        big_only: bool,
        edges: &mut Vec<Edges>,
    ) -> Option<Triangle> {
        match SmallTriangle::of(v, span).filter(|_| !big_only) {
            Some(small) => {
                let mask = small.coverage(span);
                (mask != 0).then(|| Triangle::masked(small.planes(v, area as f32), span, mask))
            }
            None => Some(BigTriangle::of(v, span).triangle(v, area, edges)),
        }
    }

    /// Coverage counts of a triangulated grid of points over a 64 x 64 screen.
    fn coverage(points: &[Vec2], n: usize, rng: &mut SplitMix64, big_only: bool) -> Vec<u32> {
        let mut count = vec![0u32; 64 * 64];
        let at = |c: usize, r: usize| sv(points[r * n + c].x, points[r * n + c].y);
        for r in 0..n - 1 {
            for c in 0..n - 1 {
                let (a, b, cc, d) = (at(c, r), at(c + 1, r), at(c, r + 1), at(c + 1, r + 1));
                let tris = if rng.next_f32() < 0.5 {
                    [[a, b, d], [a, d, cc]]
                } else {
                    [[a, b, cc], [b, d, cc]]
                };
                for mut t in tris {
                    let mut area = signed_area(&t[0], &t[1], &t[2]);
                    if area < 0 {
                        t.swap(1, 2);
                        area = -area;
                    }
                    let v = [&t[0], &t[1], &t[2]];
                    let mut edges = Vec::new();
                    let span = ScreenBox::of(v).span(64, 64);
                    if area == 0 || span.is_empty() {
                        continue;
                    }
                    let Some(tri) = set_up(v, area, span, big_only, &mut edges) else {
                        continue;
                    };
                    tri.for_each_run(&edges, 0..64, |run| {
                        for x in run.x0..=run.x1 {
                            count[(run.y * 64 + x) as usize] += 1;
                        }
                    });
                }
            }
        }
        count
    }

    #[test]
    fn shared_edges_draw_every_pixel_exactly_once() {
        let mut rng = SplitMix64::new(0x9e37_79b9_7f4a_7c15);
        // Vertices exactly on pixel centres (edges through centres: the fill rule
        // decides), then jittered sub-pixel vertices; big cells exercise the
        // edge walk with solved row runs, small ones the coverage masks.
        for (n, spacing, jitter) in [
            (5, 14.0, 0.0),
            (5, 14.0, 5.0),
            (9, 7.0, 0.0),
            (9, 7.0, 3.0),
            (17, 3.5, 0.0),
            (17, 3.5, 1.5),
        ] {
            let points: Vec<Vec2> = (0..n * n)
                .map(|k| {
                    let base =
                        Vec2::new((k % n) as f32, (k / n) as f32) * spacing + Vec2::splat(4.5);
                    let on_border = k % n == 0 || k / n == 0 || k % n == n - 1 || k / n == n - 1;
                    let j = if on_border { 0.0 } else { jitter };
                    base + Vec2::new(rng.next_f32() - 0.5, rng.next_f32() - 0.5) * j
                })
                .collect();
            // The batches' set-up (small triangles in lanes), then the general
            // edge walk for every triangle.
            for big_only in [false, true] {
                let count = coverage(&points, n, &mut rng, big_only);
                for y in 0..64usize {
                    for x in 0..64usize {
                        let c = count[y * 64 + x];
                        assert!(c <= 1, "pixel ({x}, {y}) drawn {c} times (jitter {jitter})");
                        // Centres strictly inside the outer square [4.5, 60.5]: exactly once.
                        let inside = (5..=59).contains(&x) && (5..=59).contains(&y);
                        if inside {
                            assert_eq!(c, 1, "pixel ({x}, {y}) missed (jitter {jitter})");
                        }
                    }
                }
            }
        }
    }

    /// Renders a batch into a fresh `w` x `h` colour and depth buffer, band by band.
    fn draw(batch: &ScreenBatch, w: i32, h: i32) -> (Vec<u8>, Vec<f32>) {
        let mut color = vec![0u8; (w * h * 4) as usize];
        let mut depth = vec![0f32; (w * h) as usize];
        let rows = BAND_ROWS as usize;
        let bands = color
            .chunks_mut(w as usize * 4 * rows)
            .zip(depth.chunks_mut(w as usize * rows));
        for (b, (color, depth)) in bands.enumerate() {
            let y0 = b as i32 * BAND_ROWS;
            let y1 = y0 + (depth.len() / w as usize) as i32;
            let mut band = Band {
                color,
                depth,
                width: w,
                y0,
                y1,
            };
            batch.draw_band(b as i32, &mut band);
        }
        (color, depth)
    }

    fn cv(p: Vec4, color: Vec3) -> ClipVertex {
        ClipVertex { pos: p, color }
    }

    fn build(verts: &[ClipVertex], tris: &[[u32; 3]], w: i32, h: i32) -> ScreenBatch {
        ScreenBatch::build(
            verts,
            &[TriangleGroup {
                triangles: tris,
                cull: CullMode::None,
                first_vertex: 0,
            }],
            Viewport {
                width: w,
                height: h,
            },
            Kernels::Dispatched,
        )
    }

    /// Small random triangles (many covering one centre) in clip space, some
    /// facing away, some off screen.
    fn small_triangles(rng: &mut SplitMix64, count: usize) -> (Vec<ClipVertex>, Vec<[u32; 3]>) {
        let mut verts = Vec::new();
        for _ in 0..count {
            let centre = Vec2::new(rng.next_f32() * 2.4 - 1.2, rng.next_f32() * 2.4 - 1.2);
            let size = 0.03 + 0.4 * rng.next_f32() * rng.next_f32();
            let w = 1.0 + 3.0 * rng.next_f32();
            for _ in 0..3 {
                let p = centre + Vec2::new(rng.next_f32() - 0.5, rng.next_f32() - 0.5) * size;
                let colour = Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32());
                verts.push(cv(Vec4::new(p.x * w, p.y * w, 0.5 * w, w), colour));
            }
        }
        let tris = (0..count as u32)
            .map(|t| [3 * t, 3 * t + 1, 3 * t + 2])
            .collect();
        (verts, tris)
    }

    #[test]
    fn dots_draw_exactly_what_their_triangles_draw() {
        let mut rng = SplitMix64::new(0x5851_f42d_4c95_7f2d);
        let (w, h) = (48, 40);
        let (verts, tris) = small_triangles(&mut rng, 3000);
        let batch = build(&verts, &tris, w, h);
        let (dots, tris_kept) = batch.kinds();
        assert!(
            dots > 300 && tris_kept > 300,
            "{dots} dots, {tris_kept} triangles"
        );
        let (color, depth) = draw(&batch, w, h);
        // Reference: every triangle set up and filled as a full triangle, in order.
        let vp = Viewport {
            width: w,
            height: h,
        };
        let screen: Vec<ScreenVertex> = verts.iter().map(|v| vp.project(v)).collect();
        let mut want_color = vec![0u8; (w * h * 4) as usize];
        let mut want_depth = vec![0f32; (w * h) as usize];
        let mut band = Band {
            color: &mut want_color,
            depth: &mut want_depth,
            width: w,
            y0: 0,
            y1: h,
        };
        let mut edges = Vec::new();
        let mut filled = 0;
        for tri in &tris {
            let [a, b, c] = tri.map(|k| &screen[k as usize]);
            let mut area = signed_area(a, b, c);
            let v = if area < 0 {
                area = -area;
                [a, c, b]
            } else {
                [a, b, c]
            };
            let span = ScreenBox::of(v).span(w, h);
            if area == 0 || span.is_empty() {
                continue;
            }
            // Reference: the general edge walk for every triangle.
            let tri = set_up(v, area, span, true, &mut edges).expect("big triangles are kept");
            tri.draw(&edges, &mut band);
            let small_covers = SmallTriangle::of(v, span).map(|s| s.coverage(span) != 0);
            if small_covers != Some(false) {
                filled += 1;
            }
        }
        assert_eq!(filled, batch.len());
        assert_eq!(color, want_color);
        assert_eq!(depth, want_depth);
    }

    #[test]
    fn shaded_batches_draw_like_eager_ones() {
        let mut rng = SplitMix64::new(0x1405_7b7e_f767_814f);
        let (w, h) = (40, 32);
        // 2001 triangles: a vertex count that leaves a remainder of lanes.
        let (verts, tris) = small_triangles(&mut rng, 2001);
        let group = [TriangleGroup {
            triangles: &tris,
            cull: CullMode::Back,
            first_vertex: 0,
        }];
        let vp = Viewport {
            width: w,
            height: h,
        };
        let clip: Vec<Vec4> = verts.iter().map(|v| v.pos).collect();
        let eager = ScreenBatch::build(&verts, &group, vp, Kernels::Baseline);
        // One batch rebuilt for both: nothing of the first build may remain.
        let mut shaded = ScreenBatch::default();
        for kernels in [Kernels::Baseline, Kernels::Dispatched] {
            shaded.rebuild_shaded(
                ClipPositions(&clip),
                ClipVertexList(&verts),
                &group,
                vp,
                kernels,
            );
            assert!(shaded.len() > 50);
            assert_eq!(shaded.len(), eager.len());
            assert_eq!(draw(&shaded, w, h), draw(&eager, w, h), "{kernels:?}");
        }
    }

    #[test]
    fn display_rgba_rounds_like_to_u8() {
        let mut rng = SplitMix64::new(0x2545_f491_4f6c_dd1d);
        let edges = [0.0, 0.5 / 255.0, 1.0, 1.0 + 1e-3, -1e-3, 127.5 / 255.0];
        for k in 0..20_000 {
            let c = if k < edges.len() * 3 {
                Vec3::new(edges[k % 6], edges[k / 3 % 6], edges[k / 6 % 6])
            } else {
                Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * 1.2 - 0.1
            };
            let inv_w = 0.05 + rng.next_f32() * 4.0;
            let a = Vec4::new(inv_w, c.x * inv_w, c.y * inv_w, c.z * inv_w);
            let d = Vec3::new(a.y, a.z, a.w) / a.x;
            assert_eq!(
                display_rgba(a),
                [to_u8(d.x), to_u8(d.y), to_u8(d.z), 255],
                "{c}"
            );
        }
    }

    #[test]
    fn nearer_triangle_wins_in_either_order() {
        let near = |c| {
            [
                cv(Vec4::new(-0.8, -0.8, 0.5, 1.0), c),
                cv(Vec4::new(0.8, -0.8, 0.5, 1.0), c),
                cv(Vec4::new(0.0, 0.8, 0.5, 1.0), c),
            ]
        };
        // The far triangle has w = 2 (half the 1/w depth), scaled to cover the same area.
        let far = |c| {
            [
                cv(Vec4::new(-2.0, -2.0, 1.0, 2.0), c),
                cv(Vec4::new(2.0, -2.0, 1.0, 2.0), c),
                cv(Vec4::new(0.0, 2.0, 1.0, 2.0), c),
            ]
        };
        let (red, blue) = (Vec3::X, Vec3::Z);
        for near_first in [true, false] {
            let mut verts = Vec::new();
            if near_first {
                verts.extend(near(red));
                verts.extend(far(blue));
            } else {
                verts.extend(far(blue));
                verts.extend(near(red));
            }
            let batch = build(&verts, &[[0, 1, 2], [3, 4, 5]], 32, 32);
            let (color, _) = draw(&batch, 32, 32);
            let centre = 4 * (16 * 32 + 16);
            assert_eq!(&color[centre..centre + 4], &[255, 0, 0, 255]);
        }
    }

    #[test]
    fn interpolation_is_perspective_correct() {
        // A floor quad receding from the camera, coloured by its world z.
        let cam = Camera::perspective(1.2, 64, 64, 0.1, 100.0)
            .unwrap()
            .look_at(Vec3::new(0.0, 1.0, 0.0), Vec3::new(0.0, 0.0, -4.0), Vec3::Y);
        let vp_m: Mat4 = cam.view_proj();
        let (z_near, z_far) = (-1.0f32, -9.0f32);
        let colour = |z: f32| Vec3::splat((z - z_near) / (z_far - z_near));
        let corners = [(-3.0, z_near), (3.0, z_near), (3.0, z_far), (-3.0, z_far)];
        let verts: Vec<ClipVertex> = corners
            .iter()
            .map(|&(x, z)| cv(vp_m * Vec4::new(x, 0.0, z, 1.0), colour(z)))
            .collect();
        let batch = build(&verts, &[[0, 1, 2], [0, 2, 3]], 64, 64);
        let (color, depth) = draw(&batch, 64, 64);
        let inv = vp_m.inverse();
        let mut checked = 0;
        for y in 0..64 {
            for x in 0..64 {
                let k = y * 64 + x;
                if depth[k] == 0.0 {
                    continue;
                }
                // Analytic reference: intersect the pixel's ray with the floor y = 0.
                let ndc = Vec2::new((x as f32 + 0.5) / 32.0 - 1.0, 1.0 - (y as f32 + 0.5) / 32.0);
                let a = inv.project_point3(ndc.extend(0.0));
                let b = inv.project_point3(ndc.extend(1.0));
                let t = a.y / (a.y - b.y);
                let z = a.z + (b.z - a.z) * t;
                let want = colour(z).x * 255.0;
                let got = color[4 * k] as f32;
                assert!(
                    (got - want).abs() <= 1.5,
                    "pixel ({x}, {y}): {got} vs {want}"
                );
                checked += 1;
            }
        }
        assert!(checked > 500);
    }

    #[test]
    fn near_plane_clipping_keeps_what_is_in_front() {
        // A huge floor that passes under and behind the camera.
        let cam = Camera::perspective(1.0, 48, 32, 0.1, 100.0)
            .unwrap()
            .look_at(Vec3::new(0.0, 1.0, 0.0), Vec3::new(0.0, 1.0, -1.0), Vec3::Y);
        let m = cam.view_proj();
        let corners = [(-50.0, 50.0), (50.0, 50.0), (50.0, -50.0), (-50.0, -50.0)];
        let verts: Vec<ClipVertex> = corners
            .iter()
            .map(|&(x, z)| cv(m * Vec4::new(x, 0.0, z, 1.0), Vec3::ONE))
            .collect();
        let batch = build(&verts, &[[0, 1, 2], [0, 2, 3]], 48, 32);
        // Clipping turns the two triangles into polygons of up to 8 vertices.
        assert!(batch.len() > 2, "the floor must have been clipped");
        let (_, depth) = draw(&batch, 48, 32);
        // Looking level: the floor fills the lower half, up to the horizon (far
        // edge 50 m away sits just below it), and nothing above.
        for y in 0..32 {
            let covered = (0..48).filter(|&x| depth[y * 48 + x] > 0.0).count();
            if y < 16 {
                assert_eq!(covered, 0, "row {y} is above the horizon");
            } else if y > 16 {
                assert_eq!(covered, 48, "row {y} is floor");
            }
        }
    }
}
