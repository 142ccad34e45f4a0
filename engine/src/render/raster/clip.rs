//! Clipping of triangles in homogeneous clip space.
//!
//! Only triangles that cross the near plane or leave the guard band are clipped;
//! everything else goes straight to the rasterizer, whose screen scissor does the rest.

use glam::{Vec3, Vec4};

/// How far outside the viewport (in viewport half-sizes) vertices may lie before
/// their triangle is clipped. Keeps fixed-point screen coordinates well inside `i32`
/// and edge products inside `i64`.
pub(crate) const GUARD_BAND: f32 = 8.0;

/// A vertex in clip space with its colour (display-encoded RGB).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct ClipVertex {
    /// Homogeneous clip position.
    pub pos: Vec4,
    /// Colour to interpolate, with all the sun that reaches past the
    /// terrain.
    pub color: Vec3,
    /// The part of `color` the sun gives, where casters are resolved per
    /// pixel (see [`super::PixelShadow`]): a pixel a caster hides from the
    /// sun loses it. Zero for geometry shaded past the casters per vertex.
    pub sun: Vec3,
}

impl ClipVertex {
    fn lerp(&self, other: &ClipVertex, t: f32) -> ClipVertex {
        ClipVertex {
            pos: self.pos.lerp(other.pos, t),
            color: self.color.lerp(other.color, t),
            sun: self.sun.lerp(other.sun, t),
        }
    }
}

/// Outcode bit: outside the left, right, bottom or top frustum plane, behind the near plane.
pub(crate) const OUT_LEFT: u8 = 1;
/// Outcode bit: outside the right plane.
pub(crate) const OUT_RIGHT: u8 = 2;
pub(crate) const OUT_BOTTOM: u8 = 4;
pub(crate) const OUT_TOP: u8 = 8;
pub(crate) const OUT_NEAR: u8 = 16;
/// Outcode bit: outside the guard band (needs clipping before fixed-point conversion).
pub(crate) const OUT_GUARD: u8 = 32;
/// Bits that reject a triangle when all three vertices share one of them.
pub(crate) const OUT_FRUSTUM: u8 = OUT_LEFT | OUT_RIGHT | OUT_BOTTOM | OUT_TOP | OUT_NEAR;

/// The outcode of a clip-space position.
#[inline]
pub(crate) fn outcode(p: Vec4) -> u8 {
    // x < -w is -x > w (negation is exact): the four side planes are one
    // vector compare whose lanes are OUT_LEFT, OUT_RIGHT, OUT_BOTTOM, OUT_TOP.
    let sides = Vec4::new(-p.x, p.x, -p.y, p.y)
        .cmpgt(Vec4::splat(p.w))
        .bitmask() as u8;
    // NaN positions count as behind, so they are rejected or clipped away.
    let near = if p.z >= 0.0 { 0 } else { OUT_NEAR };
    let g = GUARD_BAND * p.w;
    let guard = if p.x.abs() <= g && p.y.abs() <= g {
        0
    } else {
        OUT_GUARD
    };
    sides | near | guard
}

/// The clip planes used when clipping: near (`z >= 0`) then the four guard-band planes.
const CLIP_PLANES: [Vec4; 5] = [
    Vec4::new(0.0, 0.0, 1.0, 0.0),
    Vec4::new(1.0, 0.0, 0.0, GUARD_BAND),
    Vec4::new(-1.0, 0.0, 0.0, GUARD_BAND),
    Vec4::new(0.0, 1.0, 0.0, GUARD_BAND),
    Vec4::new(0.0, -1.0, 0.0, GUARD_BAND),
];

/// Clips triangle `tri` against the near plane and the guard band
/// (Sutherland–Hodgman) and returns the resulting convex polygon (0 or 3..=8 vertices)
/// in `out`, which is cleared first.
pub(crate) fn clip_triangle(tri: [ClipVertex; 3], out: &mut Vec<ClipVertex>) {
    out.clear();
    out.extend_from_slice(&tri);
    let mut scratch: Vec<ClipVertex> = Vec::with_capacity(9);
    for plane in CLIP_PLANES {
        if out.is_empty() {
            return;
        }
        scratch.clear();
        for k in 0..out.len() {
            let a = out[k];
            let b = out[(k + 1) % out.len()];
            let da = plane.dot(a.pos);
            let db = plane.dot(b.pos);
            let a_in = da >= 0.0;
            if a_in {
                scratch.push(a);
            }
            if a_in != (db >= 0.0) {
                scratch.push(a.lerp(&b, da / (da - db)));
            }
        }
        std::mem::swap(out, &mut scratch);
    }
    if out.len() < 3 {
        out.clear();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn v(x: f32, y: f32, z: f32, w: f32) -> ClipVertex {
        ClipVertex {
            pos: Vec4::new(x, y, z, w),
            color: Vec3::new(z, 0.0, 0.0),
            sun: Vec3::ZERO,
        }
    }

    #[test]
    fn near_plane_cuts_a_triangle_into_a_quad() {
        let mut out = Vec::new();
        clip_triangle(
            [
                v(0.0, 0.0, -1.0, 1.0),
                v(1.0, 0.0, 1.0, 2.0),
                v(0.0, 1.0, 1.0, 2.0),
            ],
            &mut out,
        );
        assert_eq!(out.len(), 4);
        assert!(out.iter().all(|p| p.pos.z >= -1e-6));
        // Two of the new vertices lie on the plane with interpolated colour 0.
        assert_eq!(out.iter().filter(|p| p.pos.z.abs() < 1e-6).count(), 2);
        assert!(out.iter().all(|p| (p.color.x - p.pos.z).abs() < 1e-6));
    }

    #[test]
    fn fully_behind_is_removed_and_inside_is_kept() {
        let mut out = Vec::new();
        clip_triangle(
            [
                v(0.0, 0.0, -1.0, 1.0),
                v(1.0, 0.0, -2.0, 1.0),
                v(0.0, 1.0, -1.0, 1.0),
            ],
            &mut out,
        );
        assert!(out.is_empty());
        let inside = [
            v(0.0, 0.0, 0.5, 1.0),
            v(0.5, 0.0, 0.5, 1.0),
            v(0.0, 0.5, 0.5, 1.0),
        ];
        clip_triangle(inside, &mut out);
        assert_eq!(out, inside.to_vec());
        assert_eq!(outcode(Vec4::new(0.0, 0.0, -0.1, 1.0)), OUT_NEAR);
        assert_eq!(
            outcode(Vec4::new(20.0, 0.0, 0.5, 1.0)),
            OUT_RIGHT | OUT_GUARD
        );
    }
}
