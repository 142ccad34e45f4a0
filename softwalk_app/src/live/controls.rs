//! Keys to steering: WASD or the arrows move relative to the camera, Shift
//! hurries; the brush cycles through the loose grounds and grass.

use glam::Vec2;

/// Walking speed asked by a movement key, m/s.
pub const WALK_SPEED_M_S: f32 = 1.2;
/// Factor on the speed while Shift is held.
pub const RUN_FACTOR: f32 = 1.5;
/// The materials the brush cycles through, in order.
pub const BRUSH_MATERIALS: [&str; 5] = ["sand", "soil", "mud", "snow", "grass"];

/// The movement keys held this frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Held {
    /// W or Up: away from the camera.
    pub forward: bool,
    /// S or Down: towards the camera.
    pub back: bool,
    /// A or Left.
    pub left: bool,
    /// D or Right.
    pub right: bool,
}

/// The planar velocity (x, z) the held keys ask for, before the speed
/// factor, for a camera at `yaw` radians (the camera looks along
/// `(-sin yaw, -cos yaw)` on the ground): forward is away from the camera,
/// right is the screen's right. Diagonals are as fast as straight moves.
pub fn desired_velocity(held: Held, yaw: f32) -> Vec2 {
    let axis = |plus: bool, minus: bool| f32::from(u8::from(plus)) - f32::from(u8::from(minus));
    let ahead = axis(held.forward, held.back);
    let side = axis(held.right, held.left);
    let (s, c) = yaw.sin_cos();
    let forward = Vec2::new(-s, -c);
    let right = Vec2::new(c, -s);
    (forward * ahead + right * side).normalize_or_zero() * WALK_SPEED_M_S
}

/// The brush material after `current` (the first when `current` is not one).
pub fn next_brush(current: Option<&str>) -> &'static str {
    let at = current.and_then(|c| BRUSH_MATERIALS.iter().position(|m| *m == c));
    match at {
        Some(k) => BRUSH_MATERIALS[(k + 1) % BRUSH_MATERIALS.len()],
        None => BRUSH_MATERIALS[0],
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: Vec2, b: Vec2) -> bool {
        (a - b).length() < 1e-5
    }

    #[test]
    fn keys_move_relative_to_the_camera() {
        let w = Held {
            forward: true,
            ..Held::default()
        };
        // yaw 0: the camera stands on +z looking towards -z.
        assert!(close(desired_velocity(w, 0.0), Vec2::new(0.0, -1.2)));
        let d = Held {
            right: true,
            ..Held::default()
        };
        assert!(close(desired_velocity(d, 0.0), Vec2::new(1.2, 0.0)));
        // Turned a quarter: forward is now -x.
        let quarter = std::f32::consts::FRAC_PI_2;
        assert!(close(desired_velocity(w, quarter), Vec2::new(-1.2, 0.0)));
    }

    #[test]
    fn diagonals_are_not_faster_and_opposites_cancel() {
        let wd = Held {
            forward: true,
            right: true,
            ..Held::default()
        };
        assert!((desired_velocity(wd, 0.3).length() - WALK_SPEED_M_S).abs() < 1e-5);
        let ws = Held {
            forward: true,
            back: true,
            ..Held::default()
        };
        assert_eq!(desired_velocity(ws, 0.3), Vec2::ZERO);
        assert_eq!(desired_velocity(Held::default(), 1.0), Vec2::ZERO);
    }

    #[test]
    fn the_brush_cycles_through_the_grounds() {
        assert_eq!(next_brush(None), "sand");
        assert_eq!(next_brush(Some("sand")), "soil");
        assert_eq!(next_brush(Some("snow")), "grass");
        assert_eq!(next_brush(Some("grass")), "sand");
        assert_eq!(next_brush(Some("gravel")), "sand");
    }
}
