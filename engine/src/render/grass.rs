//! Grass blades: thin tapered strips facing the camera, drawn nearest first by
//! the span rasterizer of [`super::blade_span`].

use glam::{Mat4, Vec3, Vec4};
use rayon::prelude::*;

use super::blade_span::{BladePiece, NotMonotone, SpanVertex};
use super::camera::Camera;
use super::frame_view::FrameView;
use super::grass_blade::GrassBlade;
use super::raster::{
    Band, BandBins, ClipVertex, CullMode, OUT_FRUSTUM, OUT_GUARD, OUT_NEAR, TriangleBatch,
    TriangleGroup, outcode,
};
use super::shading::{Lighting, encode_display};
use crate::rng::SplitMix64;

/// Blades per group (the unit of parallel set-up work).
const BLADES_PER_BATCH: usize = 1024;
/// Bits of a binned piece index that number the piece within its group (at
/// most two pieces per blade).
const GROUP_BITS: u32 = (2 * BLADES_PER_BATCH).next_power_of_two().trailing_zeros();

/// Triangles of one blade's five vertices: two for the lower half, one for the tip.
const BLADE_TRIANGLES: [[u32; 3]; 3] = [[0, 1, 3], [0, 3, 2], [2, 3, 4]];

/// Blades narrower than this many pixels are thinned out and the rest widened to it.
const MIN_BLADE_PX: f32 = 1.0;

/// A number in `[0, 1)` fixed for each blade index (the first draw of a
/// SplitMix64 seeded with the index).
fn unit_hash(index: u32) -> f32 {
    SplitMix64::new(u64::from(index)).next_f32()
}

/// A blade to draw: its index, drawn width and root distance from the eye.
#[derive(Debug, Clone, Copy, PartialEq)]
struct DrawnBlade {
    index: u32,
    width: f32,
    distance: f32,
}

/// The blades to draw, from the nearest root to the farthest (ties by index).
///
/// Level of detail: a blade whose root is narrower than [`MIN_BLADE_PX`] on screen
/// is kept with a probability equal to its width in those pixels (a fixed draw
/// per blade, so a blade fades out once, at one distance) and widened to
/// [`MIN_BLADE_PX`]: the meadow keeps its covered area while far blades cost
/// fewer, fuller rows. Front to back, most hidden pixels fail the depth test
/// early instead of being shaded and then overwritten.
///
/// Blades wholly outside one side of the view (or behind the near plane) are
/// left out here, before any other work: set-up would cull them anyway.
fn drawn_blades(blades: &[GrassBlade], camera: &Camera) -> Vec<DrawnBlade> {
    let focal = camera.focal_px();
    let planes = camera.frustum_planes();
    let mut keys: Vec<(u64, f32)> = blades
        .par_iter()
        .enumerate()
        .filter_map(|(k, b)| {
            let distance = b.root.distance(camera.eye);
            let px = b.width * focal / distance.max(1e-6);
            let width = if px >= MIN_BLADE_PX {
                b.width
            } else if unit_hash(k as u32) * MIN_BLADE_PX < px {
                b.width * MIN_BLADE_PX / px
            } else {
                return None;
            };
            if outside_view(&planes, b, width) {
                return None;
            }
            // Non-negative floats order like their bit patterns; the index breaks ties.
            Some(((u64::from(distance.to_bits()) << 32) | k as u64, width))
        })
        .collect();
    sort_by_distance(&mut keys);
    keys.into_iter()
        .map(|(key, width)| DrawnBlade {
            index: key as u32,
            width,
            distance: f32::from_bits((key >> 32) as u32),
        })
        .collect()
}

/// Whether a blade drawn `width` wide lies wholly outside one of the side
/// and near planes of the view: the ball around its root through its mid
/// point and tip holds its five vertices. The margin keeps the test
/// conservative against the rounding of the clip-space test in set-up.
fn outside_view(planes: &[Vec4; 6], blade: &GrassBlade, width: f32) -> bool {
    let radius = blade.mid.distance(blade.root) + blade.tip.distance(blade.mid) + width;
    // The far plane is left to the depth test, as in set-up.
    planes[..5].iter().any(|p| {
        let normal = p.truncate();
        normal.dot(blade.root) + p.w < -(1.001 * radius + 1e-3) * normal.length()
    })
}

/// Sorts blade keys (root distance bits above the blade index, in index order)
/// by distance, keeping index order among equal distances: the order of the
/// whole key. A radix sort, a byte of the distance per pass (passes where all
/// keys share the byte are skipped); a comparison sort cost about four times
/// as much.
fn sort_by_distance(keys: &mut Vec<(u64, f32)>) {
    let mut spare = vec![(0u64, 0f32); keys.len()];
    for shift in (32..64).step_by(8) {
        let digit = |key: u64| ((key >> shift) & 0xff) as usize;
        let mut starts = [0usize; 257];
        for &(key, _) in keys.iter() {
            starts[digit(key) + 1] += 1;
        }
        if starts.contains(&keys.len()) {
            continue;
        }
        for d in 0..256 {
            starts[d + 1] += starts[d];
        }
        for &item in keys.iter() {
            let d = digit(item.0);
            spare[starts[d]] = item;
            starts[d] += 1;
        }
        std::mem::swap(keys, &mut spare);
    }
}

/// The grass of one frame, set up for the bands: the blades' pieces binned by
/// bands of rows, nearest blade first, and, drawn before them, the few blades
/// that cross the near plane or leave the guard band, clipped as triangles.
#[derive(Debug, Default)]
pub(crate) struct GrassLayer {
    /// Clipped blades, through the triangle pipeline.
    clipped: TriangleBatch,
    /// Each blade's lower quad then its tip, nearest blade first, as set up
    /// by each group of blades (kept apart: concatenating them would copy
    /// megabytes per frame).
    pieces: Vec<Vec<BladePiece>>,
    /// Piece ids of each band, in drawing order: group index above
    /// [`GROUP_BITS`] bits, index within the group below.
    bins: BandBins,
}

/// What one group of blades turns into.
#[derive(Default)]
struct BladeGroup {
    pieces: Vec<BladePiece>,
    clipped_verts: Vec<ClipVertex>,
    clipped_tris: Vec<[u32; 3]>,
}

impl GrassLayer {
    /// Projects the drawn blades (in parallel groups of [`BLADES_PER_BATCH`]),
    /// sets up their pieces and bins them by bands.
    pub fn build(blades: &[GrassBlade], view: &FrameView<'_>) -> GrassLayer {
        let (camera, vp) = (view.camera, view.vp);
        let groups: Vec<BladeGroup> = drawn_blades(blades, camera)
            .par_chunks(BLADES_PER_BATCH)
            .map(|chunk| {
                let mut group = BladeGroup {
                    pieces: Vec::with_capacity(2 * chunk.len()),
                    ..BladeGroup::default()
                };
                for drawn in chunk {
                    let blade = &blades[drawn.index as usize];
                    group.add(blade, drawn, view);
                }
                group
            })
            .collect();
        let mut layer = GrassLayer::default();
        let mut clipped_verts = Vec::new();
        let mut clipped_tris = Vec::new();
        for group in groups {
            layer.pieces.push(group.pieces);
            let base = clipped_verts.len() as u32;
            clipped_verts.extend(group.clipped_verts);
            clipped_tris.extend(group.clipped_tris.iter().map(|t| t.map(|v| v + base)));
        }
        layer.clipped = TriangleBatch::build(
            &clipped_verts,
            &[TriangleGroup {
                triangles: &clipped_tris,
                cull: CullMode::None,
                first_vertex: 0,
            }],
            None,
            vp,
        );
        layer.bin(vp.height);
        layer
    }

    /// Sorts the pieces into per-band lists (order kept).
    fn bin(&mut self, height: i32) {
        self.bins = BandBins::new(height);
        for (g, group) in self.pieces.iter().enumerate() {
            for (k, piece) in group.iter().enumerate() {
                // A piece's rows lie on the screen (its runs are clamped to it).
                self.bins
                    .push(((g as u32) << GROUP_BITS) | k as u32, piece.rows());
            }
        }
    }

    /// Blade pieces plus clipped triangles set up.
    pub fn len(&self) -> usize {
        self.piece_count() + self.clipped.len()
    }

    /// Blade pieces set up.
    fn piece_count(&self) -> usize {
        self.pieces.iter().map(Vec::len).sum()
    }

    /// Draws the grass touching band `band` (of `BAND_ROWS` rows): clipped
    /// blades, then the pieces, nearest blade first.
    #[inline(always)]
    pub fn draw_band(&self, band: i32, target: &mut Band<'_>) {
        self.clipped.draw_band(band, target, None);
        for &p in self.bins.band(band) {
            let group = &self.pieces[(p >> GROUP_BITS) as usize];
            group[(p & ((1 << GROUP_BITS) - 1)) as usize].draw(target);
        }
    }
}

impl BladeGroup {
    /// Adds one blade: culled when its five vertices lie outside one frustum
    /// plane, clipped as triangles when crossing the near plane or the guard
    /// band, otherwise set up as one piece (its outline, when no row meets it
    /// twice) or two (its lower quad and its tip).
    fn add(&mut self, blade: &GrassBlade, drawn: &DrawnBlade, view: &FrameView<'_>) {
        let vp = view.vp;
        let pos = blade_clip_positions(blade, drawn.width, view.camera, &view.view_proj);
        let (mut all, mut any) = (OUT_FRUSTUM, 0);
        for p in pos {
            let code = outcode(p);
            all &= code;
            any |= code;
        }
        if all != 0 {
            return;
        }
        let sun = [blade.root, blade.tip].map(|p| view.sun_past_casters(p, Vec3::ZERO));
        let colors = blade_colors(blade, drawn.distance, view.lighting, sun);
        if any & (OUT_NEAR | OUT_GUARD) != 0 {
            let base = self.clipped_verts.len() as u32;
            self.clipped_verts
                .extend((pos.iter().zip(&colors)).map(|(&pos, &color)| ClipVertex {
                    pos,
                    color,
                    sun: Vec3::ZERO,
                }));
            self.clipped_tris
                .extend(BLADE_TRIANGLES.iter().map(|t| t.map(|v| v + base)));
            return;
        }
        let (half_w, half_h) = (0.5 * vp.width as f32, 0.5 * vp.height as f32);
        let project = |k: usize| {
            let inv_w = 1.0 / pos[k].w;
            SpanVertex {
                x: (pos[k].x * inv_w + 1.0) * half_w,
                y: (1.0 - pos[k].y * inv_w) * half_h,
                inv_w,
                color: colors[k],
            }
        };
        let s = [project(0), project(1), project(2), project(3), project(4)];
        let outline = [s[0], s[1], s[3], s[4], s[2]];
        match BladePiece::setup(&outline, vp.height) {
            Ok(piece) => self.pieces.extend(piece),
            Err(NotMonotone) => {
                // Convex: always monotone.
                let quad = BladePiece::setup(&[s[0], s[1], s[3], s[2]], vp.height);
                let tip = BladePiece::setup(&[s[2], s[3], s[4]], vp.height);
                self.pieces.extend(quad.ok().flatten());
                self.pieces.extend(tip.ok().flatten());
            }
        }
    }
}

/// A blade's five clip-space vertices: the root pair, the middle pair (0.6 of
/// the root width) and the tip, facing the camera. Clip space is linear in the
/// world point, so the side offset is transformed once.
fn blade_clip_positions(
    blade: &GrassBlade,
    width: f32,
    camera: &Camera,
    view_proj: &Mat4,
) -> [Vec4; 5] {
    let axis = blade.tip - blade.root;
    let side = axis
        .cross(camera.eye - blade.root)
        .try_normalize()
        .unwrap_or(Vec3::X)
        * (0.5 * width);
    let side = *view_proj * side.extend(0.0);
    let to_clip = |p: Vec3| *view_proj * p.extend(1.0);
    let (root, mid) = (to_clip(blade.root), to_clip(blade.mid));
    [
        root - side,
        root + side,
        mid - side * 0.6,
        mid + side * 0.6,
        to_clip(blade.tip),
    ]
}

/// The colours of a blade's five vertices: darker at the root (self-shadowing
/// in the sward), lit at the tip, each end dimmed by the sun reaching it
/// past the shadow casters (`sun`: root, tip), fogged once at the root's
/// `distance` (a blade is short against the fog's scale).
fn blade_colors(
    blade: &GrassBlade,
    distance: f32,
    lighting: &Lighting,
    [sun_root, sun_tip]: [f32; 2],
) -> [Vec3; 5] {
    let fog = |c: Vec3| lighting.apply_fog(c, distance);
    let low = fog(encode_display(lighting.radiance(
        blade.color,
        Vec3::Y,
        0.45,
        0.35 * sun_root,
    )));
    let high = fog(encode_display(lighting.radiance(
        blade.color,
        Vec3::Y,
        1.0,
        0.9 * sun_tip,
    )));
    let mid = low.lerp(high, 0.6);
    [low, low, mid, mid, high]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::raster::Viewport;

    fn row_of_blades(count: usize) -> Vec<GrassBlade> {
        (0..count)
            .map(|k| {
                let root = Vec3::new(k as f32 * 0.001, 0.0, 0.0);
                GrassBlade {
                    root,
                    mid: root + Vec3::Y * 0.15,
                    tip: root + Vec3::Y * 0.3,
                    width: 0.01,
                    color: Vec3::new(0.2, 0.5, 0.1),
                }
            })
            .collect()
    }

    #[test]
    fn distance_sort_orders_by_whole_key() {
        let mut seed = 7u64;
        let mut keys: Vec<(u64, f32)> = (0..3000u64)
            .map(|k| {
                seed = seed.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1);
                // Few distinct distances, so that ties are common.
                let distance = 1.0 + ((seed >> 33) % 50) as f32 * 0.37;
                ((u64::from(distance.to_bits()) << 32) | k, k as f32)
            })
            .collect();
        let mut expected = keys.clone();
        expected.sort_unstable_by_key(|&(key, _)| key);
        sort_by_distance(&mut keys);
        assert_eq!(keys, expected);
    }

    #[test]
    fn far_blades_are_thinned_keeping_their_covered_width() {
        let blades = row_of_blades(4000);
        // Level of detail and order.
        let camera = |z: f32| {
            Camera::perspective(0.9, 640, 400, 0.05, 500.0)
                .unwrap()
                .look_at(Vec3::new(2.0, 0.2, z), Vec3::new(2.0, 0.0, 0.0), Vec3::Y)
        };
        // Near (the whole row in view): every blade at its own width, nearest first.
        let near = drawn_blades(&blades, &camera(-3.0));
        assert_eq!(near.len(), blades.len());
        assert!(near.iter().all(|d| d.width == 0.01));
        let distance = |k: u32| blades[k as usize].root.distance(camera(-3.0).eye);
        assert!(near.iter().all(|d| d.distance == distance(d.index)));
        assert!(
            near.windows(2)
                .all(|p| distance(p[0].index) <= distance(p[1].index))
        );
        // Far (a root spans about a quarter of a pixel): about a quarter is kept,
        // widened so that the summed width stays about the same.
        let far = drawn_blades(&blades, &camera(-16.5));
        let kept = far.len() as f32 / blades.len() as f32;
        assert!((0.15..0.35).contains(&kept), "kept {kept}");
        let total: f32 = far.iter().map(|d| d.width).sum();
        let original = 0.01 * blades.len() as f32;
        assert!(
            (total / original - 1.0).abs() < 0.15,
            "{total} vs {original}"
        );
        assert!(far.iter().all(|d| d.width > 0.01));
    }

    #[test]
    fn blades_outside_the_view_are_left_out() {
        // 1 m from the middle of a 4 m row, the view spans about 0.8 m either
        // side (a blade reaches 0.3 m further): the ends of the row are
        // dropped, the middle is kept.
        let blades = row_of_blades(4000);
        let camera = Camera::perspective(0.9, 640, 400, 0.05, 500.0)
            .unwrap()
            .look_at(Vec3::new(2.0, 0.2, -1.0), Vec3::new(2.0, 0.0, 0.0), Vec3::Y);
        let drawn = drawn_blades(&blades, &camera);
        let x = |d: &DrawnBlade| blades[d.index as usize].root.x;
        assert!(drawn.iter().all(|d| (x(d) - 2.0).abs() < 1.5));
        let middle = blades
            .iter()
            .filter(|b| (b.root.x - 2.0).abs() < 0.5)
            .count();
        let kept_middle = drawn.iter().filter(|d| (x(d) - 2.0).abs() < 0.5).count();
        assert_eq!(kept_middle, middle);
        assert!(10 * drawn.len() < 7 * blades.len(), "{} drawn", drawn.len());
    }

    #[test]
    fn blades_through_the_near_plane_are_clipped_the_rest_become_pieces() {
        // Far ahead, a row of upright blades; right at the eye, one blade
        // leaning away from it, its root 2 cm ahead (inside the near distance).
        let mut blades: Vec<GrassBlade> = row_of_blades(40)
            .into_iter()
            .map(|b| GrassBlade {
                root: b.root + Vec3::new(-0.02, -0.1, 1.0),
                mid: b.mid + Vec3::new(-0.02, -0.1, 1.0),
                tip: b.tip + Vec3::new(-0.02, -0.1, 1.0),
                ..b
            })
            .collect();
        let root = Vec3::new(0.0, -0.05, 0.02);
        blades.push(GrassBlade {
            root,
            mid: root + Vec3::new(0.0, 0.05, 0.15),
            tip: root + Vec3::new(0.0, 0.08, 0.3),
            width: 0.01,
            color: Vec3::new(0.2, 0.5, 0.1),
        });
        let camera = Camera::perspective(0.9, 160, 100, 0.05, 50.0)
            .unwrap()
            .look_at(Vec3::ZERO, Vec3::Z, Vec3::Y);
        let vp = Viewport {
            width: 160,
            height: 100,
        };
        let lighting = Lighting::default();
        let view = FrameView::new(&camera, &lighting, None, vp);
        let layer = GrassLayer::build(&blades, &view);
        assert!(
            layer.clipped.len() > 0,
            "the blade around the eye is clipped"
        );
        // The row ahead is on screen: a quad and a tip per blade at most.
        let pieces = layer.piece_count();
        assert!(pieces > blades.len() / 2);
        assert!(pieces <= 2 * (blades.len() - 1));
        assert_eq!(layer.len(), pieces + layer.clipped.len());
    }
}
