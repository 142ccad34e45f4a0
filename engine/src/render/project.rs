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

use super::batch::{Viewport, to_clip};
use super::centre_box::{MAGIC, WHOLE_MAX, centre_box, whole_numbers};
use super::clip::{
    GUARD_BAND, OUT_BOTTOM, OUT_GUARD, OUT_LEFT, OUT_NEAR, OUT_RIGHT, OUT_TOP, outcode,
};
use super::raster::{ONE, ScreenVertex};

/// Vertices per step of the lane pass.
pub(crate) const LANES: usize = 4;

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
    /// A placeholder vertex (at the origin, behind the near plane).
    pub const UNUSED: ProjectedVertex = ProjectedVertex {
        centre_box: Vec4::ZERO,
        screen: ScreenVertex {
            x: 0,
            y: 0,
            inv_w: 0.0,
            color_w: Vec3::ZERO,
        },
        code: OUT_NEAR,
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

/// Where the clip positions of a batch's vertices come from.
pub(crate) trait ClipSource {
    /// Number of vertices.
    fn len(&self) -> usize;
    /// The clip position of vertex `k`.
    fn clip(&self, k: usize) -> Vec4;
    /// The clip positions of vertices `4 * group .. 4 * group + 4` as lanes:
    /// all x, all y, all z, all w (the same bits as [`ClipSource::clip`]),
    /// and the world positions they come from as lanes (x, y, z; the clip
    /// ones when there is no world space).
    fn lanes(&self, group: usize) -> ([Vec4; LANES], [Vec4; 3]);
}

/// Four vectors turned into four lanes: lane `k` of output `j` is lane `j`
/// of input `k` (a 4 x 4 transpose, between one item per vector and one
/// item per lane).
#[inline(always)]
pub(crate) fn transpose_lanes([a, b, c, d]: [Vec4; 4]) -> [Vec4; 4] {
    let rows = Mat4::from_cols(a, b, c, d).transpose();
    [rows.x_axis, rows.y_axis, rows.z_axis, rows.w_axis]
}

/// Four clip positions as lanes (all x, all y, all z, all w), and as the
/// world lanes of a source without world space (x, y, z).
#[inline(always)]
pub(crate) fn position_lanes(p: [Vec4; LANES]) -> ([Vec4; LANES], [Vec4; 3]) {
    let [x, y, z, w] = transpose_lanes(p);
    ([x, y, z, w], [x, y, z])
}

/// Clip positions given as they are (tests build batches from them).
#[cfg(test)]
pub(crate) struct ClipPositions<'a>(pub &'a [Vec4]);

#[cfg(test)]
impl ClipSource for ClipPositions<'_> {
    fn len(&self) -> usize {
        self.0.len()
    }

    fn clip(&self, k: usize) -> Vec4 {
        self.0[k]
    }

    fn lanes(&self, group: usize) -> ([Vec4; LANES], [Vec4; 3]) {
        position_lanes(std::array::from_fn(|k| self.0[LANES * group + k]))
    }
}

/// Model-space points placed by `model`, seen through `view_proj`: clip
/// position `view_proj * (model * p)`, computed four points at a time with the
/// same operations, in the same order, as glam's `transform_point3` and
/// matrix-vector product.
#[derive(Debug, Clone, Copy)]
pub(crate) struct TransformedPoints<'a> {
    /// Model-space positions.
    points: &'a [Vec3],
    /// Model-to-world transform (affine).
    model: Mat4,
    /// World-to-clip transform.
    view_proj: Mat4,
    /// The rows of `model` and `view_proj` ([`SplatRow`]s), ready for the
    /// lanes.
    rows: [[SplatRow; 4]; 2],
    /// `model == Mat4::IDENTITY`: then the model transform is skipped, which
    /// changes at most the sign of a zero coordinate (`-0 + 0` is `+0`).
    identity: bool,
}

impl<'a> TransformedPoints<'a> {
    /// The points `points` placed by the affine `model`, seen through
    /// `view_proj`.
    pub fn new(points: &'a [Vec3], model: Mat4, view_proj: Mat4) -> TransformedPoints<'a> {
        TransformedPoints {
            points,
            model,
            view_proj,
            rows: [model, view_proj].map(|m| {
                let t = m.transpose();
                [t.x_axis, t.y_axis, t.z_axis, t.w_axis].map(SplatRow::new)
            }),
            identity: model == Mat4::IDENTITY,
        }
    }

    /// The model-to-world transform.
    pub fn model(&self) -> Mat4 {
        self.model
    }

    /// The world position of point `k`.
    #[inline]
    pub fn world(&self, k: usize) -> Vec3 {
        let p = self.points[k];
        if self.identity {
            p
        } else {
            self.model.transform_point3(p)
        }
    }

    /// The world positions of points `4 * group .. 4 * group + 4` as lanes
    /// (x, y, z), with the operations of [`TransformedPoints::world`].
    #[inline(always)]
    pub fn world_lanes(&self, group: usize) -> [Vec4; 3] {
        let [x, y, z] = vec3_lanes(&self.points[LANES * group..LANES * group + LANES]);
        if self.identity {
            return [x, y, z];
        }
        // transform_point3: ((x_axis x + y_axis y) + z_axis z) + w_axis.
        let [rx, ry, rz, _] = &self.rows[0];
        [rx.times(x, y, z), ry.times(x, y, z), rz.times(x, y, z)]
    }
}

/// Four `Vec3`s (`p` holds exactly [`LANES`]) as lanes: all x, all y, all z.
#[inline(always)]
pub(crate) fn vec3_lanes(p: &[Vec3]) -> [Vec4; 3] {
    let p: &[Vec3; LANES] = p.try_into().expect("one group of lanes");
    [
        Vec4::new(p[0].x, p[1].x, p[2].x, p[3].x),
        Vec4::new(p[0].y, p[1].y, p[2].y, p[3].y),
        Vec4::new(p[0].z, p[1].z, p[2].z, p[3].z),
    ]
}

/// A matrix row with each of its four coefficients in all four lanes, so
/// that applying it to four points (a loop's work per step) needs no
/// broadcasts.
#[derive(Debug, Clone, Copy)]
pub(crate) struct SplatRow([Vec4; 4]);

impl SplatRow {
    /// The row `row` splatted.
    pub fn new(row: Vec4) -> SplatRow {
        SplatRow(row.to_array().map(Vec4::splat))
    }

    /// The row applied to four points `(x, y, z, 1)` given as lanes:
    /// `((row.x x + row.y y) + row.z z) + row.w`, the sums of glam's matrix
    /// products in their order.
    #[inline(always)]
    pub fn times(&self, x: Vec4, y: Vec4, z: Vec4) -> Vec4 {
        let [a, b, c, d] = &self.0;
        x * *a + y * *b + z * *c + *d
    }
}

impl ClipSource for TransformedPoints<'_> {
    fn len(&self) -> usize {
        self.points.len()
    }

    #[inline]
    fn clip(&self, k: usize) -> Vec4 {
        to_clip(&self.view_proj, self.world(k))
    }

    #[inline(always)]
    fn lanes(&self, group: usize) -> ([Vec4; LANES], [Vec4; 3]) {
        let [wx, wy, wz] = self.world_lanes(group);
        // Mat4 * Vec4 with w = 1: ((x_axis x + y_axis y) + z_axis z) + w_axis * 1.
        let clip = self.rows[1].each_ref().map(|row| row.times(wx, wy, wz));
        (clip, [wx, wy, wz])
    }
}

/// Where the display colours of a batch's vertices come from.
pub(crate) trait VertexShader {
    /// The colour of vertex `k`.
    fn color(&self, k: usize) -> Vec3;
    /// The colours of vertices `4 * group .. 4 * group + 4` (the same bits as
    /// [`VertexShader::color`]; by default, that of each).
    #[inline(always)]
    fn colors(&self, group: usize) -> [Vec3; LANES] {
        std::array::from_fn(|k| self.color(LANES * group + k))
    }
    /// [`VertexShader::colors`] of vertices whose world positions (as given
    /// by [`ClipSource::lanes`]) are `world`, for shaders that need them.
    #[inline(always)]
    fn colors_at(&self, group: usize, world: &[Vec4; 3]) -> [Vec3; LANES] {
        let _ = world;
        self.colors(group)
    }
}

/// Replaces the contents of `vertices` with the projected vertices of the
/// clip positions of `source`, in order, with the colours of `shader` (each
/// times the vertex's `1/w`); the vector's capacity is kept. Inlined into
/// each copy of the batch build ([`super::kernels::Kernels`]).
#[inline(always)]
pub(crate) fn project_vertices(
    source: &impl ClipSource,
    shader: &impl VertexShader,
    vp: Viewport,
    vertices: &mut Vec<ProjectedVertex>,
) {
    let count = source.len();
    // Records are pushed one by one, built in place (arrays of four built
    // elsewhere and copied in cost block copies; zeroing first costs a pass).
    vertices.clear();
    vertices.reserve(count);
    let scalar = |k: usize| {
        let mut v = ProjectedVertex::scalar(source.clip(k), vp);
        v.screen.color_w = shader.color(k) * v.screen.inv_w;
        v
    };
    for group in 0..count / LANES {
        let (clip, world) = source.lanes(group);
        let colors = shader.colors_at(group, &world);
        if !project_four(clip, colors, vp, vertices) {
            vertices.extend((LANES * group..LANES * group + LANES).map(scalar));
        }
    }
    vertices.extend((count - count % LANES..count).map(scalar));
}

/// Appends to `out` the screen vertices (with `colors` times their `1/w`),
/// outcodes and centre boxes of four clip positions given as lanes (x, y, z,
/// w), and returns true; or returns
/// false, appending nothing, when a fixed-point coordinate is too large (or NaN)
/// for the exact lane conversion.
#[inline(always)]
fn project_four(
    lanes: [Vec4; LANES],
    colors: [Vec3; LANES],
    vp: Viewport,
    out: &mut Vec<ProjectedVertex>,
) -> bool {
    let [x, y, z, w] = lanes;
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
    for k in 0..LANES {
        out.push(ProjectedVertex {
            centre_box: boxes[k],
            screen: ScreenVertex {
                x: ix[k],
                y: iy[k],
                inv_w: inv_w[k],
                color_w: colors[k] * inv_w[k],
            },
            code: codes[k],
        });
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
    transpose_lanes([fx - MAGIC, MAGIC - lx, fy - MAGIC, MAGIC - ly])
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
    use crate::render::clip::ClipVertex;
    use crate::rng::SplitMix64;

    /// Colours from a table.
    pub(crate) struct ColorTable<'a>(pub &'a [Vec3]);

    impl VertexShader for ColorTable<'_> {
        fn color(&self, k: usize) -> Vec3 {
            self.0[k]
        }
    }

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
    fn transformed_point_lanes_are_the_scalar_clip_positions() {
        let mut rng = SplitMix64::new(0xa409_3822_299f_31d0);
        let camera = crate::render::Camera::perspective(0.9, 64, 48, 0.05, 50.0)
            .unwrap()
            .look_at(Vec3::new(1.0, 3.0, -8.0), Vec3::ZERO, Vec3::Y);
        let mut v = || rng.range(-5.0, 5.0);
        let points: Vec<Vec3> = (0..4 * 500).map(|_| Vec3::new(v(), v(), v())).collect();
        let models = [
            Mat4::IDENTITY,
            Mat4::from_scale_rotation_translation(
                Vec3::new(1.5, 0.7, 2.0),
                glam::Quat::from_rotation_y(0.7) * glam::Quat::from_rotation_x(-0.3),
                Vec3::new(0.3, -1.0, 2.5),
            ),
        ];
        for model in models {
            let source = TransformedPoints::new(&points, model, camera.view_proj());
            for group in 0..points.len() / LANES {
                let (lanes, _) = source.lanes(group);
                for k in 0..LANES {
                    let clip = source.clip(LANES * group + k);
                    let from_lanes = Vec4::from_array(lanes.map(|lane| lane[k]));
                    assert_eq!(
                        from_lanes.to_array().map(f32::to_bits),
                        clip.to_array().map(f32::to_bits)
                    );
                }
            }
        }
    }

    #[test]
    fn an_identity_model_is_skipped_up_to_the_sign_of_zero() {
        let view_proj = crate::render::Camera::perspective(0.9, 64, 48, 0.05, 50.0)
            .unwrap()
            .look_at(Vec3::new(1.0, 3.0, -8.0), Vec3::ZERO, Vec3::Y)
            .view_proj();
        let mut rng = SplitMix64::new(0x1c27_f1e5_a0b3_4d96);
        let mut points: Vec<Vec3> = (0..4 * 200)
            .map(|_| Vec3::new(rng.range(-5.0, 5.0), rng.range(-5.0, 5.0), 0.0))
            .collect();
        points.extend([
            Vec3::ZERO,
            Vec3::splat(-0.0),
            Vec3::new(-0.0, 1.0, -0.0),
            Vec3::X,
        ]);
        let source = TransformedPoints::new(&points, Mat4::IDENTITY, view_proj);
        for (k, &p) in points.iter().enumerate() {
            let full = to_clip(&view_proj, Mat4::IDENTITY.transform_point3(p));
            let skipped = source.clip(k);
            // Equal as numbers (-0 == +0), and bit for bit but for zeros.
            assert_eq!(skipped, full, "{p}");
            for (a, b) in skipped.to_array().into_iter().zip(full.to_array()) {
                assert!(a.to_bits() == b.to_bits() || a == 0.0, "{p}");
            }
        }
    }

    #[test]
    fn lanes_give_the_scalar_screen_vertices_and_outcodes() {
        let mut rng = SplitMix64::new(0x243f_6a88_85a3_08d3);
        let vp = Viewport {
            width: 64,
            height: 48,
        };
        // Lengths that leave every remainder; one vector reused for all (as
        // a renderer reuses its batches), longest first.
        let mut out = Vec::new();
        for count in [20_003, 20_000, 7, 4, 3, 1, 0] {
            let clip = awkward_positions(&mut rng, count);
            let colors: Vec<Vec3> = (0..count)
                .map(|_| Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()))
                .collect();
            project_vertices(&ClipPositions(&clip), &ColorTable(&colors), vp, &mut out);
            assert_eq!(out.len(), count);
            for ((got, &p), &color) in out.iter().zip(&clip).zip(&colors) {
                let expected = vp.project(&ClipVertex { pos: p, color });
                let screen = got.screen;
                let bits = |c: Vec3| c.to_array().map(f32::to_bits);
                assert_eq!(bits(screen.color_w), bits(expected.color_w), "{p:?}");
                assert_eq!((screen.x, screen.y), (expected.x, expected.y), "{p:?}");
                assert_eq!(screen.inv_w.to_bits(), expected.inv_w.to_bits(), "{p:?}");
                assert_eq!(got.code, outcode(p), "{p:?}");
                let (a, b) = (got.centre_box, centre_box(&expected));
                assert_eq!(a.cmpeq(b).bitmask(), 0b1111, "{p:?}: {a:?} vs {b:?}");
            }
        }
    }
}
