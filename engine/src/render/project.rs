//! The vertex pass of dense meshes: clip-space positions become fixed-point
//! screen vertices and clip outcodes four at a time, one vertex per lane of
//! `f32` vectors (structure of arrays).
//!
//! Every lane does the same IEEE operations in the same order as the scalar
//! [`Viewport::project`] and [`outcode`], so the results are the same bits;
//! only the float-to-integer conversion differs in how it is written: a lane
//! whose value could saturate (or is NaN) sends its group of four through the
//! scalar path, so that the integers are the same for every input.

use glam::{Mat4, Vec3, Vec4};

use super::batch::Viewport;
use super::centre_box::{MAGIC, WHOLE_MAX, centre_box, whole_numbers};
use super::clip::{
    GUARD_BAND, OUT_BOTTOM, OUT_GUARD, OUT_LEFT, OUT_NEAR, OUT_RIGHT, OUT_TOP, outcode,
};
use super::raster::{ONE, ScreenVertex};

/// Vertices per step of the lane pass.
const LANES: usize = 4;

/// Fixed-point values below this magnitude (16,384 pixels) convert exactly
/// through the lanes (see [`whole_numbers`]); a group with a larger, infinite
/// or NaN value goes through the scalar path.
const EXACT_FIXED: f32 = WHOLE_MAX;

/// A vertex after projection, with what the triangle loop asks of it first.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ProjectedVertex {
    /// Pixel-centre box ([`centre_box`]).
    pub centre_box: Vec4,
    /// Fixed-point position, `1/w` and colour / w.
    pub screen: ScreenVertex,
    /// Clip outcode ([`outcode`]).
    pub code: u8,
}

impl ProjectedVertex {
    /// A placeholder, overwritten before use.
    const UNSET: ProjectedVertex = ProjectedVertex {
        centre_box: Vec4::ZERO,
        screen: ScreenVertex {
            x: 0,
            y: 0,
            inv_w: 0.0,
            color_w: Vec3::ZERO,
        },
        code: 0,
    };

    /// The projected vertex of screen vertex `screen`, whose clip outcode is
    /// `code`.
    #[inline]
    pub fn new(screen: ScreenVertex, code: u8) -> ProjectedVertex {
        ProjectedVertex {
            centre_box: centre_box(&screen),
            screen,
            code,
        }
    }

    /// The scalar projection of clip position `p`, colour not set.
    fn scalar(p: Vec4, vp: Viewport) -> ProjectedVertex {
        ProjectedVertex::new(vp.project_position(p), outcode(p))
    }
}

/// Spare room for the vertices of a few clipped polygons.
const SPARE: usize = 16;

/// The projected vertices (colour not set: `color_w` is zero) whose clip
/// positions are `clip`, in order.
pub(crate) fn project_positions(clip: &[Vec4], vp: Viewport) -> Vec<ProjectedVertex> {
    let mut vertices = Vec::with_capacity(clip.len() + SPARE);
    // Written in place below (records built elsewhere and copied in cost two
    // block copies per group).
    vertices.resize(clip.len(), ProjectedVertex::UNSET);
    let mut out = vertices.chunks_exact_mut(LANES);
    let mut groups = clip.chunks_exact(LANES);
    for (out, group) in (&mut out).zip(&mut groups) {
        let four = [group[0], group[1], group[2], group[3]];
        if !project_four(four, vp, out) {
            for (out, p) in out.iter_mut().zip(four) {
                *out = ProjectedVertex::scalar(p, vp);
            }
        }
    }
    for (out, &p) in out.into_remainder().iter_mut().zip(groups.remainder()) {
        *out = ProjectedVertex::scalar(p, vp);
    }
    vertices
}

/// Writes to `out` (four records) the screen vertices, outcodes and centre
/// boxes of four clip positions, one per lane, and returns true; or returns
/// false, writing nothing, when a fixed-point coordinate is too large (or NaN)
/// for the exact lane conversion.
#[inline(always)]
fn project_four(clip: [Vec4; LANES], vp: Viewport, out: &mut [ProjectedVertex]) -> bool {
    // Rows of the transpose: all x, all y, all z, all w.
    let lanes = Mat4::from_cols(clip[0], clip[1], clip[2], clip[3]).transpose();
    let (x, y, z, w) = (lanes.x_axis, lanes.y_axis, lanes.z_axis, lanes.w_axis);
    // The same operations as `Viewport::project`, lane by lane.
    let inv_w = Vec4::ONE / w;
    let sx = (x * inv_w * 0.5 + 0.5) * vp.width as f32;
    let sy = (0.5 - y * inv_w * 0.5) * vp.height as f32;
    let scale = ONE as f32;
    let fx = sx * scale + 0.5;
    let fy = sy * scale + 0.5;
    // `abs() < EXACT_FIXED` is false for NaN: such groups go scalar.
    let exact = fx.abs().cmplt(Vec4::splat(EXACT_FIXED)) & fy.abs().cmplt(Vec4::splat(EXACT_FIXED));
    if !exact.all() {
        return false;
    }
    // `as i32` rounds towards zero; in this range it does not saturate.
    let (tx, ty) = (fx.trunc(), fy.trunc());
    let (ix, iy) = (whole_numbers(tx), whole_numbers(ty));
    let inv_w = inv_w.to_array();
    let codes = outcodes(x, y, z, w);
    let boxes = centre_boxes(tx, ty);
    for (k, out) in out.iter_mut().enumerate().take(LANES) {
        *out = ProjectedVertex {
            centre_box: boxes[k],
            screen: ScreenVertex {
                x: ix[k],
                y: iy[k],
                inv_w: inv_w[k],
                color_w: Vec3::ZERO,
            },
            code: codes[k],
        };
    }
    true
}

/// The centre boxes ([`super::centre_box`]) of four vertices whose
/// fixed-point coordinates are the whole numbers in the lanes of `x` and `y`
/// (of magnitude below `2^22`).
///
/// `first_centre(v) = (v + 127) >> 8` and `last_centre(v) = (v - 128) >> 8`
/// are `floor(n / 256)` of a whole number `n`, which equals `n / 256 - 127.5 /
/// 256` rounded to the nearest whole number (never a tie: the fraction of
/// `n / 256` is a multiple of `1 / 256`); adding and subtracting [`MAGIC`]
/// rounds so. Every step is exact in `f32` in this range.
#[inline(always)]
fn centre_boxes(x: Vec4, y: Vec4) -> [Vec4; LANES] {
    const INV_ONE: f32 = 1.0 / ONE as f32;
    // (n - 127.5) / 256 + MAGIC, with n = v + 127 or v - 128.
    let first = |v: Vec4| (v - 0.5) * INV_ONE + MAGIC;
    let last = |v: Vec4| (v - 255.5) * INV_ONE + MAGIC;
    let (fx, lx, fy, ly) = (first(x), last(x), first(y), last(y));
    let rows = Mat4::from_cols(fx - MAGIC, MAGIC - lx, fy - MAGIC, MAGIC - ly).transpose();
    rows.to_cols_array_2d().map(Vec4::from_array)
}

/// [`outcode`] of four clip positions given by their coordinates in lanes: the
/// same compares, each giving its bit for four vertices at once.
#[inline(always)]
fn outcodes(x: Vec4, y: Vec4, z: Vec4, w: Vec4) -> [u8; LANES] {
    let bit = |mask: glam::BVec4A, bit: u8| Vec4::select(mask, Vec4::splat(bit as f32), Vec4::ZERO);
    let g = GUARD_BAND * w;
    let inside_guard = x.abs().cmple(g) & y.abs().cmple(g);
    // NaN positions count as behind (`z >= 0` is false), as in `outcode`.
    let sum = bit((-x).cmpgt(w), OUT_LEFT)
        + bit(x.cmpgt(w), OUT_RIGHT)
        + bit((-y).cmpgt(w), OUT_BOTTOM)
        + bit(y.cmpgt(w), OUT_TOP)
        + bit(!z.cmpge(Vec4::ZERO), OUT_NEAR)
        + bit(!inside_guard, OUT_GUARD);
    // Whole numbers below 64.
    whole_numbers(sum).map(|c| c as u8)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::SplitMix64;

    /// Clip positions that exercise every branch: ordinary, behind the near
    /// plane, at `w = 0`, huge, NaN and infinite, exact `.5` fixed-point
    /// fractions.
    fn awkward_positions(rng: &mut SplitMix64, count: usize) -> Vec<Vec4> {
        let specials = [
            0.0,
            -0.0,
            1.0,
            -1.0,
            1e-30,
            -1e-30,
            3e9,
            -3e9,
            1e38,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
        ];
        (0..count)
            .map(|k| {
                let mut c = || match rng.next_u64() % 8 {
                    0 => specials[(rng.next_u64() % specials.len() as u64) as usize],
                    1 => rng.range(-1e6, 1e6),
                    _ => rng.range(-3.0, 3.0),
                };
                let p = Vec4::new(c(), c(), c(), c());
                if k.is_multiple_of(5) {
                    // x, y on exact half fixed-point steps of a 64 x 48 screen
                    // (w = 1): (sx * 256 + 0.5) is a whole number plus 0.5 or 0.
                    let step = |n: u64, size: f32| (n as f32 / 512.0) / size * 2.0 - 1.0;
                    let (nx, ny) = (rng.next_u64() % 65_536, rng.next_u64() % 49_152);
                    Vec4::new(step(nx, 64.0), -step(ny, 48.0), 0.5, 1.0)
                } else {
                    p
                }
            })
            .collect()
    }

    #[test]
    fn lanes_give_the_scalar_screen_vertices_and_outcodes() {
        let mut rng = SplitMix64::new(0x243f_6a88_85a3_08d3);
        let vp = Viewport {
            width: 64,
            height: 48,
        };
        // Lengths that leave every remainder.
        for count in [0, 1, 3, 4, 7, 20_000, 20_003] {
            let clip = awkward_positions(&mut rng, count);
            let out = project_positions(&clip, vp);
            assert_eq!(out.len(), count);
            for (got, &p) in out.iter().zip(&clip) {
                let expected = vp.project_position(p);
                let screen = got.screen;
                assert_eq!((screen.x, screen.y), (expected.x, expected.y), "{p:?}");
                assert_eq!(screen.inv_w.to_bits(), expected.inv_w.to_bits(), "{p:?}");
                assert_eq!(got.code, outcode(p), "{p:?}");
                let (a, b) = (got.centre_box, centre_box(&expected));
                assert_eq!(a.cmpeq(b).bitmask(), 0b1111, "{p:?}: {a:?} vs {b:?}");
            }
        }
    }
}
