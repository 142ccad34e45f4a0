//! How a frame sees the geometry it draws.

use glam::{Mat4, Vec3};

use super::camera::Camera;
use super::raster::{PixelShadow, Viewport};
use super::shading::Lighting;
use super::shadow_map::ShadowMap;

/// How a frame sees its scene: the camera, the light, the shadows and the
/// viewport.
#[derive(Clone, Copy)]
pub(crate) struct FrameView<'a> {
    /// The camera.
    pub camera: &'a Camera,
    /// Its world-to-clip matrix.
    pub view_proj: Mat4,
    /// Sun, sky and fog.
    pub lighting: &'a Lighting,
    /// What the sun sees of the scene's casters, when anything casts.
    shadows: Option<&'a ShadowMap>,
    /// The casters' shadows as the pixels see them, when anything casts.
    pub pixel_shadow: Option<PixelShadow<'a>>,
    /// The image's size.
    pub vp: Viewport,
}

impl<'a> FrameView<'a> {
    /// The view of `camera` with `lighting` and `shadows` over viewport `vp`.
    pub fn new(
        camera: &'a Camera,
        lighting: &'a Lighting,
        shadows: Option<&'a ShadowMap>,
        vp: Viewport,
    ) -> Self {
        FrameView {
            camera,
            view_proj: camera.view_proj(),
            lighting,
            shadows,
            pixel_shadow: shadows.map(|map| PixelShadow::new(map, camera, vp)),
            vp,
        }
    }

    /// How much of the sun reaches world point `p` past the shadow casters
    /// (0 in shadow, 1 lit), on a surface with unit `normal` (zero for a
    /// point without one, such as a blade).
    #[inline]
    pub fn sun_past_casters(&self, p: Vec3, normal: Vec3) -> f32 {
        self.shadows.map_or(1.0, |s| s.visibility(p, normal))
    }

    /// Whether a caster may shade some point of the world box `min..=max`
    /// (conservative).
    pub fn casters_may_shade(&self, min: Vec3, max: Vec3) -> bool {
        self.shadows.is_some_and(|s| s.may_shade_box(min, max))
    }
}
