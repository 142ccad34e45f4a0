//! How far a knee may bend and how fast it turns; a swinging knee no
//! further than it can straighten again before its foot lands.
//!
//! Over deep loose ground a short leg's swing knee reaches its range's end
//! trying to lift the foot over the surface. Held there, it is still
//! straightening at its top speed when the foot lands, and the stance
//! starts deeply bent. Once the foot ploughs (the leg cannot lift it where
//! the swing aims it), the knee is bound to straighten in time: the foot
//! goes through the loose layer instead, and lands under a nearly straight
//! leg. A leg that lifts its foot clear keeps its own swing. The foot
//! ploughs no deeper than the floor under it: over rigid ground, or a print
//! already pressed, the knee bends as far as the foot needs.

use glam::{Vec2, Vec3};

use super::body::CharacterBody;
use super::gait::{FootPlan, GaitParams};
use super::ik::flexion_at_distance;
use crate::foot::FootPhase;

/// Length of a planted leg (hip to ankle, a fraction of its reach) past
/// which the pelvis rises to straighten it: a knee bent about 20°.
pub(super) const STANDING_LEG: f32 = 0.985;
/// The most a knee bends while walking, radians (about 117°: high stepping
/// out of deep snow reaches 100–110°).
pub const MAX_KNEE_FLEXION: f32 = 2.05;
/// Fastest a knee bends or straightens, rad/s (about 540°/s; walking
/// peaks at about 400–450°/s).
pub const MAX_KNEE_SPEED: f32 = 9.5;
/// Rate at which a nearly straight knee may close its last degrees, 1/s:
/// its flexion falls at most as `exp(-rate · t)`. The leg's length barely
/// changes over the last degrees, so a target that asks for a straight knee
/// would snap it straight at full speed and bend it again at the landing;
/// a real knee is braked there and eases into the stance's flexion.
pub const STRAIGHTENING_RATE: f32 = 22.0;
/// Speed at which the bound falls towards the landing, as a fraction of
/// [`MAX_KNEE_SPEED`]: the rest is slack for the knee to follow the bound
/// while its foot is also coming down.
const EXTENSION_SPEED_SHARE: f32 = 0.8;

/// The most the knee of a foot on `plan` may bend this step, radians: in
/// the swing, the flexion of a standing leg plus what the knee can
/// straighten, at [`EXTENSION_SPEED_SHARE`] of its top speed, in the swing
/// time left; never more than [`MAX_KNEE_FLEXION`]. A planted foot's knee
/// is bound by its range only.
pub(super) fn swing_knee_limit(body: &CharacterBody, params: &GaitParams, plan: &FootPlan) -> f32 {
    if plan.phase == FootPhase::Stance {
        return MAX_KNEE_FLEXION;
    }
    let swing_time = params.swing_time();
    let time_left = (1.0 - plan.swing).clamp(0.0, 1.0) * swing_time;
    let landing = flexion_at_distance(STANDING_LEG * body.leg_reach(), body.thigh, body.shank);
    let unbend = EXTENSION_SPEED_SHARE * MAX_KNEE_SPEED * time_left;
    (landing + unbend).min(MAX_KNEE_FLEXION)
}

/// The range a knee bent `last` radians may turn to in `dt` seconds: bent
/// at up to [`MAX_KNEE_SPEED`], straightened at up to that speed and, near
/// straight, no faster than [`STRAIGHTENING_RATE`] lets it.
pub(super) fn flexion_reach(last: f32, dt: f32) -> (f32, f32) {
    let least = (last - MAX_KNEE_SPEED * dt).max(last * (-STRAIGHTENING_RATE * dt).exp());
    (least, last + MAX_KNEE_SPEED * dt)
}

/// The least knee flexion at which a foot whose ankle is aimed at `ankle`
/// (its lowest point at height `lowest`), lowered straight down as a bound
/// on the knee lowers it, keeps its lowest point on or above `floor`,
/// radians; 0 when lowering the foot cannot take it below.
pub(super) fn flexion_over_floor(
    body: &CharacterBody,
    hip: Vec3,
    ankle: Vec3,
    lowest: f32,
    floor: f32,
) -> f32 {
    let across = Vec2::new(ankle.x - hip.x, ankle.z - hip.z).length();
    // How far below the hip the ankle is with the sole's lowest point on the floor.
    let below = hip.y - (ankle.y + floor - lowest);
    let longest = (across * across + below.max(0.0).powi(2)).sqrt();
    let (l1, l2) = (body.thigh, body.shank);
    if longest >= l1 + l2 {
        return 0.0;
    }
    flexion_at_distance(longest, l1, l2)
}

/// The most the knee of a foot on `plan` may bend this step: the swing's
/// bound ([`swing_knee_limit`]), raised to what keeps its sole over
/// `floor` (see [`flexion_over_floor`]), within the knee's range.
pub(super) fn knee_limit(
    body: &CharacterBody,
    params: &GaitParams,
    plan: &FootPlan,
    hip: Vec3,
    ankle: Vec3,
    lowest: f32,
    floor: f32,
) -> f32 {
    swing_knee_limit(body, params, plan)
        .max(flexion_over_floor(body, hip, ankle, lowest, floor))
        .min(MAX_KNEE_FLEXION)
}

#[cfg(test)]
mod tests {
    use super::super::ik::{distance_at_flexion, lift_to_reach};
    use super::super::support::tests::swinging_at;
    use super::*;
    use crate::character::{CharacterDesc, GaitModifiers};

    /// Height of the lowest point of a foot aimed at `ankle` (its lowest
    /// point at `lowest`) lowered straight down until the knee bends only
    /// `flexion`.
    fn lowest_at(body: &CharacterBody, hip: Vec3, ankle: Vec3, lowest: f32, flexion: f32) -> f32 {
        let d = distance_at_flexion(flexion, body.thigh, body.shank);
        let lowered = lift_to_reach(hip, ankle, d).unwrap();
        lowest + (lowered.y - ankle.y)
    }

    #[test]
    fn a_bound_knee_lowers_its_foot_to_the_floor_and_no_further() {
        let (body, params) = walk(CharacterDesc::new(1.0, 22.0));
        let hip = Vec3::new(0.0, 0.5, 0.0);
        // A foot lifted high ahead, as over deep snow late in the swing:
        // the knee bent far (about 110°).
        let ankle = hip + Vec3::new(0.2, -0.25, 0.0);
        let lowest = ankle.y - 0.04;
        let late = swinging(0.9);
        let swing_only = swing_knee_limit(&body, &params, &late);
        assert!(lowest_at(&body, hip, ankle, lowest, swing_only) < lowest - 0.1);
        // Over 0.3 m of fresh snow the foot ploughs all the way the swing's
        // bound takes it.
        let deep = lowest - 0.3;
        let limit = knee_limit(&body, &params, &late, hip, ankle, lowest, deep);
        assert_eq!(limit, swing_only);
        // Over rigid ground 5 cm under the aimed sole it stops on the floor.
        let rigid = lowest - 0.05;
        let limit = knee_limit(&body, &params, &late, hip, ankle, lowest, rigid);
        assert!(limit > swing_only);
        let reached = lowest_at(&body, hip, ankle, lowest, limit);
        assert!((reached - rigid).abs() < 1e-3, "{reached} vs {rigid}");
        // A foot aimed below its floor is not pulled further down: the
        // knee may bend at least as far as the aim needs.
        let aimed = flexion_at_distance(ankle.distance(hip), body.thigh, body.shank);
        assert!(flexion_over_floor(&body, hip, ankle, lowest, lowest + 0.1) >= aimed);
    }

    /// A plan `swing` of the way through its swing.
    fn swinging(swing: f32) -> FootPlan {
        FootPlan {
            phase: if swing < 0.5 {
                FootPhase::SwingUp
            } else {
                FootPhase::SwingDown
            },
            swing,
            ..swinging_at(Vec2::ZERO)
        }
    }

    fn walk(desc: CharacterDesc) -> (CharacterBody, GaitParams) {
        let body = CharacterBody::new(desc).unwrap();
        let params = GaitParams::new(&body, &GaitModifiers::default());
        (body, params)
    }

    #[test]
    fn the_bound_falls_to_a_standing_knee_at_the_landing_no_faster_than_the_knee() {
        for desc in [CharacterDesc::new(1.0, 22.0), CharacterDesc::adult()] {
            let (body, params) = walk(desc);
            let swing_time = params.swing_time();
            let standing =
                flexion_at_distance(STANDING_LEG * body.leg_reach(), body.thigh, body.shank);
            let landing = swing_knee_limit(&body, &params, &swinging(1.0));
            assert!((landing - standing).abs() < 1e-6, "{landing} vs {standing}");
            assert!(landing < 25f32.to_radians(), "{}", landing.to_degrees());
            let du = 0.01;
            for i in 0..100 {
                let u = i as f32 * du;
                let (now, next) = (
                    swing_knee_limit(&body, &params, &swinging(u)),
                    swing_knee_limit(&body, &params, &swinging(u + du)),
                );
                assert!(now >= next && now <= MAX_KNEE_FLEXION);
                let speed = (now - next) / (du * swing_time);
                assert!(speed <= MAX_KNEE_SPEED + 1e-3, "{speed} rad/s at {u}");
            }
        }
    }

    #[test]
    fn a_short_swing_starts_straightening_before_mid_swing_and_a_long_one_later() {
        // A 1.0 m walker's swing is too short to straighten from the cap in
        // its second half alone; an adult's leaves the whole first half free.
        let limit_at = |desc, u| {
            let (body, params) = walk(desc);
            swing_knee_limit(&body, &params, &swinging(u))
        };
        let small = CharacterDesc::new(1.0, 22.0);
        assert!(limit_at(small, 0.5) < MAX_KNEE_FLEXION);
        assert_eq!(limit_at(CharacterDesc::adult(), 0.4), MAX_KNEE_FLEXION);
        assert!(limit_at(CharacterDesc::adult(), 0.9) < 60f32.to_radians());
    }

    #[test]
    fn a_planted_knee_is_bound_by_its_range_only() {
        let (body, params) = walk(CharacterDesc::adult());
        let mut plan = swinging(0.0);
        plan.phase = FootPhase::Stance;
        assert_eq!(swing_knee_limit(&body, &params, &plan), MAX_KNEE_FLEXION);
    }

    #[test]
    fn a_nearly_straight_knee_eases_into_straight_at_any_step_rate() {
        // Far from straight the knee turns at full speed either way.
        let (least, most) = flexion_reach(1.5, 1.0 / 60.0);
        assert!((1.5 - least - MAX_KNEE_SPEED / 60.0).abs() < 1e-6);
        assert!((most - 1.5 - MAX_KNEE_SPEED / 60.0).abs() < 1e-6);
        // From 20°, a target asking for a straight knee is followed over
        // several steps: still bent about 7° after 50 ms, and 2° after
        // 100 ms, at 30 Hz, 60 Hz or 120 Hz alike.
        for hz in [30u32, 60, 120] {
            let dt = 1.0 / hz as f32;
            let mut knee = 20f32.to_radians();
            for step in 1..=hz / 10 {
                knee = flexion_reach(knee, dt).0;
                let t = step as f32 * dt;
                let expected = 20f32.to_radians() * (-STRAIGHTENING_RATE * t).exp();
                assert!((knee - expected).abs() < 1e-4, "{hz} Hz, {t} s: {knee}");
            }
            assert!(knee.to_degrees() > 2.0, "{hz} Hz: {}", knee.to_degrees());
        }
    }
}
