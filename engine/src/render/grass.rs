//! Grass blades drawn as thin tapered triangle strips that face the camera.

use glam::Vec3;
use rayon::prelude::*;

use super::Camera;
use super::batch::{CullMode, ScreenBatch, TriangleGroup, Viewport, to_clip};
use super::clip::ClipVertex;
use super::shading::{Lighting, encode_display};

/// Blades per screen batch (the unit of parallel vertex work).
const BLADES_PER_BATCH: usize = 1024;

/// One grass blade: a curve through three points, tapering from `width` at the
/// root to a point at the tip.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GrassBlade {
    /// Where the blade leaves the ground.
    pub root: Vec3,
    /// A point halfway along the blade (bent blades move it).
    pub mid: Vec3,
    /// The blade's tip.
    pub tip: Vec3,
    /// Width at the root, in metres.
    pub width: f32,
    /// Linear RGB albedo.
    pub color: Vec3,
}

/// Triangles of one blade's five vertices: two for the lower half, one for the tip.
const BLADE_TRIANGLES: [[u32; 3]; 3] = [[0, 1, 3], [0, 3, 2], [2, 3, 4]];

/// Blades narrower than this many pixels are thinned out and the rest widened to it.
const MIN_BLADE_PX: f32 = 1.0;

/// A number in `[0, 1)` fixed for each blade index (a SplitMix64 finaliser).
fn unit_hash(index: u32) -> f32 {
    let mut z = u64::from(index).wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    ((z ^ (z >> 31)) >> 40) as f32 / (1u64 << 24) as f32
}

/// The blades to draw with their drawn widths, from the nearest root to the
/// farthest (ties by index).
///
/// Level of detail: a blade whose root is narrower than [`MIN_BLADE_PX`] on screen
/// is kept with a probability equal to its width in those pixels (a fixed draw
/// per blade, so a blade fades out once, at one distance) and widened to
/// [`MIN_BLADE_PX`]: the meadow keeps its covered area while far blades cost
/// fewer, fuller rows. Front to back, most hidden pixels fail the depth test
/// early instead of being shaded and then overwritten.
fn drawn_blades(blades: &[GrassBlade], camera: &Camera) -> Vec<(u32, f32)> {
    let focal = camera.focal_px();
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
            // Non-negative floats order like their bit patterns; the index breaks ties.
            Some(((u64::from(distance.to_bits()) << 32) | k as u64, width))
        })
        .collect();
    keys.par_sort_unstable_by_key(|&(key, _)| key);
    keys.into_iter().map(|(key, w)| (key as u32, w)).collect()
}

/// Projects the drawn blades, nearest first, into screen batches of [`BLADES_PER_BATCH`].
pub(crate) fn blade_batches(
    blades: &[GrassBlade],
    camera: &Camera,
    lighting: &Lighting,
    vp: Viewport,
) -> Vec<ScreenBatch> {
    let view_proj = camera.view_proj();
    drawn_blades(blades, camera)
        .par_chunks(BLADES_PER_BATCH)
        .map(|chunk| {
            let mut verts = Vec::with_capacity(chunk.len() * 5);
            let mut tris = Vec::with_capacity(chunk.len() * 3);
            for &(k, width) in chunk {
                let blade = &blades[k as usize];
                let base = verts.len() as u32;
                let axis = blade.tip - blade.root;
                let side = axis
                    .cross(camera.eye - blade.root)
                    .try_normalize()
                    .unwrap_or(Vec3::X)
                    * (0.5 * width);
                // Darker at the root (self-shadowing in the sward), lit at the tip.
                let low = encode_display(lighting.radiance(blade.color, Vec3::Y, 0.45, 0.35));
                let high = encode_display(lighting.radiance(blade.color, Vec3::Y, 1.0, 0.9));
                let mid_color = low.lerp(high, 0.6);
                let points = [
                    (blade.root - side, low),
                    (blade.root + side, low),
                    (blade.mid - side * 0.6, mid_color),
                    (blade.mid + side * 0.6, mid_color),
                    (blade.tip, high),
                ];
                for (p, c) in points {
                    verts.push(ClipVertex {
                        pos: to_clip(&view_proj, p),
                        color: lighting.apply_fog(c, (p - camera.eye).length()),
                    });
                }
                tris.extend(BLADE_TRIANGLES.iter().map(|t| t.map(|v| v + base)));
            }
            ScreenBatch::build(
                &verts,
                &[TriangleGroup {
                    triangles: &tris,
                    cull: CullMode::None,
                }],
                vp,
            )
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

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
    fn far_blades_are_thinned_keeping_their_covered_width() {
        let blades = row_of_blades(4000);
        let camera = |z: f32| {
            Camera::perspective(0.9, 640, 400, 0.05, 500.0)
                .unwrap()
                .look_at(Vec3::new(2.0, 0.2, z), Vec3::new(2.0, 0.0, 0.0), Vec3::Y)
        };
        // Near: every blade at its own width, nearest first.
        let near = drawn_blades(&blades, &camera(-1.0));
        assert_eq!(near.len(), blades.len());
        assert!(near.iter().all(|&(_, w)| w == 0.01));
        let distance = |k: u32| blades[k as usize].root.distance(camera(-1.0).eye);
        assert!(
            near.windows(2)
                .all(|p| distance(p[0].0) <= distance(p[1].0))
        );
        // Far (a root spans about a quarter of a pixel): about a quarter is kept,
        // widened so that the summed width stays about the same.
        let far = drawn_blades(&blades, &camera(-16.5));
        let kept = far.len() as f32 / blades.len() as f32;
        assert!((0.15..0.35).contains(&kept), "kept {kept}");
        let total: f32 = far.iter().map(|&(_, w)| w).sum();
        let original = 0.01 * blades.len() as f32;
        assert!(
            (total / original - 1.0).abs() < 0.15,
            "{total} vs {original}"
        );
        assert!(far.iter().all(|&(_, w)| w > 0.01));
    }
}
