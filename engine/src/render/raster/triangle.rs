//! The triangle: projection of its vertices to 16.8 fixed point, its set-up
//! (facing, winding, pixel box, edge functions with the top-left rule, planes
//! of `1/w`, colour / w and sun part / w) and its fill into a band (depth
//! test `1/w` greater than stored, perspective-correct colour, less the sun
//! part a caster hides from the pixel when the triangle resolves shadows).

use std::ops::{Add, Mul, Sub};

use glam::{Vec3, Vec4, Vec4Swizzles};

use super::band::Band;
use super::clip::ClipVertex;
use super::pixel_shadow::PixelShadow;
use super::viewport::{CullMode, Viewport};

/// Sub-pixel bits of screen coordinates (16.8 fixed point, as D3D11).
const SUBPIXEL_BITS: u32 = 8;
/// One pixel in fixed point.
const ONE: i64 = 1 << SUBPIXEL_BITS;
/// Half a pixel in fixed point.
const HALF: i64 = ONE / 2;

/// A vertex after projection: fixed-point pixel position (y down), `1/w`,
/// colour / w and sun part / w.
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
    /// Sun part divided by `w` (see [`ClipVertex::sun`]).
    pub sun_w: Vec3,
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
            sun_w: v.sun * inv_w,
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

/// An attribute's plane over the pixel centres of a triangle's box.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Plane<T> {
    /// Value at the box's first pixel centre.
    base: T,
    /// Change per pixel to the right.
    step_x: T,
    /// Change per pixel down.
    step_y: T,
}

impl<T: Copy + Add<Output = T> + Mul<f32, Output = T>> Plane<T> {
    /// The value at offset `(dx, dy)` from the box's first pixel centre.
    #[inline]
    fn at(&self, dx: i32, dy: i32) -> T {
        self.base + self.step_y * dy as f32 + self.step_x * dx as f32
    }
}

/// The barycentric weights of a triangle's vertices 1 and 2 as planes over
/// its box: what turns per-vertex values into attribute planes.
struct Weights([Plane<f32>; 2]);

impl Weights {
    /// The plane of an attribute with values `v` at the three vertices.
    fn plane<T>(&self, v: [T; 3]) -> Plane<T>
    where
        T: Copy + Add<Output = T> + Sub<Output = T> + Mul<f32, Output = T>,
    {
        let [w1, w2] = &self.0;
        let (d1, d2) = (v[1] - v[0], v[2] - v[0]);
        Plane {
            base: v[0] + d1 * w1.base + d2 * w2.base,
            step_x: d1 * w1.step_x + d2 * w2.step_x,
            step_y: d1 * w1.step_y + d2 * w2.step_y,
        }
    }
}

/// A triangle set up for filling: its pixel box, its edge functions and the
/// plane of its attributes (`1/w`, colour / w) over the pixel centres.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Triangle {
    /// Edge functions; edge `k` is opposite vertex `k`.
    edges: [Edge; 3],
    /// The attributes `1/w` and colour / w.
    attributes: Plane<Vec4>,
    /// Where its batch keeps the plane of its sun part / w, when it
    /// resolves caster shadows per pixel.
    pub sun_plane: Option<u32>,
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
        Triangle::with_weights(v, cull, vp).map(|(t, _, _)| t)
    }

    /// Sets up triangle `v` like [`Triangle::set_up`], with the plane of
    /// its sun part / w.
    pub fn set_up_with_sun(
        v: [&ScreenVertex; 3],
        cull: CullMode,
        vp: Viewport,
    ) -> Option<(Triangle, Plane<Vec3>)> {
        let (t, weights, order) = Triangle::with_weights(v, cull, vp)?;
        Some((t, weights.plane(order.map(|k| v[k].sun_w))))
    }

    /// The set-up triangle, the barycentric weights of its vertices and
    /// which of `v` became its vertices 0, 1 and 2 (wound clockwise on
    /// screen).
    fn with_weights(
        v: [&ScreenVertex; 3],
        cull: CullMode,
        vp: Viewport,
    ) -> Option<(Triangle, Weights, [usize; 3])> {
        let [a, b, c] = v;
        let area = (b.x as i64 - a.x as i64) * (c.y as i64 - a.y as i64)
            - (b.y as i64 - a.y as i64) * (c.x as i64 - a.x as i64);
        // Counter-clockwise in the world, seen from the front, projects to a
        // negative area on the y-down screen.
        let (order, area) = if area < 0 {
            ([0, 2, 1], -area)
        } else if area > 0 && cull == CullMode::None {
            ([0, 1, 2], area)
        } else {
            return None;
        };
        let v = order.map(|k| v[k]);
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
        let weights = Weights([1, 2].map(|k| Plane {
            base: edges[k].start as f32 * inv_area,
            step_x: edges[k].step_x as f32 * inv_area,
            step_y: edges[k].step_y as f32 * inv_area,
        }));
        let triangle = Triangle {
            edges,
            attributes: weights.plane(v.map(ScreenVertex::attributes)),
            sun_plane: None,
            x0,
            x1,
            y0,
            y1,
        };
        Some((triangle, weights, order))
    }

    /// The first and last pixel rows of its box.
    pub fn rows(&self) -> (i32, i32) {
        (self.y0, self.y1)
    }

    /// The covered columns of row `y` of its box, as offsets from its first
    /// column (empty when `lo > hi`).
    #[inline(always)]
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

    /// Calls `fill(x, y, pixel)` for each covered pixel of `band` whose
    /// `1/w` beats the stored depth (which it replaces), with the pixel's
    /// interpolated attributes; `fill` gives its RGBA.
    #[inline(always)]
    fn fill(&self, band: &mut Band<'_>, mut fill: impl FnMut(i32, i32, Vec4) -> [u8; 4]) {
        let width = band.width as usize;
        for y in self.y0.max(band.y0)..=self.y1.min(band.y1 - 1) {
            let (lo, hi) = self.covered(y);
            if lo > hi {
                continue;
            }
            let start = self.attributes.at(lo, y - self.y0);
            let step = self.attributes.step_x;
            let first = (y - band.y0) as usize * width + (self.x0 + lo) as usize;
            let end = first + (hi - lo) as usize + 1;
            let pixels = band.depth[first..end]
                .iter_mut()
                .zip(band.color[4 * first..4 * end].chunks_exact_mut(4));
            for (c, (depth, color)) in pixels.enumerate() {
                let a = start + step * c as f32;
                if a.x > *depth {
                    *depth = a.x;
                    color.copy_from_slice(&fill(self.x0 + lo + c as i32, y, a));
                }
            }
        }
    }

    /// Draws the triangle's pixels in `band`: depth test `1/w` greater than
    /// stored, perspective-correct colour.
    #[inline]
    pub fn draw(&self, band: &mut Band<'_>) {
        self.fill(band, |_, _, a| display_rgba(1.0 / a.x, a.yzw()));
    }

    /// Draws the triangle's pixels in `band` like [`Triangle::draw`], less
    /// the share of the sun part (plane `sun`) that `shadow` says casters
    /// hide from each pixel.
    pub fn draw_with_shadow(&self, band: &mut Band<'_>, sun: &Plane<Vec3>, shadow: &PixelShadow) {
        self.fill(band, |x, y, a| {
            let w = 1.0 / a.x;
            let hidden = 1.0 - shadow.visibility(x, y, w);
            let sun_w = sun.at(x - self.x0, y - self.y0);
            display_rgba(w, a.yzw() - sun_w * hidden)
        });
    }
}

/// A display value in `[0, 1]` to 8 bits (rounded, clamped; NaN gives 0).
#[inline]
pub(crate) fn to_u8(v: f32) -> u8 {
    (v * 255.0 + 0.5).clamp(0.0, 255.0) as u8
}

/// The opaque RGBA8 pixel of a pixel's `w` and interpolated colour / w.
#[inline]
fn display_rgba(w: f32, color_w: Vec3) -> [u8; 4] {
    [
        to_u8(color_w.x * w),
        to_u8(color_w.y * w),
        to_u8(color_w.z * w),
        255,
    ]
}
