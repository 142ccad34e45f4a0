//! Set-up of small triangles (the common case for dense meshes: boxes of a few
//! pixels) with their three edge functions in the lanes of one `f32` vector.
//!
//! Inside a small triangle's box every edge value at a pixel centre is an
//! integer below `2^24` in magnitude (see [`MASK_EXTENT`]), so `f32` lanes hold
//! the edge functions exactly: the coverage, the top-left rule and the
//! attribute planes are the same as the general `i64` set-up's, in a few
//! vector operations instead of three scalar edges.

use glam::{BVec4A, Vec4, Vec4Swizzles};

use super::raster::{HALF, MASK_EXTENT, MASK_SIDE, ONE, PixelSpan, Planes, ScreenVertex};

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

impl SmallTriangle {
    /// The edge functions of the triangle `v` (clockwise on screen) over its
    /// non-empty pixel box `span`, or `None` when the box or the triangle is too
    /// big for exact `f32` edges (then the general set-up applies).
    #[inline(always)]
    pub fn of(v: [&ScreenVertex; 3], span: PixelSpan) -> Option<SmallTriangle> {
        if span.x1 - span.x0 >= MASK_SIDE || span.y1 - span.y0 >= MASK_SIDE {
            return None;
        }
        let extent = |a: i32, b: i32, c: i32| a.max(b).max(c) - a.min(b).min(c);
        if extent(v[0].x, v[1].x, v[2].x) >= MASK_EXTENT
            || extent(v[0].y, v[1].y, v[2].y) >= MASK_EXTENT
        {
            return None;
        }
        // Vertices relative to the first centre, which lies inside the
        // vertices' box: offsets below MASK_EXTENT, exact in `f32`.
        let px = span.x0 * ONE as i32 + HALF as i32;
        let py = span.y0 * ONE as i32 + HALF as i32;
        // Lane k holds the edge's first vertex, k + 1 (mod 3).
        let x = Vec4::new(
            (v[1].x - px) as f32,
            (v[2].x - px) as f32,
            (v[0].x - px) as f32,
            0.0,
        );
        let y = Vec4::new(
            (v[1].y - py) as f32,
            (v[2].y - py) as f32,
            (v[0].y - py) as f32,
            0.0,
        );
        let dx = x.yzxw() - x;
        let dy = y.yzxw() - y;
        // Pixels exactly on an edge belong to it only when it is a top edge
        // (horizontal, going right) or a left edge (going up).
        let top_left: BVec4A = dy.cmplt(Vec4::ZERO) | (dy.cmpeq(Vec4::ZERO) & dx.cmpgt(Vec4::ZERO));
        let bias = Vec4::select(top_left, Vec4::ZERO, Vec4::NEG_ONE);
        let one = ONE as f32;
        Some(SmallTriangle {
            // E(p) = dx (py - ay) - dy (px - ax) at p = the first centre.
            start: dy * x - dx * y + bias,
            // Subtracted from zero, not negated, so a zero step is +0 as in integers.
            step_x: Vec4::ZERO - dy * one,
            step_y: dx * one,
        })
    }

    /// Bit `8 * row + column` (relative to the box corner) per pixel centre of
    /// `span` (the box given to [`SmallTriangle::of`]) that the triangle covers.
    #[inline(always)]
    pub fn coverage(&self, span: PixelSpan) -> u64 {
        let (columns, rows) = (
            (span.x1 - span.x0 + 1) as u32,
            (span.y1 - span.y0 + 1) as u32,
        );
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

    /// The attribute planes of the triangle `v` (the vertices given to
    /// [`SmallTriangle::of`], with positive doubled area `area`).
    #[inline(always)]
    pub fn planes(&self, v: [&ScreenVertex; 3], area: i64) -> Planes {
        Planes::from_edge_weights(v, area, self.start, self.step_x, self.step_y)
    }
}
