//! [`ClipGait`]: the timing and stride a walk clip gives a character's gait.

use engine::anim::WalkCycle;

use super::gravity::GRAVITY;
/// Walking Froude numbers (v² / (g · hip height)) a clip's speed is kept within,
/// as `CharacterDesc::froude`.
const FROUDE_RANGE: (f32, f32) = (0.02, 0.5);
/// Strides, in leg lengths, a clip's stride is kept within.
const RELATIVE_STRIDE_RANGE: (f32, f32) = (0.5, 2.5);
/// Stance fractions the gait accepts (double support, not a run).
pub const CLIP_DUTY_RANGE: (f32, f32) = (0.55, 0.7);

/// A walk clip's cycle free of the clip's units: its period, its stride
/// over its leg length, its duty factor. A character whose description has
/// one walks with the clip's cadence and duty and a stride scaled by its own
/// legs, instead of Boulic's walk for its Froude number.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClipGait {
    /// One cycle (two steps), seconds.
    pub period: f32,
    /// Stride over leg length (hip to knee to ankle).
    pub relative_stride: f32,
    /// Fraction of the cycle a foot stands.
    pub duty: f32,
}

/// Speed (m/s), stride (m) and duty of a clip's walk on one body.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClipTiming {
    /// Walking speed, m/s.
    pub speed: f32,
    /// Stride, metres.
    pub stride: f32,
    /// Stance fraction.
    pub duty: f32,
}

impl ClipGait {
    /// The gait of an analysed clip.
    pub fn from_cycle(cycle: &WalkCycle) -> ClipGait {
        ClipGait {
            period: cycle.period,
            relative_stride: cycle.stride / cycle.leg_length,
            duty: cycle.duty,
        }
    }

    /// The walk on a body whose legs are `leg` long (hip to ankle) with its
    /// hips `hip_height` high: the stride scaled by the legs, the
    /// speed one stride per period, each kept within the gait's valid
    /// ranges (stride 0.5 to 2.5 leg lengths, Froude number 0.02 to 0.5,
    /// duty 0.55 to 0.7; a non-finite value reads as the range's middle).
    pub fn timing(&self, leg: f32, hip_height: f32) -> ClipTiming {
        let stride = within(self.relative_stride, RELATIVE_STRIDE_RANGE) * leg;
        let froude_speed = |fr: f32| (fr * GRAVITY * hip_height).sqrt();
        let speed_range = (froude_speed(FROUDE_RANGE.0), froude_speed(FROUDE_RANGE.1));
        let speed = within(stride / self.period, speed_range);
        ClipTiming {
            speed,
            stride,
            duty: within(self.duty, CLIP_DUTY_RANGE),
        }
    }
}

/// `value` clamped to `range`; its middle when not finite.
fn within(value: f32, range: (f32, f32)) -> f32 {
    if value.is_finite() {
        value.clamp(range.0, range.1)
    } else {
        0.5 * (range.0 + range.1)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::character::{CharacterBody, CharacterDesc};

    fn timing_on(gait: &ClipGait, body: &CharacterBody) -> ClipTiming {
        gait.timing(body.leg_reach(), body.hip_height)
    }

    #[test]
    fn the_stride_scales_with_the_legs_and_the_cadence_stays() {
        let gait = ClipGait {
            period: 1.1,
            relative_stride: 1.6,
            duty: 0.62,
        };
        let adult = CharacterBody::new(CharacterDesc::adult()).unwrap();
        let tall = CharacterBody::new(CharacterDesc::tall()).unwrap();
        let (a, t) = (timing_on(&gait, &adult), timing_on(&gait, &tall));
        let leg = CharacterBody::leg_reach;
        assert!((a.stride - 1.6 * leg(&adult)).abs() < 1e-5);
        assert!((t.stride / a.stride - leg(&tall) / leg(&adult)).abs() < 1e-5);
        assert!((a.stride / a.speed - 1.1).abs() < 1e-5);
        assert!((t.stride / t.speed - 1.1).abs() < 1e-5);
        assert_eq!(a.duty, 0.62);
    }

    #[test]
    fn out_of_range_clips_are_held_to_a_walk() {
        let adult = CharacterBody::new(CharacterDesc::adult()).unwrap();
        let sprint = ClipGait {
            period: 0.3,
            relative_stride: 9.0,
            duty: 0.3,
        };
        let t = timing_on(&sprint, &adult);
        assert!((t.stride - 2.5 * adult.leg_reach()).abs() < 1e-5);
        let froude = t.speed * t.speed / (GRAVITY * adult.hip_height);
        assert!((froude - 0.5).abs() < 1e-4, "{froude}");
        assert_eq!(t.duty, 0.55);
        let broken = ClipGait {
            period: f32::NAN,
            relative_stride: f32::NAN,
            duty: f32::INFINITY,
        };
        let t = timing_on(&broken, &adult);
        assert!(t.speed.is_finite() && t.stride.is_finite() && t.duty.is_finite());
    }
}
