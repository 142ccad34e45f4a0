//! Set-up of small triangles (the common case for dense meshes: boxes of a few
//! pixels) with their three edge functions in the lanes of one `f32` vector.
//!
//! Inside a small triangle's box every edge value at a pixel centre is an
//! integer below `2^24` in magnitude (see [`MASK_EXTENT`]), so `f32` lanes hold
//! the edge functions exactly: the coverage, the top-left rule and the
//! attribute planes are the same as the general `i64` set-up's, in a few
//! vector operations instead of three scalar edges.

use glam::{BVec4A, Vec4, Vec4Swizzles};

use super::batch::CullMode;
use super::raster::{
    HALF, MASK_EXTENT, MASK_SIDE, ONE, PixelSpan, Planes, ScreenVertex, VertexWeights,
};

/// Boxes at most this many centres wide ...
pub(crate) const WINDOW_COLUMNS: u32 = 4;
/// ... and this many tall test a fixed window of centres.
pub(crate) const WINDOW_ROWS: u32 = 2;

/// Other boxes of at most this many pixel centres test them one by one.
const CENTRE_BY_CENTRE_MAX: u32 = 4;

/// Edge functions in `f32` lanes, every lane on its own: the value at the
/// box's first centre with the top-left bias (covered when `>= 0`), then the
/// change per pixel right and per pixel down, of edges (clockwise on screen)
/// that change by `dx`, `dy` along themselves and have the values
/// `edge_values` at that centre. The lanes hold the three edges of one
/// triangle ([`SmallTriangle`]) or one edge of four triangles
/// ([`super::four_small_triangles`]).
#[inline(always)]
pub(crate) fn edge_lanes(edge_values: Vec4, dx: Vec4, dy: Vec4) -> [Vec4; 3] {
    // Pixels exactly on an edge belong to it only when it is a top edge
    // (horizontal, going right) or a left edge (going up).
    let top_left: BVec4A = dy.cmplt(Vec4::ZERO) | (dy.cmpeq(Vec4::ZERO) & dx.cmpgt(Vec4::ZERO));
    let bias = Vec4::select(top_left, Vec4::ZERO, Vec4::NEG_ONE);
    let one = ONE as f32;
    [
        edge_values + bias,
        // Subtracted from zero, not negated, so a zero step is +0 as in integers.
        Vec4::ZERO - dy * one,
        dx * one,
    ]
}

/// Whether a box of `columns` x `rows` pixel centres fits the fixed window
/// ([`WINDOW_COLUMNS`] x [`WINDOW_ROWS`]) whose coverage is tested whole.
#[inline(always)]
pub(crate) fn fits_window(columns: u32, rows: u32) -> bool {
    columns <= WINDOW_COLUMNS && rows <= WINDOW_ROWS
}

/// The three edge functions of a small triangle (clockwise on screen), edge `k`
/// (opposite vertex `k`) in lane `k`; lane 3 is unused.
#[derive(Debug, Clone, Copy)]
pub(crate) struct SmallTriangle {
    /// Edge values at the box's first pixel centre, top-left bias included:
    /// a centre is covered when all three are `>= 0`.
    start: Vec4,
    /// Change per pixel to the right.
    step_x: Vec4,
    /// Change per pixel down.
    step_y: Vec4,
}

/// What the small set-up makes of a submitted triangle.
#[derive(Debug, Clone, Copy)]
pub(crate) enum SmallSetUp<'v> {
    /// The box or the triangle is too big for exact `f32` edges: the general
    /// set-up applies.
    TooBig,
    /// Zero area, or a back face that its cull mode drops.
    Dropped,
    /// A triangle to draw.
    Kept {
        /// The vertices, clockwise on screen.
        vertices: [&'v ScreenVertex; 3],
        /// Twice the area in fixed point squared (positive, exact).
        area: f32,
        /// The edge functions of `vertices`.
        triangle: SmallTriangle,
    },
}

impl SmallTriangle {
    /// Culls, orients and sets up the triangle `v` (in submitted order) over
    /// its non-empty pixel box `span`, all in `f32` lanes: its signed area is
    /// a cross product of two edge lanes (exact below `2^24`, see
    /// [`MASK_EXTENT`]), and turning it clockwise negates and swaps lanes
    /// instead of building them again.
    #[inline(always)]
    pub fn set_up<'v>(v: [&'v ScreenVertex; 3], span: PixelSpan, cull: CullMode) -> SmallSetUp<'v> {
        if span.x1 - span.x0 >= MASK_SIDE || span.y1 - span.y0 >= MASK_SIDE {
            return SmallSetUp::TooBig;
        }
        // Vertices relative to the first centre, which lies inside the
        // vertices' box. The coordinates of a triangle that reaches here lie
        // within the guard band, below `2^24`: exact in `f32`, and so are
        // their offsets below MASK_EXTENT (a vertex converted inexactly lies
        // far beyond it).
        let px = (span.x0 * ONE as i32 + HALF as i32) as f32;
        let py = (span.y0 * ONE as i32 + HALF as i32) as f32;
        // Lane k holds the first vertex of edge k (opposite vertex k): k + 1 (mod 3).
        let x = Vec4::new(v[1].x as f32, v[2].x as f32, v[0].x as f32, px) - Vec4::splat(px);
        let y = Vec4::new(v[1].y as f32, v[2].y as f32, v[0].y as f32, py) - Vec4::splat(py);
        let dx = x.yzxw() - x;
        let dy = y.yzxw() - y;
        // A triangle's extent per axis is the largest of its edges' (lane 3
        // is zero). A larger extent cannot round below MASK_EXTENT.
        let extent = dx.abs().max(dy.abs());
        if extent.cmpge(Vec4::splat(MASK_EXTENT as f32)).any() {
            return SmallSetUp::TooBig;
        }
        // E(p) = dx (py - ay) - dy (px - ax) at p = the first centre.
        let edge_values = dy * x - dx * y;
        // signed_area(v0, v1, v2) from edges 2 (v0 to v1) and 1 (v2 to v0).
        let area = dy.z * dx.y - dx.z * dy.y;
        // Counter-clockwise in the world, seen from the front, projects to a
        // negative area on the y-down screen (the rule of `batch::clockwise`
        // for big triangles).
        if area < 0.0 {
            // Clockwise order v0, v2, v1: each edge reverses (values and
            // steps negate) and edges 1 and 2 trade places. Subtracted from
            // zero, not negated, so that zeros stay +0 as the integers'.
            let turn = |lanes: Vec4| Vec4::ZERO - lanes.xzyw();
            SmallSetUp::Kept {
                vertices: [v[0], v[2], v[1]],
                area: -area,
                triangle: SmallTriangle::from_edges(turn(edge_values), turn(dx), turn(dy)),
            }
        } else if area > 0.0 && cull == CullMode::None {
            SmallSetUp::Kept {
                vertices: v,
                area,
                triangle: SmallTriangle::from_edges(edge_values, dx, dy),
            }
        } else {
            SmallSetUp::Dropped
        }
    }

    /// The edge functions of a clockwise triangle whose edges (lane `k`
    /// opposite vertex `k`) change by `dx`, `dy` along themselves and have
    /// the values `edge_values` at the box's first centre.
    #[inline(always)]
    fn from_edges(edge_values: Vec4, dx: Vec4, dy: Vec4) -> SmallTriangle {
        let [start, step_x, step_y] = edge_lanes(edge_values, dx, dy);
        SmallTriangle {
            start,
            step_x,
            step_y,
        }
    }

    /// The edge functions of the triangle `v`, already clockwise on screen,
    /// over its non-empty pixel box `span`, or `None` when the box or the
    /// triangle is too big for exact `f32` edges.
    #[cfg(test)]
    pub fn of(v: [&ScreenVertex; 3], span: PixelSpan) -> Option<SmallTriangle> {
        match SmallTriangle::set_up(v, span, CullMode::None) {
            SmallSetUp::Kept { triangle, .. } => Some(triangle),
            SmallSetUp::TooBig | SmallSetUp::Dropped => None,
        }
    }

    /// Bit `8 * row + column` (relative to the box corner) per pixel centre of
    /// `span` (the box given to [`SmallTriangle::set_up`]) that the triangle covers.
    #[inline(always)]
    pub fn coverage(&self, span: PixelSpan) -> u64 {
        let (columns, rows) = span.size();
        if fits_window(columns, rows) {
            self.coverage_in_window(columns, rows)
        } else if columns * rows <= CENTRE_BY_CENTRE_MAX {
            self.coverage_by_centre(columns, rows)
        } else {
            self.coverage_by_row(columns, rows)
        }
    }

    /// [`SmallTriangle::coverage`] of a box of at most [`WINDOW_COLUMNS`] x
    /// [`WINDOW_ROWS`] centres: the whole window is tested, with no branch
    /// and no loop whose length depends on the box (dense meshes give boxes
    /// of one to four columns and one or two rows in a data-random order, so
    /// such branches mispredict), and the centres outside the box are masked
    /// off.
    #[inline(always)]
    fn coverage_in_window(&self, columns: u32, rows: u32) -> u64 {
        const COLUMN: Vec4 = Vec4::new(0.0, 1.0, 2.0, 3.0);
        let edge = |start: f32, step_x: f32, step_y: f32| {
            let first = Vec4::splat(start) + Vec4::splat(step_x) * COLUMN;
            (first, first + Vec4::splat(step_y))
        };
        let (a0, a1) = edge(self.start.x, self.step_x.x, self.step_y.x);
        let (b0, b1) = edge(self.start.y, self.step_x.y, self.step_y.y);
        let (c0, c1) = edge(self.start.z, self.step_x.z, self.step_y.z);
        let first_row = a0.min(b0).min(c0).cmpge(Vec4::ZERO).bitmask();
        let second_row = a1.min(b1).min(c1).cmpge(Vec4::ZERO).bitmask();
        let row_bits = (1u32 << columns) - 1;
        // Rows are one or two: the second row's bits count only for two.
        let in_box = row_bits | ((row_bits << 8) * (rows - 1));
        u64::from((first_row | (second_row << 8)) & in_box)
    }

    /// [`SmallTriangle::coverage`] testing one centre at a time, its three edge
    /// values in one vector: cheapest for boxes of a few centres.
    #[inline(always)]
    fn coverage_by_centre(&self, columns: u32, rows: u32) -> u64 {
        let mut mask = 0u64;
        let mut row = self.start;
        for r in 0..rows {
            let mut e = row;
            for c in 0..columns {
                let inside = e.cmpge(Vec4::ZERO).bitmask() & 7 == 7;
                mask |= u64::from(inside) << (8 * r + c);
                e += self.step_x;
            }
            row += self.step_y;
        }
        mask
    }

    /// [`SmallTriangle::coverage`] testing a row of up to eight centres at a
    /// time, one edge's values per vector (lanes past the box are masked off).
    #[inline(always)]
    fn coverage_by_row(&self, columns: u32, rows: u32) -> u64 {
        const LEFT: Vec4 = Vec4::new(0.0, 1.0, 2.0, 3.0);
        const RIGHT: Vec4 = Vec4::new(4.0, 5.0, 6.0, 7.0);
        let lane = |v: Vec4| [Vec4::splat(v.x), Vec4::splat(v.y), Vec4::splat(v.z)];
        let (step_x, step_y) = (lane(self.step_x), lane(self.step_y));
        let mut row = lane(self.start);
        let left = step_x.map(|s| s * LEFT);
        let right = step_x.map(|s| s * RIGHT);
        let values = |half: &[Vec4; 3], row: &[Vec4; 3]| {
            (half[0] + row[0])
                .min(half[1] + row[1])
                .min(half[2] + row[2])
        };
        let wide = columns > 4;
        let in_box = (1u32 << columns) - 1;
        let mut mask = 0u64;
        for r in 0..rows {
            let mut bits = values(&left, &row).cmpge(Vec4::ZERO).bitmask();
            if wide {
                bits |= values(&right, &row).cmpge(Vec4::ZERO).bitmask() << 4;
            }
            mask |= u64::from(bits & in_box) << (8 * r);
            for (value, step) in row.iter_mut().zip(step_y) {
                *value += step;
            }
        }
        mask
    }

    /// The attribute planes of the triangle `v` (the clockwise vertices it
    /// was set up from, with positive doubled area `area`).
    #[inline(always)]
    pub fn planes(&self, v: [&ScreenVertex; 3], area: f32) -> Planes {
        Planes::from_weights(v, self.weights(area))
    }

    /// The weights of the vertices 1 and 2 of the triangle set up with
    /// positive doubled area `area`.
    #[inline(always)]
    pub fn weights(&self, area: f32) -> VertexWeights {
        VertexWeights::from_edges(area, self.start, self.step_x, self.step_y)
    }
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::*;
    use crate::render::raster::{BigTriangle, ScreenBox, signed_area};
    use crate::rng::SplitMix64;

    #[test]
    fn both_coverage_tests_agree_with_the_general_edge_walk() {
        let mut rng = SplitMix64::new(0x6a09_e667_f3bc_c908);
        let mut tested = [0usize; 3];
        for _ in 0..20_000 {
            let centre = (rng.next_f32() * 40.0, rng.next_f32() * 40.0);
            let size = 0.2 + 9.0 * rng.next_f32() * rng.next_f32();
            let mut vertex = || ScreenVertex {
                x: ((centre.0 + (rng.next_f32() - 0.5) * size) * ONE as f32) as i32,
                y: ((centre.1 + (rng.next_f32() - 0.5) * size) * ONE as f32) as i32,
                inv_w: 1.0,
                color_w: Vec3::ZERO,
            };
            let (a, b, c) = (vertex(), vertex(), vertex());
            let (v, area) = match signed_area(&a, &b, &c) {
                0 => continue,
                area if area < 0 => ([&a, &c, &b], -area),
                area => ([&a, &b, &c], area),
            };
            let span = ScreenBox::of(v).span(48, 48);
            if span.is_empty() {
                continue;
            }
            let Some(small) = SmallTriangle::of(v, span) else {
                continue;
            };
            // Set up in the submitted order, turned clockwise in lanes: the
            // same bits as set up clockwise; culled by the submitted winding.
            let submitted = [&a, &b, &c];
            let clockwise_first = signed_area(&a, &b, &c) > 0;
            for cull in [CullMode::None, CullMode::Back] {
                match SmallTriangle::set_up(submitted, span, cull) {
                    SmallSetUp::Kept {
                        vertices,
                        area: kept_area,
                        triangle,
                    } => {
                        assert!(cull == CullMode::None || !clockwise_first);
                        assert_eq!(vertices, v);
                        assert_eq!(kept_area, area as f32);
                        let bits = |t: &SmallTriangle| {
                            [t.start, t.step_x, t.step_y].map(|l| l.to_array().map(f32::to_bits))
                        };
                        assert_eq!(bits(&triangle), bits(&small));
                    }
                    SmallSetUp::Dropped => assert!(cull == CullMode::Back && clockwise_first),
                    SmallSetUp::TooBig => panic!("{span:?} fits the small set-up"),
                }
            }
            let (columns, rows) = span.size();
            let by_centre = small.coverage_by_centre(columns, rows);
            assert_eq!(by_centre, small.coverage_by_row(columns, rows));
            if fits_window(columns, rows) {
                assert_eq!(by_centre, small.coverage_in_window(columns, rows));
                tested[2] += 1;
            }
            // The general set-up: i64 edges, walked row by row.
            let mut edges = Vec::new();
            let mut walked = 0u64;
            BigTriangle::of(v, span)
                .triangle(v, area, &mut edges)
                .for_each_run(&edges, 0..48, |run| {
                    for x in run.x0..=run.x1 {
                        walked |= 1 << (8 * (run.y - span.y0) + x - span.x0);
                    }
                });
            assert_eq!(by_centre, walked, "{span:?}");
            tested[usize::from(columns * rows > CENTRE_BY_CENTRE_MAX)] += 1;
        }
        assert!(tested.iter().all(|&n| n > 1000), "{tested:?}");
    }
}
