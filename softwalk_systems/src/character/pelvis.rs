//! The pelvis height as a critically damped follower: it goes after the
//! height the legs need with a bounded speed and acceleration, so a deeper
//! print or a foot that cannot reach lowers the body smoothly, never in one
//! step. The target's own rate (bounded too) is fed forward, so a steady
//! slope is followed without lag.

/// Time constant of the follower, seconds (critically damped: no overshoot
/// without the bounds).
pub const PELVIS_RESPONSE_TIME: f32 = 0.08;
/// Fastest the pelvis base moves relative to the ground's own rise under
/// the walk, m/s (the gait's bob comes on top).
pub const PELVIS_MAX_SPEED: f32 = 0.2;
/// Largest acceleration of the pelvis base, m/s².
pub const PELVIS_MAX_ACCELERATION: f32 = 6.0;
/// Fastest the pelvis, its base and the gait's bob together, rises relative
/// to the ground's own rise when it climbs a step, m/s (0.67 cm per 60 Hz
/// step): the climb takes what the bob leaves (see [`climb_speed`]).
pub const PELVIS_MAX_CLIMB_SPEED: f32 = 0.4;

/// How much faster than [`PELVIS_MAX_SPEED`] the pelvis base may rise this
/// step, m/s, to climb a step `rise` metres high in `time` seconds while
/// the bob raises the pelvis at `bob_rate` m/s: never so fast that base
/// and bob together rise faster than [`PELVIS_MAX_CLIMB_SPEED`].
pub fn climb_speed(rise: f32, time: f32, bob_rate: f32) -> f32 {
    let wanted = rise.max(0.0) / time.max(f32::EPSILON);
    let room = PELVIS_MAX_CLIMB_SPEED - PELVIS_MAX_SPEED - bob_rate.max(0.0);
    wanted.min(room.max(0.0))
}

/// The pelvis base height (the walking height's floor) and its vertical speed.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PelvisFollower {
    /// Current base height, metres.
    pub height: f32,
    /// Current vertical speed, m/s.
    pub speed: f32,
    /// The target of the last step, metres (its rate of change is fed
    /// forward, so a steady slope is followed without lag).
    pub last_target: f32,
    /// False until the first step places it.
    pub placed: bool,
}

impl PelvisFollower {
    /// Moves towards `target` over `dt` seconds while the ground under the
    /// body rises at `ground_rate` m/s (its slope times the walking speed):
    /// the bounds apply to the motion relative to that ground, so a steep
    /// slope is followed at its own pace. Climbing a step, the pelvis may
    /// rise `climb` m/s faster (see [`climb_speed`]). A `dt` of 0 (or the
    /// first call) jumps to the target at rest.
    pub fn follow(&mut self, target: f32, ground_rate: f32, climb: f32, dt: f32) -> f32 {
        if dt <= 0.0 || !self.placed {
            *self = PelvisFollower {
                height: target,
                speed: ground_rate,
                last_target: target,
                placed: true,
            };
            return self.height;
        }
        let up = PELVIS_MAX_SPEED + climb.max(0.0);
        let (lo, hi) = (ground_rate - PELVIS_MAX_SPEED, ground_rate + up);
        let w = 1.0 / PELVIS_RESPONSE_TIME;
        let target_speed = ((target - self.last_target) / dt).clamp(lo, hi);
        self.last_target = target;
        let pull = w * w * (target - self.height) + 2.0 * w * (target_speed - self.speed);
        let accel = pull.clamp(-PELVIS_MAX_ACCELERATION, PELVIS_MAX_ACCELERATION);
        self.speed = (self.speed + accel * dt).clamp(lo, hi);
        self.height += self.speed * dt;
        self.height
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_step_in_the_target_is_followed_within_the_bounds() {
        let mut p = PelvisFollower::default();
        p.follow(1.0, 0.0, 0.0, 0.0);
        let dt = 1.0 / 60.0;
        let mut last = p.height;
        for _ in 0..120 {
            let h = p.follow(0.7, 0.0, 0.0, dt);
            assert!((last - h).abs() <= PELVIS_MAX_SPEED * dt + 1e-6);
            assert!(h >= 0.7 - 1e-3, "no undershoot: {h}");
            last = h;
        }
        assert!((p.height - 0.7).abs() < 1e-3);
    }

    #[test]
    fn a_step_is_climbed_faster_but_base_and_bob_never_faster_than_the_climb_bound() {
        let dt = 1.0 / 60.0;
        let rise_time = |step: f32, bob_rate: f32| {
            let mut p = PelvisFollower::default();
            p.follow(0.0, 0.0, 0.0, 0.0);
            let mut last = p.height;
            for s in 1..=120 {
                let climb = climb_speed(step - p.height, 0.5, bob_rate);
                let h = p.follow(step, 0.0, climb, dt);
                let rise = (h - last) / dt + bob_rate.max(0.0);
                let bound = PELVIS_MAX_CLIMB_SPEED.max(PELVIS_MAX_SPEED + bob_rate);
                assert!(rise <= bound + 1e-3, "{rise} m/s");
                last = h;
                if h >= 0.95 * step {
                    return s;
                }
            }
            usize::MAX
        };
        let walking = {
            let mut p = PelvisFollower::default();
            p.follow(0.0, 0.0, 0.0, 0.0);
            (1..=120)
                .find(|_| p.follow(0.3, 0.0, 0.0, dt) >= 0.285)
                .unwrap()
        };
        let (climbing, under_bob) = (rise_time(0.3, 0.0), rise_time(0.3, 0.2));
        assert!(3 * climbing < 2 * walking, "{climbing} vs {walking} steps");
        assert!(
            under_bob > climbing,
            "the bob leaves less room: {under_bob} steps"
        );
        assert_eq!(climb_speed(-0.1, 0.5, 0.0), 0.0, "no step: no climb");
        assert_eq!(climb_speed(0.3, 0.5, 1.0), 0.0, "a fast bob: no climb");
    }

    #[test]
    fn zero_dt_places_at_rest() {
        let mut p = PelvisFollower::default();
        p.follow(0.5, 0.0, 0.0, 1.0 / 60.0);
        assert_eq!(p.height, 0.5);
        p.follow(0.2, 0.0, 0.0, 0.0);
        assert_eq!((p.height, p.speed), (0.2, 0.0));
    }

    #[test]
    fn a_steep_slope_is_followed_at_its_own_pace() {
        let mut p = PelvisFollower::default();
        let dt = 1.0 / 60.0;
        let rate = -0.45;
        p.follow(0.0, rate, 0.0, 0.0);
        for k in 1..=120 {
            p.follow(rate * dt * k as f32, rate, 0.0, dt);
        }
        assert!((p.height - rate * 2.0).abs() < 0.01, "{}", p.height);
    }
}
