//! The viewer's camera: it orbits the followed character with the mouse,
//! zooms with the wheel, and follows smoothly.

use glam::Vec3;

/// The viewer's camera offset from the character when the scene's camera is
/// fixed, metres.
pub const DEFAULT_CAMERA_OFFSET: Vec3 = Vec3::new(0.5, 1.6, 4.0);

/// Radians turned per pixel of mouse drag.
const RADIANS_PER_PIXEL: f32 = 0.008;
/// Lowest and highest elevation above the ground, radians.
const PITCH_RANGE: (f32, f32) = (0.05, 1.45);
/// Nearest and farthest distance from the target, metres.
const DISTANCE_RANGE: (f32, f32) = (1.0, 30.0);
/// Distance change per wheel notch (multiplicative).
const ZOOM_PER_NOTCH: f32 = 0.9;
/// Time constant of the follow, seconds.
const FOLLOW_TIME_S: f32 = 0.25;
/// Height above the centre of mass the camera looks at, metres.
const LOOK_ABOVE_COM_M: f32 = 0.2;

/// A camera on a sphere around a target that follows a point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OrbitCamera {
    /// Angle about the vertical, radians: 0 puts the camera on +z of the target.
    pub yaw: f32,
    /// Elevation above the horizon, radians.
    pub pitch: f32,
    /// Distance to the target, metres.
    pub distance: f32,
    /// The point looked at.
    pub target: Vec3,
}

impl OrbitCamera {
    /// A camera at `offset` from `target` (its yaw, pitch and distance).
    pub fn from_offset(target: Vec3, offset: Vec3) -> Self {
        let distance = offset.length().clamp(DISTANCE_RANGE.0, DISTANCE_RANGE.1);
        let flat = offset.x.hypot(offset.z);
        OrbitCamera {
            yaw: offset.x.atan2(offset.z),
            pitch: offset.y.atan2(flat).clamp(PITCH_RANGE.0, PITCH_RANGE.1),
            distance,
            target,
        }
    }

    /// Turns by a mouse drag of `(dx, dy)` pixels: right drags turn the
    /// camera left round the target, down drags raise it.
    pub fn drag(&mut self, dx: f32, dy: f32) {
        self.yaw -= dx * RADIANS_PER_PIXEL;
        self.pitch = (self.pitch + dy * RADIANS_PER_PIXEL).clamp(PITCH_RANGE.0, PITCH_RANGE.1);
    }

    /// Zooms by `notches` of the wheel (positive: closer).
    pub fn zoom(&mut self, notches: f32) {
        self.distance = (self.distance * ZOOM_PER_NOTCH.powf(notches))
            .clamp(DISTANCE_RANGE.0, DISTANCE_RANGE.1);
    }

    /// Moves the target towards the centre of mass `com` over `dt` seconds.
    pub fn follow(&mut self, com: Vec3, dt: f32) {
        let goal = com + Vec3::Y * LOOK_ABOVE_COM_M;
        let t = 1.0 - (-dt.max(0.0) / FOLLOW_TIME_S).exp();
        self.target += (goal - self.target) * t;
    }

    /// Puts the target on the centre of mass `com` at once.
    pub fn snap(&mut self, com: Vec3) {
        self.target = com + Vec3::Y * LOOK_ABOVE_COM_M;
    }

    /// Where the camera stands.
    pub fn eye(&self) -> Vec3 {
        let (sy, cy) = self.yaw.sin_cos();
        let (sp, cp) = self.pitch.sin_cos();
        self.target + Vec3::new(sy * cp, sp, cy * cp) * self.distance
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_offset_round_trips_and_the_eye_keeps_its_distance() {
        let cam = OrbitCamera::from_offset(Vec3::ZERO, DEFAULT_CAMERA_OFFSET);
        assert!((cam.eye() - DEFAULT_CAMERA_OFFSET).length() < 1e-4);
        let mut turned = cam;
        turned.drag(120.0, 0.0);
        assert!((turned.eye().length() - cam.distance).abs() < 1e-4);
        assert!(turned.yaw < cam.yaw);
    }

    #[test]
    fn pitch_and_zoom_stay_in_range() {
        let mut cam = OrbitCamera::from_offset(Vec3::ZERO, Vec3::new(0.0, 1.0, 4.0));
        cam.drag(0.0, 1.0e4);
        assert_eq!(cam.pitch, PITCH_RANGE.1);
        cam.zoom(1.0e3);
        assert_eq!(cam.distance, DISTANCE_RANGE.0);
        cam.zoom(-1.0e3);
        assert_eq!(cam.distance, DISTANCE_RANGE.1);
        let before = cam.distance;
        cam.zoom(1.0);
        assert!(cam.distance < before);
    }

    #[test]
    fn following_closes_in_without_overshoot() {
        let mut cam = OrbitCamera::from_offset(Vec3::ZERO, Vec3::new(0.0, 1.0, 4.0));
        cam.snap(Vec3::ZERO);
        let com = Vec3::new(2.0, 0.0, 0.0);
        let mut last = 0.0;
        for _ in 0..120 {
            cam.follow(com, 1.0 / 60.0);
            assert!(cam.target.x >= last && cam.target.x <= 2.0);
            last = cam.target.x;
        }
        assert!((cam.target.x - 2.0).abs() < 0.01);
    }
}
