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
use super::clip::{
    GUARD_BAND, OUT_BOTTOM, OUT_GUARD, OUT_LEFT, OUT_NEAR, OUT_RIGHT, OUT_TOP, outcode,
};
use super::raster::{ONE, ScreenVertex};

/// Vertices per step of the lane pass.
const LANES: usize = 4;

/// Fixed-point values below this magnitude (16,384 pixels) convert exactly
/// through the lanes (see [`truncate`]); a group with a larger, infinite or
/// NaN value goes through the scalar path.
const EXACT_FIXED: f32 = (1 << 22) as f32;

/// `1.5 * 2^23`: whole numbers `t` with `|t| < 2^22` added to it give a float
/// whose bits are `MAGIC.to_bits() + t`.
const MAGIC: f32 = 12_582_912.0;

/// The screen vertices (colour not set: `color_w` is zero) and clip outcodes
/// of `count` vertices whose clip positions are `clip[k]`.
pub(crate) fn project_positions(clip: &[Vec4], vp: Viewport) -> (Vec<ScreenVertex>, Vec<u8>) {
    let mut screen = Vec::with_capacity(clip.len());
    let mut codes = Vec::with_capacity(clip.len());
    let groups = clip.chunks_exact(LANES);
    let rest = groups.remainder();
    for group in groups {
        let (four, four_codes) = project_four([group[0], group[1], group[2], group[3]], vp);
        screen.extend_from_slice(&four);
        codes.extend_from_slice(&four_codes);
    }
    for &p in rest {
        screen.push(vp.project_position(p));
        codes.push(outcode(p));
    }
    (screen, codes)
}

/// Screen vertices and outcodes of four clip positions, one per lane.
#[inline(always)]
fn project_four(clip: [Vec4; LANES], vp: Viewport) -> ([ScreenVertex; LANES], [u8; LANES]) {
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
    let codes = outcodes(x, y, z, w);
    // `abs() < EXACT_FIXED` is false for NaN: such groups go scalar too.
    let exact = fx.abs().cmplt(Vec4::splat(EXACT_FIXED)) & fy.abs().cmplt(Vec4::splat(EXACT_FIXED));
    if !exact.all() {
        return (clip.map(|p| vp.project_position(p)), codes);
    }
    let (ix, iy) = (truncate(fx), truncate(fy));
    let inv_w = inv_w.to_array();
    let screen = std::array::from_fn(|k| ScreenVertex {
        x: ix[k],
        y: iy[k],
        inv_w: inv_w[k],
        color_w: Vec3::ZERO,
    });
    (screen, codes)
}

/// `v as i32` per lane for lanes of magnitude below [`EXACT_FIXED`]: rounded
/// towards zero in the vector, then read from the bits of the whole number
/// plus [`MAGIC`] (the vector form of the cast, which has no saturation to do
/// in this range).
#[inline(always)]
fn truncate(v: Vec4) -> [i32; LANES] {
    whole_numbers(v.trunc())
}

/// The whole numbers `v` (each of magnitude below `2^22`) as integers.
#[inline(always)]
fn whole_numbers(v: Vec4) -> [i32; LANES] {
    let bits = (v + MAGIC).to_array().map(f32::to_bits);
    bits.map(|b| b.wrapping_sub(MAGIC.to_bits()) as i32)
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
                if k % 5 == 0 {
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
            let (screen, codes) = project_positions(&clip, vp);
            assert_eq!(screen.len(), count);
            for (k, &p) in clip.iter().enumerate() {
                let expected = vp.project_position(p);
                let got = screen[k];
                assert_eq!((got.x, got.y), (expected.x, expected.y), "{p:?}");
                assert_eq!(got.inv_w.to_bits(), expected.inv_w.to_bits(), "{p:?}");
                assert_eq!(codes[k], outcode(p), "{p:?}");
            }
        }
    }
}
