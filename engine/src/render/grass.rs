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

/// Blade indices from the nearest root to the farthest (ties by index).
///
/// Drawing a dense meadow front to back makes most hidden pixels fail the depth
/// test early instead of being shaded and then overwritten.
fn front_to_back(blades: &[GrassBlade], eye: Vec3) -> Vec<u32> {
    // Non-negative floats order like their bit patterns; the index breaks ties.
    let mut keys: Vec<u64> = blades
        .par_iter()
        .enumerate()
        .map(|(k, b)| (u64::from(b.root.distance_squared(eye).to_bits()) << 32) | k as u64)
        .collect();
    keys.par_sort_unstable();
    keys.into_iter().map(|key| key as u32).collect()
}

/// Projects blades, nearest first, into screen batches of [`BLADES_PER_BATCH`].
pub(crate) fn blade_batches(
    blades: &[GrassBlade],
    camera: &Camera,
    lighting: &Lighting,
    vp: Viewport,
) -> Vec<ScreenBatch> {
    let view_proj = camera.view_proj();
    front_to_back(blades, camera.eye)
        .par_chunks(BLADES_PER_BATCH)
        .map(|chunk| {
            let mut verts = Vec::with_capacity(chunk.len() * 5);
            let mut tris = Vec::with_capacity(chunk.len() * 3);
            for blade in chunk.iter().map(|&k| &blades[k as usize]) {
                let base = verts.len() as u32;
                let axis = blade.tip - blade.root;
                let side = axis
                    .cross(camera.eye - blade.root)
                    .try_normalize()
                    .unwrap_or(Vec3::X)
                    * (0.5 * blade.width);
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
