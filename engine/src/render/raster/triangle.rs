//! The triangle: projection of its vertices to 16.8 fixed point, its set-up
//! (facing, winding, pixel box, edge functions with the top-left rule, planes
//! of `1/w` and colour / w) and its fill into a band (depth test `1/w`
//! greater than stored, perspective-correct colour).

use glam::{Vec3, Vec4};

use super::band::Band;
use super::clip::ClipVertex;
use super::viewport::{CullMode, Viewport};

/// Sub-pixel bits of screen coordinates (16.8 fixed point, as D3D11).
const SUBPIXEL_BITS: u32 = 8;
/// One pixel in fixed point.
const ONE: i64 = 1 << SUBPIXEL_BITS;
/// Half a pixel in fixed point.
const HALF: i64 = ONE / 2;

/// A vertex after projection: fixed-point pixel position (y down), `1/w`,
/// colour / w.
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
    /// The screen vertex of a clip vertex inside the guard band on `vp`.
    #[inline]
    pub fn project(v: &ClipVertex, vp: Viewport) -> ScreenVertex {
        let inv_w = 1.0 / v.pos.w;
        let sx = (v.pos.x * inv_w * 0.5 + 0.5) * vp.width as f32;
        let sy = (0.5 - v.pos.y * inv_w * 0.5) * vp.height as f32;
        let scale = ONE as f32;
        ScreenVertex {
            // Saturating casts: vertices outside the guard band are clipped
            // before they are set up, so their garbage never draws.
            x: (sx * scale + 0.5) as i32,
            y: (sy * scale + 0.5) as i32,
            inv_w,
            color_w: v.color * inv_w,
        }
    }

    /// The interpolated attributes: `1/w` then colour / w.
    #[inline]
    fn attributes(&self) -> Vec4 {
        Vec4::new(self.inv_w, self.color_w.x, self.color_w.y, self.color_w.z)
    }
}

/// One edge function `E(p) = dx * (py - ay) - dy * (px - ax)`, top-left bias
/// included, at the first pixel centre of its triangle's box.
#[derive(Debug, Clone, Copy)]
struct Edge {
    /// Change per pixel to the right.
    step_x: i64,
    /// Change per pixel down.
    step_y: i64,
    /// Value at the box's first pixel centre: covered when `>= 0`.
    start: i64,
}

impl Edge {
    /// The edge from `a` to `b` at fixed point `(px, py)`.
    fn new(a: &ScreenVertex, b: &ScreenVertex, px: i64, py: i64) -> Edge {
        let dx = b.x as i64 - a.x as i64;
        let dy = b.y as i64 - a.y as i64;
        // Interior is E > 0 (clockwise on a y-down screen). Pixels exactly on
        // an edge belong to it only when it is a top edge (horizontal, going
        // right) or a left edge (going up), so shared edges draw once.
        let top_left = dy < 0 || (dy == 0 && dx > 0);
        let bias = if top_left { 0 } else { -1 };
        Edge {
            step_x: -dy * ONE,
            step_y: dx * ONE,
            start: dx * (py - a.y as i64) - dy * (px - a.x as i64) + bias,
        }
    }

    /// Narrows the pixel run `lo..=hi` (offsets from the box's first column,
    /// where the edge value is `value`) to where this edge covers.
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

/// Boxes narrower than this many pixels scan a row for its covered run;
/// wider ones solve it from the edge equations.
const SOLVE_MIN_WIDTH: i32 = 6;

/// A triangle set up for filling: its pixel box, its edge functions and the
/// planes of its attributes (`1/w`, colour / w) over the pixel centres.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Triangle {
    /// Edge functions; edge `k` is opposite vertex `k`.
    edges: [Edge; 3],
    /// Attributes at the box's first pixel centre.
    base: Vec4,
    /// Attribute change per pixel to the right.
    step_x: Vec4,
    /// Attribute change per pixel down.
    step_y: Vec4,
    /// First and last covered column and row (clipped to the screen).
    x0: i32,
    x1: i32,
    y0: i32,
    y1: i32,
}

/// First pixel index whose centre is at or after fixed coordinate `v`.
#[inline]
fn first_centre(v: i32) -> i32 {
    // Arithmetic shifts floor, also for negative values.
    (v - HALF as i32 + ONE as i32 - 1) >> SUBPIXEL_BITS
}

/// Last pixel index whose centre is at or before fixed coordinate `v`.
#[inline]
fn last_centre(v: i32) -> i32 {
    (v - HALF as i32) >> SUBPIXEL_BITS
}

impl Triangle {
    /// Sets up triangle `v` on `vp`: `None` when `cull` drops its facing, it
    /// has no area, or its box holds no pixel centre of the screen.
    pub fn set_up(v: [&ScreenVertex; 3], cull: CullMode, vp: Viewport) -> Option<Triangle> {
        let [a, b, c] = v;
        let area = (b.x as i64 - a.x as i64) * (c.y as i64 - a.y as i64)
            - (b.y as i64 - a.y as i64) * (c.x as i64 - a.x as i64);
        // Counter-clockwise in the world, seen from the front, projects to a
        // negative area on the y-down screen.
        let (v, area) = if area < 0 {
            ([a, c, b], -area)
        } else if area > 0 && cull == CullMode::None {
            (v, area)
        } else {
            return None;
        };
        let x0 = first_centre(v[0].x.min(v[1].x).min(v[2].x)).max(0);
        let x1 = last_centre(v[0].x.max(v[1].x).max(v[2].x)).min(vp.width - 1);
        let y0 = first_centre(v[0].y.min(v[1].y).min(v[2].y)).max(0);
        let y1 = last_centre(v[0].y.max(v[1].y).max(v[2].y)).min(vp.height - 1);
        if x0 > x1 || y0 > y1 {
            return None;
        }
        let (px, py) = (x0 as i64 * ONE + HALF, y0 as i64 * ONE + HALF);
        let edges = [
            Edge::new(v[1], v[2], px, py),
            Edge::new(v[2], v[0], px, py),
            Edge::new(v[0], v[1], px, py),
        ];
        // Barycentric weights of vertices 1 and 2 are edges 1 and 2 over the
        // doubled area.
        let inv_area = 1.0 / area as f32;
        let a0 = v[0].attributes();
        let (d1, d2) = (v[1].attributes() - a0, v[2].attributes() - a0);
        let blend = |e: fn(&Edge) -> i64| {
            d1 * (e(&edges[1]) as f32 * inv_area) + d2 * (e(&edges[2]) as f32 * inv_area)
        };
        Some(Triangle {
            edges,
            base: a0 + blend(|e| e.start),
            step_x: blend(|e| e.step_x),
            step_y: blend(|e| e.step_y),
            x0,
            x1,
            y0,
            y1,
        })
    }

    /// The first and last pixel rows of its box.
    pub fn rows(&self) -> (i32, i32) {
        (self.y0, self.y1)
    }

    /// The covered columns of row `y` of its box, as offsets from its first
    /// column (empty when `lo > hi`).
    #[inline]
    fn covered(&self, y: i32) -> (i32, i32) {
        let r = (y - self.y0) as i64;
        let values = self.edges.map(|e| e.start + r * e.step_y);
        let (mut lo, mut hi) = (0, self.x1 - self.x0);
        if hi >= SOLVE_MIN_WIDTH {
            for (edge, &value) in self.edges.iter().zip(&values) {
                (lo, hi) = edge.covered_run(value, lo, hi);
            }
        } else {
            let inside = |c: i32| {
                (self.edges.iter().zip(&values)).all(|(e, &v)| v + c as i64 * e.step_x >= 0)
            };
            while lo <= hi && !inside(lo) {
                lo += 1;
            }
            while hi >= lo && !inside(hi) {
                hi -= 1;
            }
        }
        (lo, hi)
    }

    /// Draws the triangle's pixels in `band`: depth test `1/w` greater than
    /// stored, perspective-correct colour.
    #[inline]
    pub fn draw(&self, band: &mut Band<'_>) {
        let width = band.width as usize;
        for y in self.y0.max(band.y0)..=self.y1.min(band.y1 - 1) {
            let (lo, hi) = self.covered(y);
            if lo > hi {
                continue;
            }
            let start = self.base + self.step_y * (y - self.y0) as f32 + self.step_x * lo as f32;
            let first = (y - band.y0) as usize * width + (self.x0 + lo) as usize;
            let end = first + (hi - lo) as usize + 1;
            let pixels = band.depth[first..end]
                .iter_mut()
                .zip(band.color[4 * first..4 * end].chunks_exact_mut(4));
            for (c, (depth, color)) in pixels.enumerate() {
                let a = start + self.step_x * c as f32;
                if a.x > *depth {
                    *depth = a.x;
                    color.copy_from_slice(&display_rgba(a));
                }
            }
        }
    }
}

/// A display value in `[0, 1]` to 8 bits (rounded, clamped; NaN gives 0).
#[inline]
pub(crate) fn to_u8(v: f32) -> u8 {
    (v * 255.0 + 0.5).clamp(0.0, 255.0) as u8
}

/// The opaque RGBA8 pixel of interpolated attributes (`1/w`, colour / w).
#[inline]
fn display_rgba(a: Vec4) -> [u8; 4] {
    let inv = 1.0 / a.x;
    [to_u8(a.y * inv), to_u8(a.z * inv), to_u8(a.w * inv), 255]
}
