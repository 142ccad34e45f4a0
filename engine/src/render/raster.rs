//! The triangle rasterizer: integer edge functions with 8 sub-pixel bits, the
//! top-left fill rule, a `1/w` depth buffer and perspective-correct colours.

use glam::Vec3;

/// Sub-pixel bits of screen coordinates (16.8 fixed point, as D3D11).
pub(crate) const SUBPIXEL_BITS: u32 = 8;
/// One pixel in fixed point.
pub(crate) const ONE: i64 = 1 << SUBPIXEL_BITS;
const HALF: i64 = ONE / 2;

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

/// The pixel range a triangle's bounding box covers: first/last pixel columns
/// and rows whose centres lie inside the box (may be empty: first > last).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct PixelSpan {
    pub x0: i32,
    pub x1: i32,
    pub y0: i32,
    pub y1: i32,
}

/// First pixel index whose centre is at or after fixed coordinate `v`.
#[inline]
fn first_centre(v: i64) -> i64 {
    (v - HALF + ONE - 1).div_euclid(ONE)
}

/// Last pixel index whose centre is at or before fixed coordinate `v`.
#[inline]
fn last_centre(v: i64) -> i64 {
    (v - HALF).div_euclid(ONE)
}

impl PixelSpan {
    /// The span of pixel centres inside the bounding box of `v`, clipped to a
    /// `width` x `height` screen.
    #[inline]
    pub fn of(v: [&ScreenVertex; 3], width: i32, height: i32) -> PixelSpan {
        let min_x = v[0].x.min(v[1].x).min(v[2].x) as i64;
        let max_x = v[0].x.max(v[1].x).max(v[2].x) as i64;
        let min_y = v[0].y.min(v[1].y).min(v[2].y) as i64;
        let max_y = v[0].y.max(v[1].y).max(v[2].y) as i64;
        PixelSpan {
            x0: first_centre(min_x).max(0) as i32,
            x1: last_centre(max_x).min(width as i64 - 1) as i32,
            y0: first_centre(min_y).max(0) as i32,
            y1: last_centre(max_y).min(height as i64 - 1) as i32,
        }
    }

    /// True when no pixel centre is covered.
    #[inline]
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
    /// Frame height in pixels.
    pub height: i32,
    /// First row of the band.
    pub y0: i32,
    /// One past the last row of the band.
    pub y1: i32,
}

/// One edge function `E(p) = dx * (py - ay) - dy * (px - ax)` with its top-left bias.
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
        // Interior is E > 0 (clockwise on a y-down screen). Pixels exactly on an
        // edge belong to it only when it is a top edge (horizontal, going right)
        // or a left edge (going up), so shared edges are drawn exactly once.
        let top_left = dy < 0 || (dy == 0 && dx > 0);
        let bias = if top_left { 0 } else { -1 };
        Edge {
            step_x: -dy * ONE,
            step_y: dx * ONE,
            start: dx * (py - a.y as i64) - dy * (px - a.x as i64) + bias,
        }
    }
}

/// Draws one triangle (clockwise on screen, positive [`signed_area`]) into the
/// band: depth test `1/w` greater than stored, perspective-correct colour.
#[inline]
pub(crate) fn draw_triangle(band: &mut Band<'_>, v: [&ScreenVertex; 3], area: i64) {
    let mut span = PixelSpan::of(v, band.width, band.height);
    span.y0 = span.y0.max(band.y0);
    span.y1 = span.y1.min(band.y1 - 1);
    if span.is_empty() {
        return;
    }
    let px = span.x0 as i64 * ONE + HALF;
    let py = span.y0 as i64 * ONE + HALF;
    // Edge k is opposite vertex k, so its value is vertex k's barycentric weight.
    let e0 = Edge::new(v[1], v[2], px, py);
    let e1 = Edge::new(v[2], v[0], px, py);
    let e2 = Edge::new(v[0], v[1], px, py);
    let inv_area = 1.0 / area as f32;
    let w0 = v[0].inv_w;
    let dw1 = v[1].inv_w - w0;
    let dw2 = v[2].inv_w - w0;
    let c0 = v[0].color_w;
    let dc1 = v[1].color_w - c0;
    let dc2 = v[2].color_w - c0;
    let width = band.width as usize;
    let (mut r0, mut r1, mut r2) = (e0.start, e1.start, e2.start);
    for y in span.y0..=span.y1 {
        let row = (y - band.y0) as usize * width;
        let (mut a0, mut a1, mut a2) = (r0, r1, r2);
        for x in span.x0..=span.x1 {
            if (a0 | a1 | a2) >= 0 {
                // The bias of at most 1 unit is negligible for the weights.
                let l1 = a1 as f32 * inv_area;
                let l2 = a2 as f32 * inv_area;
                let inv_w = w0 + l1 * dw1 + l2 * dw2;
                let k = row + x as usize;
                if inv_w > band.depth[k] {
                    band.depth[k] = inv_w;
                    let c = (c0 + l1 * dc1 + l2 * dc2) / inv_w;
                    let px = &mut band.color[4 * k..4 * k + 4];
                    px[0] = to_u8(c.x);
                    px[1] = to_u8(c.y);
                    px[2] = to_u8(c.z);
                    px[3] = 255;
                }
            }
            a0 += e0.step_x;
            a1 += e1.step_x;
            a2 += e2.step_x;
        }
        r0 += e0.step_y;
        r1 += e1.step_y;
        r2 += e2.step_y;
    }
}

/// A display value in `[0, 1]` to 8 bits (rounded, clamped; NaN gives 0).
#[inline]
pub(crate) fn to_u8(v: f32) -> u8 {
    (v * 255.0 + 0.5).clamp(0.0, 255.0) as u8
}
