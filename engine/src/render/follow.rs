use glam::Vec3;

use super::Camera;

/// Makes a camera follow a moving target (an entity position) smoothly.
///
/// The eye tends to `target + offset` and the look-at point to `target` with
/// exponential smoothing of time constant `smoothing` seconds (0 snaps). The
/// update depends only on its inputs, so a replay gives the same camera path.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CameraFollow {
    /// Eye position relative to the followed target.
    pub offset: Vec3,
    /// Time constant of the smoothing, in seconds (0 = no smoothing).
    pub smoothing: f32,
}

impl CameraFollow {
    /// Moves `camera` one step of `dt` seconds towards following `target`.
    pub fn update(&self, camera: &mut Camera, target: Vec3, dt: f32) {
        let blend = if self.smoothing > 0.0 && dt.is_finite() {
            1.0 - (-dt.max(0.0) / self.smoothing).exp()
        } else {
            1.0
        };
        camera.eye = camera.eye.lerp(target + self.offset, blend);
        camera.target = camera.target.lerp(target, blend);
    }

    /// Places `camera` exactly at its follow position (e.g. on the first frame).
    pub fn snap(&self, camera: &mut Camera, target: Vec3) {
        camera.eye = target + self.offset;
        camera.target = target;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn converges_smoothly_and_snaps() {
        let mut cam = Camera::perspective(1.0, 64, 64, 0.1, 50.0).unwrap();
        let follow = CameraFollow {
            offset: Vec3::new(0.0, 2.0, 4.0),
            smoothing: 0.25,
        };
        follow.snap(&mut cam, Vec3::ZERO);
        assert_eq!(cam.eye, Vec3::new(0.0, 2.0, 4.0));
        let target = Vec3::new(1.0, 0.0, 0.0);
        let mut last = f32::INFINITY;
        for _ in 0..60 {
            follow.update(&mut cam, target, 1.0 / 30.0);
            let gap = (cam.target - target).length();
            assert!(
                gap < last,
                "the camera must move monotonically towards the target"
            );
            last = gap;
        }
        assert!(last < 1e-3);
        assert!((cam.eye - (target + follow.offset)).length() < 1e-3);
    }
}
