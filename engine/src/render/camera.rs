use glam::{Mat4, Vec2, Vec3, Vec4};

use super::error::{RenderError, positive};

/// A perspective camera looking from `eye` at `target` (right handed, Y up).
///
/// The viewport size in pixels is part of the camera so that [`Camera::project`]
/// gives pixel coordinates; render with a [`super::Renderer`] of the same size.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Camera {
    /// Eye position.
    pub eye: Vec3,
    /// Point looked at.
    pub target: Vec3,
    /// Approximate up direction.
    pub up: Vec3,
    /// Vertical field of view in radians.
    pub fov_y: f32,
    /// Near plane distance (geometry closer than this is clipped).
    pub near: f32,
    /// Far plane distance (used to cull terrain patches).
    pub far: f32,
    /// Viewport width in pixels.
    pub width: u32,
    /// Viewport height in pixels.
    pub height: u32,
}

impl Camera {
    /// A camera with vertical field of view `fov_y` (radians) for a `width` x `height`
    /// pixel viewport (aspect = width / height) and near/far distances, looking
    /// down -Z from the origin until [`Camera::look_at`] is called.
    pub fn perspective(
        fov_y: f32,
        width: u32,
        height: u32,
        near: f32,
        far: f32,
    ) -> Result<Camera, RenderError> {
        positive("fov_y", fov_y)?;
        if fov_y >= std::f32::consts::PI {
            return Err(RenderError::InvalidParameter {
                name: "fov_y",
                reason: format!("{fov_y} rad must be below pi"),
            });
        }
        if width == 0 || height == 0 {
            return Err(RenderError::InvalidParameter {
                name: "viewport",
                reason: format!("{width} x {height} pixels is empty"),
            });
        }
        positive("near", near)?;
        positive("far", far)?;
        if far <= near {
            return Err(RenderError::InvalidParameter {
                name: "far",
                reason: format!("{far} must exceed near = {near}"),
            });
        }
        Ok(Camera {
            eye: Vec3::ZERO,
            target: Vec3::NEG_Z,
            up: Vec3::Y,
            fov_y,
            near,
            far,
            width,
            height,
        })
    }

    /// The same camera placed at `eye`, looking at `target`, with `up` as the up hint.
    pub fn look_at(mut self, eye: Vec3, target: Vec3, up: Vec3) -> Camera {
        self.eye = eye;
        self.target = target;
        self.up = up;
        self
    }

    /// Width over height.
    pub fn aspect(&self) -> f32 {
        self.width as f32 / self.height as f32
    }

    /// Unit viewing direction; -Z when eye and target coincide.
    pub fn forward(&self) -> Vec3 {
        (self.target - self.eye)
            .try_normalize()
            .unwrap_or(Vec3::NEG_Z)
    }

    /// The world-to-view matrix. A degenerate up hint (parallel to the view
    /// direction) is replaced by a perpendicular axis.
    pub fn view(&self) -> Mat4 {
        let (s, u, f) = self.basis();
        Mat4::from_cols(
            Vec4::new(s.x, u.x, -f.x, 0.0),
            Vec4::new(s.y, u.y, -f.y, 0.0),
            Vec4::new(s.z, u.z, -f.z, 0.0),
            Vec4::new(-self.eye.dot(s), -self.eye.dot(u), self.eye.dot(f), 1.0),
        )
    }

    /// The view's unit axes in the world: right, up and forward. A
    /// degenerate up hint (parallel to the view direction) is replaced by a
    /// perpendicular axis.
    fn basis(&self) -> (Vec3, Vec3, Vec3) {
        let f = self.forward();
        let up = if self.up.cross(f).length_squared() > 1e-12 {
            self.up
        } else if f.cross(Vec3::Z).length_squared() > 1e-12 {
            Vec3::Z
        } else {
            Vec3::X
        };
        let s = f.cross(up).normalize();
        (s, s.cross(f), f)
    }

    /// The world point seen at clip coordinates `x`, `y` and `w` (the depth
    /// along the view direction), as the matrix taking `(x, y, w, 1)` to it:
    /// the inverse of the projection for points known by their `w`.
    pub fn clip_to_world(&self) -> Mat4 {
        let (s, u, f) = self.basis();
        let focal = self.focal();
        Mat4::from_cols(
            (s * (self.aspect() / focal)).extend(0.0),
            (u / focal).extend(0.0),
            f.extend(0.0),
            self.eye.extend(1.0),
        )
    }

    /// The projection's focal factor, `1 / tan(fov_y / 2)`.
    fn focal(&self) -> f32 {
        1.0 / (0.5 * self.fov_y).tan()
    }

    /// The view-to-clip matrix (clip depth in `[0, w]`).
    pub fn proj(&self) -> Mat4 {
        let f = self.focal();
        let depth = self.far / (self.near - self.far);
        Mat4::from_cols(
            Vec4::new(f / self.aspect(), 0.0, 0.0, 0.0),
            Vec4::new(0.0, f, 0.0, 0.0),
            Vec4::new(0.0, 0.0, depth, -1.0),
            Vec4::new(0.0, 0.0, self.near * depth, 0.0),
        )
    }

    /// World-to-clip matrix.
    pub fn view_proj(&self) -> Mat4 {
        self.proj() * self.view()
    }

    /// Focal length in pixels: how many pixels one metre spans at one metre distance.
    pub fn focal_px(&self) -> f32 {
        0.5 * self.height as f32 / (0.5 * self.fov_y).tan()
    }

    /// Pixel coordinates (x right, y down, pixel centres at `.5`) of a world point,
    /// or `None` when it lies behind the near plane.
    pub fn project(&self, world: Vec3) -> Option<Vec2> {
        let clip = self.view_proj() * world.extend(1.0);
        if !clip.is_finite() || clip.w < self.near * 0.999 {
            return None;
        }
        let ndc = Vec2::new(clip.x, clip.y) / clip.w;
        Some(Vec2::new(
            (ndc.x * 0.5 + 0.5) * self.width as f32,
            (0.5 - ndc.y * 0.5) * self.height as f32,
        ))
    }

    /// The six frustum planes (left, right, bottom, top, near, far) as
    /// `a x + b y + c z + d >= 0` inside.
    pub fn frustum_planes(&self) -> [Vec4; 6] {
        let m = self.view_proj();
        let (r0, r1, r2, r3) = (m.row(0), m.row(1), m.row(2), m.row(3));
        [r3 + r0, r3 - r0, r3 + r1, r3 - r1, r2, r3 - r2]
    }

    /// True when the axis-aligned box `[min, max]` may be visible (conservative).
    pub fn sees_box(&self, planes: &[Vec4; 6], min: Vec3, max: Vec3) -> bool {
        planes.iter().all(|p| {
            let corner = Vec3::new(
                if p.x >= 0.0 { max.x } else { min.x },
                if p.y >= 0.0 { max.y } else { min.y },
                if p.z >= 0.0 { max.z } else { min.z },
            );
            p.truncate().dot(corner) + p.w >= 0.0
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cam() -> Camera {
        Camera::perspective(1.0, 200, 100, 0.1, 100.0)
            .unwrap()
            .look_at(Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO, Vec3::Y)
    }

    #[test]
    fn projects_centre_and_rejects_behind() {
        let c = cam();
        let p = c.project(Vec3::ZERO).unwrap();
        assert!((p - Vec2::new(100.0, 50.0)).length() < 1e-3);
        // Up in the world is up on screen (smaller y); right is right.
        assert!(c.project(Vec3::Y).unwrap().y < 50.0);
        assert!(c.project(Vec3::X).unwrap().x > 100.0);
        assert_eq!(c.project(Vec3::new(0.0, 0.0, 10.0)), None);
    }

    #[test]
    fn clip_to_world_undoes_the_projection() {
        let c = cam().look_at(Vec3::new(1.0, 2.0, 3.0), Vec3::new(-0.5, 0.2, 0.0), Vec3::Y);
        let back = c.clip_to_world();
        for p in [
            Vec3::ZERO,
            Vec3::new(0.3, -0.4, 0.2),
            Vec3::new(-2.0, 1.0, -4.0),
        ] {
            let clip = c.view_proj() * p.extend(1.0);
            let seen = back * Vec4::new(clip.x, clip.y, clip.w, 1.0);
            assert!(
                (seen.truncate() - p).length() < 1e-4,
                "{p} came back as {seen}"
            );
            assert_eq!(seen.w, 1.0);
        }
    }

    #[test]
    fn refuses_bad_parameters() {
        assert!(Camera::perspective(f32::NAN, 10, 10, 0.1, 1.0).is_err());
        assert!(Camera::perspective(1.0, 0, 10, 0.1, 1.0).is_err());
        assert!(Camera::perspective(1.0, 10, 10, 1.0, 0.5).is_err());
        assert!(Camera::perspective(4.0, 10, 10, 0.1, 1.0).is_err());
    }

    #[test]
    fn frustum_culls_boxes_behind() {
        let c = cam();
        let planes = c.frustum_planes();
        assert!(c.sees_box(&planes, Vec3::splat(-0.5), Vec3::splat(0.5)));
        assert!(!c.sees_box(
            &planes,
            Vec3::new(-1.0, -1.0, 6.0),
            Vec3::new(1.0, 1.0, 8.0)
        ));
        assert!(!c.sees_box(
            &planes,
            Vec3::new(50.0, -1.0, -1.0),
            Vec3::new(51.0, 1.0, 1.0)
        ));
    }

    #[test]
    fn degenerate_up_still_gives_a_finite_view() {
        let c = cam().look_at(Vec3::new(0.0, 5.0, 0.0), Vec3::ZERO, Vec3::Y);
        assert!(c.view_proj().is_finite());
        assert!(c.project(Vec3::ZERO).is_some());
    }
}
