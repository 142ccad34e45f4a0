//! Caster shadows resolved per pixel: a pixel's light coordinates follow
//! from its position and its depth (`w`), and the sun shadow map says how
//! much sun reaches it. Triangles whose vertices carry a sun part
//! ([`super::ClipVertex::sun`]) are drawn this way where the map's coarse
//! grid says a caster may shade them.

use glam::{Mat4, Vec3, Vec4};

use super::viewport::Viewport;
use crate::render::camera::Camera;
use crate::render::shadow_map::ShadowMap;

/// The sun shadow map as the pixels of one camera see it.
#[derive(Debug, Clone, Copy)]
pub(crate) struct PixelShadow<'a> {
    /// The casters' shadow map.
    map: &'a ShadowMap,
    /// Clip coordinates `(x, y, w, 1)` to light coordinates.
    clip_to_light: Mat4,
    /// Light coordinates of the eye.
    eye: Vec3,
    /// Change of the light coordinates per unit of `w` through the centre
    /// of pixel (0, 0) ...
    ray: Vec3,
    /// ... and its change per pixel to the right ...
    ray_x: Vec3,
    /// ... and per pixel down.
    ray_y: Vec3,
}

impl<'a> PixelShadow<'a> {
    /// The pixels of `camera` over viewport `vp` looking up `map`.
    pub fn new(map: &'a ShadowMap, camera: &Camera, vp: Viewport) -> PixelShadow<'a> {
        let m = map.to_light() * camera.clip_to_world();
        let (width, height) = (vp.width as f32, vp.height as f32);
        // Pixel (x, y)'s centre has ndc (2 (x + 0.5) / width - 1,
        // 1 - 2 (y + 0.5) / height).
        let (cx, cy, cw) = (
            m.x_axis.truncate(),
            m.y_axis.truncate(),
            m.z_axis.truncate(),
        );
        PixelShadow {
            map,
            clip_to_light: m,
            eye: m.w_axis.truncate(),
            ray: cw + cx * (1.0 / width - 1.0) + cy * (1.0 - 1.0 / height),
            ray_x: cx * (2.0 / width),
            ray_y: cy * (-2.0 / height),
        }
    }

    /// The light coordinates of clip position `clip`, for [`Self::may_shade`].
    #[inline]
    pub fn light_point(&self, clip: Vec4) -> Vec3 {
        self.clip_to_light
            .transform_point3(Vec3::new(clip.x, clip.y, clip.w))
    }

    /// Whether a caster may shade some point of the triangle whose corners
    /// have light coordinates `corners` ([`Self::light_point`]; conservative).
    pub fn may_shade(&self, corners: [Vec3; 3]) -> bool {
        let [a, b, c] = corners;
        self.map.may_shade(a.min(b).min(c), a.max(b).max(c))
    }

    /// How much sun reaches the surface seen at pixel `(x, y)` at depth `w`.
    #[inline]
    pub fn visibility(&self, x: i32, y: i32, w: f32) -> f32 {
        let ray = self.ray + self.ray_x * x as f32 + self.ray_y * y as f32;
        self.map.visibility_at(self.eye + ray * w)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::test_ground::floating_square;

    #[test]
    fn a_pixel_sees_the_shadow_its_ground_point_is_in() {
        // The sun straight above a floating square: its shadow is the
        // square below it on the ground.
        let casters = floating_square();
        let camera = Camera::perspective(1.0, 64, 48, 0.05, 50.0)
            .unwrap()
            .look_at(Vec3::new(0.3, 3.0, -4.0), Vec3::ZERO, Vec3::Y);
        let map = ShadowMap::build(&casters, &[], Vec3::Y, &camera, Some(0.0)).unwrap();
        let vp = Viewport {
            width: 64,
            height: 48,
        };
        let pixels = PixelShadow::new(&map, &camera, vp);
        let vp_mat = camera.view_proj();
        for (ground, lit) in [
            (Vec3::new(0.2, 0.0, -0.3), 0.0),
            (Vec3::new(-0.4, 0.0, 0.4), 0.0),
            (Vec3::new(0.8, 0.0, 0.0), 1.0),
            (Vec3::new(0.0, 0.0, -1.0), 1.0),
        ] {
            // The pixel whose centre sees `ground`: place `ground` at one.
            let px = camera.project(ground).unwrap().floor();
            let clip = vp_mat * ground.extend(1.0);
            let ndc = (px + 0.5) / glam::Vec2::new(32.0, -24.0) + glam::Vec2::new(-1.0, 1.0);
            let seen =
                camera.clip_to_world() * Vec4::new(ndc.x * clip.w, ndc.y * clip.w, clip.w, 1.0);
            let expected = map.visibility_at(map.to_light().transform_point3(seen.truncate()));
            let got = pixels.visibility(px.x as i32, px.y as i32, clip.w);
            assert!(
                (got - expected).abs() < 1e-4,
                "{ground}: {got} vs {expected}"
            );
            assert_eq!(got.round(), lit, "{ground}");
            let corner = pixels.light_point(clip);
            assert_eq!(pixels.may_shade([corner; 3]), lit == 0.0, "{ground}");
        }
    }
}
