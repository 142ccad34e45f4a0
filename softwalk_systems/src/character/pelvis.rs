//! The pelvis height as a critically damped follower: it goes after the
//! height the legs need with a bounded speed and acceleration, so a deeper
//! print or a foot that cannot reach lowers the body smoothly, never in one
//! step. The target's own rate (bounded too) is fed forward, so a steady
//! slope is followed without lag. Up a step it may rise faster, and for a
//! foot landing lower than its leg reaches it may lower faster, both within
//! what the gait's bob leaves of a bound on the pelvis's whole motion.

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
/// Fastest the pelvis, its base and the gait's bob together, lowers
/// relative to the ground's own rise when it reaches down for a foot landing
/// lower than its leg reaches, m/s (0.83 cm per 60 Hz step; see
/// [`descent_speed`]).
pub const PELVIS_MAX_DESCENT_SPEED: f32 = 0.5;

/// How much faster than [`PELVIS_MAX_SPEED`] the pelvis base may rise this
/// step, m/s, to climb a step `rise` metres high in `time` seconds while
/// the bob raises the pelvis at `bob_rate` m/s: never so fast that base
/// and bob together rise faster than [`PELVIS_MAX_CLIMB_SPEED`].
pub fn climb_speed(rise: f32, time: f32, bob_rate: f32) -> f32 {
    extra_speed(rise, time, PELVIS_MAX_CLIMB_SPEED - bob_rate.max(0.0))
}

/// How much faster than [`PELVIS_MAX_SPEED`] the pelvis base may lower this
/// step, m/s, to come down `drop` metres in `time` seconds while the bob
/// moves the pelvis at `bob_rate` m/s: never so fast that base and bob
/// together lower faster than [`PELVIS_MAX_DESCENT_SPEED`]. While the bob
/// rises the base may lower as much faster, so the pelvis comes down evenly.
pub fn descent_speed(drop: f32, time: f32, bob_rate: f32) -> f32 {
    extra_speed(drop, time, PELVIS_MAX_DESCENT_SPEED + bob_rate)
}

/// The speed beyond [`PELVIS_MAX_SPEED`] that covers `distance` metres in
/// `time` seconds, within `bound` m/s for the base's whole speed.
fn extra_speed(distance: f32, time: f32, bound: f32) -> f32 {
    let wanted = distance.max(0.0) / time.max(f32::EPSILON);
    wanted.min((bound - PELVIS_MAX_SPEED).max(0.0))
}

/// How much faster than [`PELVIS_MAX_SPEED`] the pelvis base may move this
/// step, m/s (see [`climb_speed`] and [`descent_speed`]).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ExtraSpeed {
    /// Extra rising speed, m/s.
    pub climb: f32,
    /// Extra lowering speed, m/s.
    pub descent: f32,
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
    /// slope is followed at its own pace. The pelvis may move `extra` m/s
    /// faster up or down (see [`ExtraSpeed`]). A `dt` of 0 (or the first
    /// call) jumps to the target at rest.
    pub fn follow(&mut self, target: f32, ground_rate: f32, extra: ExtraSpeed, dt: f32) -> f32 {
        if dt <= 0.0 || !self.placed {
            *self = PelvisFollower {
                height: target,
                speed: ground_rate,
                last_target: target,
                placed: true,
            };
            return self.height;
        }
        let up = PELVIS_MAX_SPEED + extra.climb.max(0.0);
        let down = PELVIS_MAX_SPEED + extra.descent.max(0.0);
        let (lo, hi) = (ground_rate - down, ground_rate + up);
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
        p.follow(1.0, 0.0, ExtraSpeed::default(), 0.0);
        let dt = 1.0 / 60.0;
        let mut last = p.height;
        for _ in 0..120 {
            let h = p.follow(0.7, 0.0, ExtraSpeed::default(), dt);
            assert!((last - h).abs() <= PELVIS_MAX_SPEED * dt + 1e-6);
            assert!(h >= 0.7 - 1e-3, "no undershoot: {h}");
            last = h;
        }
        assert!((p.height - 0.7).abs() < 1e-3);
    }

    /// Steps of `dt` the follower takes, within the walking bounds, from 0
    /// to within 5 % of `target`.
    fn walking_steps(target: f32, dt: f32) -> usize {
        let mut p = PelvisFollower::default();
        p.follow(0.0, 0.0, ExtraSpeed::default(), 0.0);
        (1..=120)
            .find(|_| {
                let h = p.follow(target, 0.0, ExtraSpeed::default(), dt);
                (h - target).abs() <= 0.05 * target.abs()
            })
            .unwrap()
    }

    #[test]
    fn a_step_is_climbed_faster_but_base_and_bob_never_faster_than_the_climb_bound() {
        let dt = 1.0 / 60.0;
        let rise_time = |step: f32, bob_rate: f32| {
            let mut p = PelvisFollower::default();
            p.follow(0.0, 0.0, ExtraSpeed::default(), 0.0);
            let mut last = p.height;
            for s in 1..=120 {
                let climb = climb_speed(step - p.height, 0.5, bob_rate);
                let h = p.follow(
                    step,
                    0.0,
                    ExtraSpeed {
                        climb,
                        descent: 0.0,
                    },
                    dt,
                );
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
        let walking = walking_steps(0.3, dt);
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
    fn a_drop_in_time_is_made_faster_but_base_and_bob_never_faster_than_the_descent_bound() {
        let dt = 1.0 / 60.0;
        let drop_time = |bob_rate: f32| {
            let mut p = PelvisFollower::default();
            p.follow(0.0, 0.0, ExtraSpeed::default(), 0.0);
            let mut last = p.height;
            for s in 1..=120 {
                let descent = descent_speed(p.height + 0.25, 0.4, bob_rate);
                let extra = ExtraSpeed {
                    climb: 0.0,
                    descent,
                };
                let h = p.follow(-0.25, 0.0, extra, dt);
                let fall = (last - h) / dt - bob_rate;
                let bound = PELVIS_MAX_DESCENT_SPEED.max(PELVIS_MAX_SPEED - bob_rate);
                assert!(fall <= bound + 1e-3, "{fall} m/s");
                last = h;
                if h <= -0.95 * 0.25 {
                    return s;
                }
            }
            usize::MAX
        };
        let walking = walking_steps(-0.25, dt);
        let (dropping, under_bob) = (drop_time(0.0), drop_time(-0.2));
        assert!(3 * dropping < 2 * walking, "{dropping} vs {walking} steps");
        assert!(
            under_bob > dropping,
            "the bob leaves less room: {under_bob} steps"
        );
        assert!(drop_time(0.1) < dropping, "a rising bob leaves more");
        assert_eq!(
            descent_speed(-0.1, 0.4, 0.0),
            0.0,
            "no drop: no extra speed"
        );
        assert_eq!(descent_speed(0.3, 0.4, -1.0), 0.0, "a fast bob: none");
    }

    #[test]
    fn zero_dt_places_at_rest() {
        let mut p = PelvisFollower::default();
        p.follow(0.5, 0.0, ExtraSpeed::default(), 1.0 / 60.0);
        assert_eq!(p.height, 0.5);
        p.follow(0.2, 0.0, ExtraSpeed::default(), 0.0);
        assert_eq!((p.height, p.speed), (0.2, 0.0));
    }

    #[test]
    fn a_steep_slope_is_followed_at_its_own_pace() {
        let mut p = PelvisFollower::default();
        let dt = 1.0 / 60.0;
        let rate = -0.45;
        p.follow(0.0, rate, ExtraSpeed::default(), 0.0);
        for k in 1..=120 {
            p.follow(rate * dt * k as f32, rate, ExtraSpeed::default(), dt);
        }
        assert!((p.height - rate * 2.0).abs() < 0.01, "{}", p.height);
    }
}
