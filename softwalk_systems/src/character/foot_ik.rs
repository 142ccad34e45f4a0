//! Stage 5, foot IK: legs solved to the foot keys, feet aligned to the ground
//! normal, pelvis lowered when a leg cannot reach, the upper body tilted by
//! the proxy; outputs the final pose and each foot's state.

use glam::{Quat, Vec2, Vec3};

use super::balance::RigidProxy;
use super::body::CharacterBody;
use super::gait::{Gait, clamp_dt};
use super::ik::solve_two_bone;
use super::pose::Pose;
use super::rays::{FootRays, GroundKey};
use super::skeleton::Joint;
use crate::foot::{FootPhase, FootSole, FootState, Side};

/// Foot IK state: the smoothed pelvis drop and last ankle positions.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FootIK {
    /// How far the pelvis is lowered below its walking height, metres.
    pub pelvis_drop: f32,
    /// Half-life with which the drop relaxes when less is needed, seconds
    /// (more is applied at once, so the feet always reach).
    pub drop_halflife: f32,
    /// Sole-centre target of each foot this step (world).
    pub sole_targets: [Vec3; 2],
    /// Ankle position of each foot last step (world), for velocities.
    pub last_ankles: [Vec3; 2],
}

impl Default for FootIK {
    fn default() -> Self {
        FootIK {
            pelvis_drop: 0.0,
            drop_halflife: 0.1,
            sole_targets: [Vec3::ZERO; 2],
            last_ankles: [Vec3::ZERO; 2],
        }
    }
}

/// How much of the upper body's lean the pelvis takes back (so the whole-body
/// COM moves less than the trunk): a fraction of the trunk length.
const PELVIS_COUNTER_SHIFT: f32 = 0.15;
/// Leg reach kept in reserve when lowering the pelvis.
const REACH_MARGIN: f32 = 0.995;

/// One foot's sole placed on its key: sole centre, frame and ankle target.
struct FootPlacement {
    sole: FootSole,
    centre: Vec3,
    normal: Vec3,
    ankle: Vec3,
}

fn place_foot(
    body: &CharacterBody,
    key: &GroundKey,
    at: Vec2,
    lift: f32,
    forward: Vec3,
) -> FootPlacement {
    let normal = key.normal;
    let centre = Vec3::new(at.x, key.point.y + lift, at.y);
    let along = (forward - normal * forward.dot(normal))
        .try_normalize()
        .unwrap_or(forward);
    let ankle_offset = body.ankle_above_sole();
    let half = 0.5 * body.foot_length;
    FootPlacement {
        sole: FootSole {
            heel: centre - along * half,
            toe: centre + along * half,
            width: body.foot_width,
        },
        centre,
        normal,
        ankle: centre + normal * ankle_offset.y + along * ankle_offset.z,
    }
}

/// Stage 5: builds the final pose and returns each foot's state (left first).
/// A `dt` of 0 (see [`clamp_dt`]) poses without moving the drop spring and
/// reports zero velocities.
pub fn foot_ik_stage(
    ik: &mut FootIK,
    pose: &mut Pose,
    body: &CharacterBody,
    gait: &Gait,
    rays: &FootRays,
    proxy: &RigidProxy,
    dt: f32,
) -> [FootState; 2] {
    let dt = clamp_dt(dt);
    let forward = gait.pelvis.heading3();
    let right = forward.cross(Vec3::Y);
    let feet = [0, 1].map(|k| {
        let plan = &gait.feet[k];
        place_foot(body, &rays.feet[k], plan.target, plan.lift, forward)
    });

    // Pelvis: walking height over the ground under it, bob, sway, and a small
    // shift back against the trunk's lean.
    let xz = gait.pelvis.position;
    let mut pelvis = Vec3::new(xz.x, rays.body.point.y, xz.y)
        + Vec3::Y * (gait.params.walking_hip_height(body) + gait.bob)
        + right * gait.sway
        - forward * (PELVIS_COUNTER_SHIFT * body.trunk * proxy.tilt.sin());
    let hips = [
        pelvis - right * body.hip_half_width,
        pelvis + right * body.hip_half_width,
    ];
    let reach = REACH_MARGIN * body.leg_reach();
    let needed = (0..2)
        .map(|k| {
            let d = feet[k].ankle - hips[k];
            let r = Vec2::new(d.x, d.z).length().min(reach);
            -d.y - (reach * reach - r * r).sqrt()
        })
        .fold(0.0f32, f32::max)
        .min(0.6 * body.leg_reach());
    ik.pelvis_drop = if needed >= ik.pelvis_drop || dt == 0.0 {
        needed
    } else {
        let relax = 1.0 - (-dt * std::f32::consts::LN_2 / ik.drop_halflife).exp();
        ik.pelvis_drop + (needed - ik.pelvis_drop) * relax
    };
    pelvis.y -= ik.pelvis_drop;

    // Legs.
    let legs = [
        (
            Joint::HipLeft,
            Joint::KneeLeft,
            Joint::AnkleLeft,
            Joint::ToeLeft,
        ),
        (
            Joint::HipRight,
            Joint::KneeRight,
            Joint::AnkleRight,
            Joint::ToeRight,
        ),
    ];
    let foot_radius = body.bone_radius(super::skeleton::Bone::FootLeft);
    let mut soles = [feet[0].sole, feet[1].sole];
    for (k, &(hip, knee, ankle, toe)) in legs.iter().enumerate() {
        let hip_at = hips[k] - Vec3::Y * ik.pelvis_drop;
        let pole = hip_at + forward * body.leg_reach();
        let s = solve_two_bone(hip_at, feet[k].ankle, pole, body.thigh, body.shank);
        // The foot follows the ankle the IK really reached.
        let miss = s.end - feet[k].ankle;
        soles[k].heel += miss;
        soles[k].toe += miss;
        pose.joints[hip as usize] = hip_at;
        pose.joints[knee as usize] = s.mid;
        pose.joints[ankle as usize] = s.end;
        pose.joints[toe as usize] = soles[k].toe + feet[k].normal * foot_radius;
    }

    // Upper body, rotated by the proxy's tilt about the hips.
    let lean = Quat::from_axis_angle(right, -proxy.tilt);
    let up = lean * Vec3::Y;
    let neck = pelvis + up * body.trunk;
    pose.joints[Joint::Pelvis as usize] = pelvis;
    pose.joints[Joint::Neck as usize] = neck;
    pose.joints[Joint::HeadTop as usize] = neck + up * body.head;
    let arms = [
        (
            Joint::ShoulderLeft,
            Joint::ElbowLeft,
            Joint::WristLeft,
            -1.0,
            gait.arm_swing,
        ),
        (
            Joint::ShoulderRight,
            Joint::ElbowRight,
            Joint::WristRight,
            1.0,
            -gait.arm_swing,
        ),
    ];
    for (shoulder, elbow, wrist, sign, swing) in arms {
        let at = neck + right * (sign * body.shoulder_half_width);
        let upper = Quat::from_axis_angle(right, swing) * (lean * Vec3::NEG_Y);
        let elbow_at = at + upper * body.upper_arm;
        let lower = Quat::from_axis_angle(right, 0.25 + 0.5 * swing.max(0.0)) * upper;
        pose.joints[shoulder as usize] = at;
        pose.joints[elbow as usize] = elbow_at;
        pose.joints[wrist as usize] = elbow_at + lower * body.forearm;
    }
    pose.forward = forward;
    pose.right = right;

    let ankles = [pose.joint(Joint::AnkleLeft), pose.joint(Joint::AnkleRight)];
    let states = Side::BOTH.map(|side| {
        let k = side.index();
        let plan = &gait.feet[k];
        FootState {
            side,
            sole: soles[k],
            ankle: ankles[k],
            velocity: if dt > 0.0 {
                (ankles[k] - ik.last_ankles[k]) / dt
            } else {
                Vec3::ZERO
            },
            phase: plan.phase,
            contact: plan.phase == FootPhase::Stance && rays.feet[k].hit,
        }
    });
    ik.last_ankles = ankles;
    ik.sole_targets = [feet[0].centre, feet[1].centre];
    states
}
