//! Per-vertex pixel-centre boxes: the first and last pixel-centre column and
//! row at or beyond each vertex, kept in the lanes of one `f32` vector, so that
//! a triangle's pixel span is the lane-wise minimum of its three vertices'
//! boxes (two vector minimums) instead of a fixed-point box, four roundings and
//! four clamps per triangle.
//!
//! The box of a vertex at fixed-point `(x, y)` holds
//! `(first_centre(x), -last_centre(x), first_centre(y), -last_centre(y))`:
//! both roundings are monotonic, so the first centre of a triangle's box is
//! the smallest of its vertices' first centres and its last centre is the
//! largest of their last centres (the smallest negated). Pixel indices of
//! 16.8 fixed-point `i32` coordinates are below `2^24`: exact in `f32`.

use glam::{Vec4, Vec4Swizzles};

use super::raster::{PixelSpan, ScreenVertex, first_centre, last_centre};

/// The centre box of one vertex (see the module documentation). Coordinates
/// are clamped far outside the guard band first (where they only belong to
/// vertices that are clipped, whose boxes are not used), so that the
/// roundings cannot overflow.
#[inline]
pub(crate) fn centre_box(v: &ScreenVertex) -> Vec4 {
    const FAR: i32 = 1 << 30;
    let (x, y) = (v.x.clamp(-FAR, FAR), v.y.clamp(-FAR, FAR));
    Vec4::new(
        first_centre(x) as f32,
        -(last_centre(x) as f32),
        first_centre(y) as f32,
        -(last_centre(y) as f32),
    )
}

/// The screen's limits in centre-box lanes: the first column and row (0) and
/// the last ones, negated.
#[inline]
pub(crate) fn screen_limits(width: i32, height: i32) -> Vec4 {
    Vec4::new(0.0, (1 - width) as f32, 0.0, (1 - height) as f32)
}

/// The pixel span of a triangle whose vertices have centre boxes `a`, `b` and
/// `c`, clipped to the screen of `limits` ([`screen_limits`]), or `None` when
/// no pixel centre lies in it: the same span as
/// [`super::raster::ScreenBox::span`] of the vertices' box.
#[inline(always)]
pub(crate) fn triangle_span(a: Vec4, b: Vec4, c: Vec4, limits: Vec4) -> Option<PixelSpan> {
    let lanes = SpanLanes::of(a, b, c, limits);
    (!lanes.is_empty()).then(|| lanes.span())
}

/// A triangle's pixel span in centre-box lanes, `(x0, -x1, y0, -y1)`, clipped
/// to the screen: [`triangle_span`] in two steps, so that the emptiness test
/// can feed a branch-free selection.
#[derive(Debug, Clone, Copy)]
pub(crate) struct SpanLanes(Vec4);

impl SpanLanes {
    /// A span with no pixel centre.
    pub const EMPTY: SpanLanes = SpanLanes(Vec4::new(1.0, 0.0, 1.0, 0.0));

    /// The lanes `(x0, -x1, y0, -y1)`.
    #[inline(always)]
    pub fn lanes(self) -> Vec4 {
        self.0
    }

    /// The span lanes of a triangle whose vertices have centre boxes `a`,
    /// `b` and `c`, clipped to the screen of `limits` ([`screen_limits`]).
    #[inline(always)]
    pub fn of(a: Vec4, b: Vec4, c: Vec4, limits: Vec4) -> SpanLanes {
        SpanLanes(a.min(b).min(c).max(limits))
    }

    /// Whether no pixel centre lies in the span: x0 > x1 or y0 > y1, that is
    /// x0 + (-x1) > 0 in lane 0, y in lane 2.
    #[inline(always)]
    pub fn is_empty(self) -> bool {
        let lanes = self.0;
        (lanes + lanes.yxwz()).cmpgt(Vec4::ZERO).bitmask() & 0b0101 != 0
    }

    /// The span (only meaningful when not [`SpanLanes::is_empty`]).
    #[inline(always)]
    pub fn span(self) -> PixelSpan {
        let [x0, x1, y0, y1] = whole_numbers(self.0);
        PixelSpan {
            x0,
            x1: -x1,
            y0,
            y1: -y1,
        }
    }
}

/// `1.5 * 2^23`: a whole number `t` with `|t| < 2^22` added to it gives a
/// float whose bits are `MAGIC.to_bits() + t`.
pub(crate) const MAGIC: f32 = 12_582_912.0;

/// Largest magnitude [`whole_numbers`] converts.
pub(crate) const WHOLE_MAX: f32 = (1 << 22) as f32;

/// The whole numbers in `v` (each of magnitude below [`WHOLE_MAX`]) as
/// integers, read from the bits of their sums with [`MAGIC`]: the vector form
/// of `as i32` for values that need no rounding nor saturation.
#[inline(always)]
pub(crate) fn whole_numbers(v: Vec4) -> [i32; 4] {
    let bits = (v + MAGIC).to_array().map(f32::to_bits);
    bits.map(|b| b.wrapping_sub(MAGIC.to_bits()) as i32)
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::*;
    use crate::render::raster::ScreenBox;
    use crate::rng::SplitMix64;

    #[test]
    fn lane_spans_equal_the_fixed_point_box_spans() {
        let mut rng = SplitMix64::new(0x1319_8a2e_0370_7344);
        let (width, height) = (64, 48);
        let limits = screen_limits(width, height);
        let mut outcomes = [0usize; 2];
        for k in 0..30_000 {
            let size = if k % 2 == 0 { 4.0 } else { 100.0 };
            let centre = (rng.range(-4.0, 68.0), rng.range(-4.0, 52.0));
            let mut vertex = || {
                let mut x = ((centre.0 + rng.around(0.0, size)) * 256.0) as i32;
                let mut y = ((centre.1 + rng.around(0.0, size)) * 256.0) as i32;
                // Exact pixel centres and pixel edges.
                if rng.next_u64().is_multiple_of(4) {
                    x = (x >> 7) << 7;
                    y = (y >> 7) << 7;
                }
                ScreenVertex {
                    x,
                    y,
                    inv_w: 1.0,
                    color_w: Vec3::ZERO,
                }
            };
            let v = [vertex(), vertex(), vertex()];
            let expected = ScreenBox::of([&v[0], &v[1], &v[2]]).span(width, height);
            let got = triangle_span(
                centre_box(&v[0]),
                centre_box(&v[1]),
                centre_box(&v[2]),
                limits,
            );
            match got {
                Some(span) => assert_eq!(span, expected, "{v:?}"),
                None => assert!(expected.is_empty(), "{v:?}"),
            }
            outcomes[usize::from(got.is_some())] += 1;
        }
        assert!(outcomes.iter().all(|&n| n > 3000), "{outcomes:?}");
    }

    #[test]
    fn whole_numbers_are_exact_up_to_the_limit() {
        let m = WHOLE_MAX as i32 - 1;
        for v in [0, 1, -1, 127, -128, m, -m, 12_345, -54_321] {
            assert_eq!(whole_numbers(Vec4::splat(v as f32)), [v; 4]);
        }
        assert_eq!(
            whole_numbers(Vec4::new(-0.0, 0.0, 2.0, -3.0)),
            [0, 0, 2, -3]
        );
    }
}
