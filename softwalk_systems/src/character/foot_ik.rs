//! Stage 5, foot IK: legs solved to the foot keys, feet aligned to the ground
//! normal, pelvis lowered when a leg cannot reach, the upper body tilted by
//! the proxy; outputs the final pose and each foot's state.

use glam::{Quat, Vec2, Vec3};

use super::balance::RigidProxy;
use super::body::CharacterBody;
use super::gait::{FootPlan, Gait, clamp_dt, contact_offset};
use super::ik::{clamp_flexion, flexion_at_distance, lift_to_reach, solve_two_bone};
use super::pelvis::{ExtraSpeed, PelvisFollower, climb_speed, descent_speed};
use super::pose::Pose;
use super::rays::{FootRays, GroundKey};
use super::skeleton::Joint;
use super::stance_ground::{step_up, unloaded_give};
use super::support::sole_direction;
use super::swing_knee::{MAX_KNEE_FLEXION, STANDING_LEG, flexion_reach, knee_limit};
use crate::foot::{FootPhase, FootSole, FootState, Side};
use crate::ground::rise_along;
use crate::terrain::SINK_TIME_S;

/// Foot IK state: the pelvis follower, the foot roll added for reach, and
/// last ankle positions.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FootIK {
    /// The pelvis base height, following the height the legs need.
    pub pelvis: PelvisFollower,
    /// How far the pelvis is below its walking height over the body's
    /// ground raised by [`Self::step_up`] this step, metres (positive: lowered).
    pub pelvis_drop: f32,
    /// How far the floors under the feet bearing the weight stand above the
    /// body's ground this step, metres (see `step_up`): up a step, the
    /// pelvis walks over the upper side as soon as a foot bears weight there.
    pub step_up: f32,
    /// Foot pitch each leg added to its scheduled roll this step so that it
    /// reaches its foot without lowering the pelvis, radians: negative is
    /// more heel lift (a trailing leg), positive more toe lift (a leading leg).
    /// It changes by at most 6 rad/s in the swing and 3 rad/s on the ground;
    /// the pelvis drop covers the rest.
    pub extra_pitch: [f32; 2],
    /// Sole-centre target of each foot this step (world).
    pub sole_targets: [Vec3; 2],
    /// Lowest point of each sole this step (world): the heel while the toe is
    /// up, the toe while the heel is up, the sole centre when flat.
    pub contact_points: [Vec3; 2],
    /// Ankle position of each foot last step (world), for velocities.
    pub last_ankles: [Vec3; 2],
    /// Height of each flat sole-centre target last step: a target may fall
    /// by at most `MAX_FOOT_FALL_SPEED` (a vanishing platform, a key
    /// dropping into a print), so a foot drops onto the ground instead of
    /// teleporting.
    pub flat_heights: Option<[f32; 2]>,
    /// Knee flexion of each leg last step, radians: it changes within
    /// `swing_knee::flexion_reach` (its top speed, eased near straight).
    pub knee_flexion: Option<[f32; 2]>,
}

impl Default for FootIK {
    fn default() -> Self {
        FootIK {
            pelvis: PelvisFollower::default(),
            pelvis_drop: 0.0,
            step_up: 0.0,
            extra_pitch: [0.0; 2],
            sole_targets: [Vec3::ZERO; 2],
            contact_points: [Vec3::ZERO; 2],
            last_ankles: [Vec3::ZERO; 2],
            flat_heights: None,
            knee_flexion: None,
        }
    }
}

/// How much of the upper body's lean the pelvis takes back (so the whole-body
/// COM moves less than the trunk): a fraction of the trunk length.
const PELVIS_COUNTER_SHIFT: f32 = 0.15;
/// Leg reach kept in reserve when lowering the pelvis or lifting a heel.
const REACH_MARGIN: f32 = 0.999;
/// The most a heel may be lifted (foot pitch about the toe), radians (about 63°).
const MAX_HEEL_LIFT: f32 = 1.1;
/// The most a toe may be lifted (foot pitch about the heel), radians (about 34°).
const MAX_TOE_LIFT: f32 = 0.6;
/// Fastest change of the extra foot pitch, rad/s (ankle speeds of real gait).
const MAX_PITCH_RATE: f32 = 6.0;
/// Fastest change of a planted foot's extra pitch, rad/s: its toe or heel
/// comes down onto ground that gives no faster than the ground is pressed.
const MAX_PLANTED_PITCH_RATE: f32 = 3.0;
/// Fastest change of a standing walker's extra foot pitch, rad/s: a foot
/// rolled to reach lies down flat no faster than the pelvis lowers for it
/// (the ankle falls by about 1.5 mm a step at 60 Hz).
const MAX_STANDING_PITCH_RATE: f32 = 1.0;
/// The most the pelvis lowers below its walking height for a leg to reach,
/// a fraction of the leg reach.
const MAX_PELVIS_DROP: f32 = 0.6;
/// The most the pelvis rises above its walking height for bent planted legs,
/// a fraction of the leg reach.
const MAX_PELVIS_RAISE: f32 = 0.12;
/// Fastest a foot's target falls, m/s.
pub const MAX_FOOT_FALL_SPEED: f32 = 3.0;
/// How far below where its swing aims it a foot the leg cannot lift
/// further goes before it ploughs through the ground, metres.
const PLOUGH_DEPTH: f32 = 0.01;
/// How far beyond the planted legs' own need a landing may lie out of
/// reach before the pelvis lowers for it in the swing, metres: the bounded
/// pelvis takes up a slight stretch at the landing itself (a long stride on
/// level ground), as a walking leg does.
const LANDING_SLACK: f32 = 0.02;
/// Bisection steps when solving the foot pitch a leg needs (resolution below 0.001 rad).
const PITCH_STEPS: usize = 11;

/// One foot's sole placed on its key: sole, frame, ankle target and contact
/// point, with the flat frame and the pitch it was placed from.
#[derive(Debug, Clone, Copy)]
struct FootPlacement {
    sole: FootSole,
    centre: Vec3,
    normal: Vec3,
    ankle: Vec3,
    lowest: Vec3,
    frame: FootFrame,
    pitch: f32,
}

impl FootPlacement {
    /// The placement moved by `offset`.
    fn moved(mut self, offset: Vec3) -> Self {
        self.sole.heel += offset;
        self.sole.toe += offset;
        self.centre += offset;
        self.ankle += offset;
        self.lowest += offset;
        self
    }
}

/// Where one foot goes this step before its roll: the flat sole on the key.
#[derive(Debug, Clone, Copy)]
struct FootFrame {
    /// Flat sole centre: on the key, raised by the swing lift.
    centre: Vec3,
    /// Ground normal of the key.
    normal: Vec3,
    /// Unit direction from heel to toe, in the ground's tangent plane.
    along: Vec3,
    /// Where along the sole the key was cast (see [`FootPlan::contact_along`]).
    contact_along: f32,
}

impl FootFrame {
    /// The flat sole whose scheduled contact point stands on the key
    /// (raised by the swing lift), aligned to the key's normal; its centre
    /// never goes below a platform under it.
    fn new(key: &GroundKey, plan: &FootPlan) -> Self {
        let normal = key.normal;
        let along = sole_direction(plan.heading, normal);
        let mut centre = key.point + Vec3::Y * plan.lift - along * plan.contact_along;
        centre.y = centre.y.max(key.platform.unwrap_or(f32::MIN));
        FootFrame {
            centre,
            normal,
            along,
            contact_along: plan.contact_along,
        }
    }

    /// The foot rolled by `pitch` (toe up > 0 about the heel, heel up < 0
    /// about the toe); the pivot stays where the flat foot has it.
    fn place(&self, body: &CharacterBody, pitch: f32) -> FootPlacement {
        let half = 0.5 * body.foot_length;
        let c = if pitch == 0.0 {
            self.contact_along
        } else {
            contact_offset(pitch, body.foot_length)
        };
        let pivot = self.centre + self.along * c;
        let (sin, cos) = pitch.sin_cos();
        let along = self.along * cos + self.normal * sin;
        let normal = self.normal * cos - self.along * sin;
        let at = |x: f32, y: f32| pivot + along * (x - c) + normal * y;
        let ankle = body.ankle_above_sole();
        FootPlacement {
            sole: FootSole {
                heel: at(-half, 0.0),
                toe: at(half, 0.0),
                width: body.foot_width,
            },
            centre: at(0.0, 0.0),
            normal,
            ankle: at(ankle.z, ankle.y),
            lowest: pivot,
            frame: *self,
            pitch,
        }
    }

    /// The pitch nearest `from` on the way to `limit` at which `accept`
    /// holds for the placed foot (`limit` when it holds nowhere before).
    fn pitch_where(
        &self,
        body: &CharacterBody,
        from: f32,
        limit: f32,
        accept: impl Fn(&FootPlacement) -> bool,
    ) -> f32 {
        let accepts = |pitch: f32| accept(&self.place(body, pitch));
        if accepts(from) {
            return from;
        }
        let (mut refused, mut accepted) = (from, limit);
        for _ in 0..PITCH_STEPS {
            let mid = 0.5 * (refused + accepted);
            if accepts(mid) {
                accepted = mid;
            } else {
                refused = mid;
            }
        }
        accepted
    }

    /// The pitch nearest `from` on the way to `limit` at which a leg of
    /// `reach` from `hip` reaches the ankle (`limit` when none does). The
    /// ankle comes closer to a hip behind the foot as the toe lifts (about
    /// the heel) and to a hip ahead of it as the heel lifts (about the toe).
    fn pitch_to_reach(
        &self,
        body: &CharacterBody,
        hip: Vec3,
        reach: f32,
        from: f32,
        limit: f32,
    ) -> f32 {
        self.pitch_where(body, from, limit, |foot| foot.ankle.distance(hip) <= reach)
    }

    /// The roll nearest `from` at which a leg of `reach` from `hip` reaches
    /// the ankle: more heel lift for a foot `trailing` behind the hip, more
    /// toe lift ahead of it, up to [`MAX_HEEL_LIFT`] and [`MAX_TOE_LIFT`].
    fn roll_to_reach(
        &self,
        body: &CharacterBody,
        hip: Vec3,
        reach: f32,
        from: f32,
        trailing: bool,
    ) -> f32 {
        if trailing {
            let from = from.min(0.0);
            self.pitch_to_reach(body, hip, reach, from, -MAX_HEEL_LIFT.max(-from))
        } else {
            let from = from.max(0.0);
            self.pitch_to_reach(body, hip, reach, from, MAX_TOE_LIFT.max(from))
        }
    }
}

/// How far above `ankle` a hip at `hip`'s horizontal position may stand for
/// a leg of `length` to reach it, relative to `hip` (negative: the hip must
/// come down that far); a horizontal distance beyond `length` reads as `length`.
fn rise_to_reach(hip: Vec3, ankle: Vec3, length: f32) -> f32 {
    let d = ankle - hip;
    let r = Vec2::new(d.x, d.z).length().min(length);
    d.y + (length * length - r * r).sqrt()
}

/// A knee that cannot bend as fast as its foot rolls leaves the leg longer
/// than the foot needs. The foot then unrolls towards flat about the part on
/// the ground until its ankle is `length` from `hip`, so the sole neither
/// sinks into the ground nor slides; the hip line takes what unrolling
/// cannot. Returns `foot` when unrolling would not lengthen the leg.
fn unroll_to_length(
    body: &CharacterBody,
    hip: Vec3,
    foot: &FootPlacement,
    length: f32,
) -> FootPlacement {
    let distance = |placed: &FootPlacement| placed.ankle.distance(hip);
    if foot.pitch == 0.0 || distance(foot) >= length {
        return *foot;
    }
    let flat = foot.frame.place(body, 0.0);
    if distance(&flat) <= distance(foot) {
        return *foot;
    }
    let pitch = foot
        .frame
        .pitch_where(body, foot.pitch, 0.0, |placed| distance(placed) >= length);
    foot.frame.place(body, pitch)
}

/// Stage 5: builds the final pose and returns each foot's state (left first).
/// A `dt` of 0 (see [`clamp_dt`]) places the pelvis follower at rest and
/// reports zero velocities.
///
/// Each foot rolls as the gait schedules it (heel strike about the heel,
/// heel rise about the toe), and further where a leg cannot reach its foot;
/// the pelvis follows the height the legs need at a bounded speed
/// (`PelvisFollower`); the knees stay within their range and speed. Each
/// foot's sole as the leg really reached it is recorded in `rays`
/// ([`super::FootSupport::reached`]), and a swinging foot that ploughs
/// holds its landing there ([`super::FootSupport::landing_held`]).
pub fn foot_ik_stage(
    ik: &mut FootIK,
    pose: &mut Pose,
    body: &CharacterBody,
    gait: &Gait,
    rays: &mut FootRays,
    proxy: &RigidProxy,
    dt: f32,
) -> [FootState; 2] {
    let dt = clamp_dt(dt);
    let forward = gait.pelvis.heading3();
    let right = forward.cross(Vec3::Y);
    let travel = gait.travel_heading();
    let travel = Vec3::new(travel.x, 0.0, travel.y);
    // Pelvis: walking height over the ground under it, bob, sway, and a small
    // shift back against the trunk's lean (which is along the travel).
    let xz = gait.pelvis.position;
    ik.step_up = step_up(gait, rays, xz);
    let mut pelvis = Vec3::new(xz.x, rays.body.point.y + ik.step_up, xz.y)
        + Vec3::Y * (gait.params.walking_hip_height(body) + gait.bob)
        + right * gait.sway
        - travel * (PELVIS_COUNTER_SHIFT * body.trunk * proxy.tilt.sin());
    let hips = [
        pelvis - right * body.hip_half_width,
        pelvis + right * body.hip_half_width,
    ];
    let feet = place_feet(ik, body, gait, rays, &hips, forward, dt);
    ik.pelvis_drop = follow_pelvis(ik, body, gait, rays, &hips, &feet, dt);
    pelvis.y -= ik.pelvis_drop;
    let lowered_hips = hips.map(|hip| hip - Vec3::Y * ik.pelvis_drop);
    let planted = gait.feet.map(|f| f.phase == FootPhase::Stance);
    let knee_limits = [0, 1].map(|k| {
        // Once a swinging foot has ploughed (see [`ploughs`]), its knee is
        // bound to straighten in time for the landing.
        if !rays.support[k].landing_held {
            return MAX_KNEE_FLEXION;
        }
        let floor = reachable_floor(&rays.feet[k], dt);
        let (hip, ankle, lowest) = (lowered_hips[k], feet[k].ankle, feet[k].lowest.y);
        knee_limit(body, &gait.params, &gait.feet[k], hip, ankle, lowest, floor)
    });
    let legs = Legs {
        hips: &lowered_hips,
        feet: &feet,
        planted,
        knee_limits,
    };
    let placed = solve_legs(ik, pose, body, &legs, forward, dt);
    pose_upper_body(pose, body, gait, proxy, pelvis, travel, right);
    pose.forward = forward;
    pose.right = right;
    let ploughing = [0, 1].map(|k| !planted[k] && ploughs(&feet[k], &placed[k]));
    for ((support, &ploughed), foot) in rays.support.iter_mut().zip(&ploughing).zip(&placed) {
        support.landing_held |= ploughed;
        support.reached = Some(foot.centre);
    }
    foot_states(ik, pose, gait, rays, &placed, ploughing, dt)
}

/// Places each foot on its key with the scheduled roll, plus the roll a
/// leg needs to reach its foot before the pelvis drops: more heel lift
/// behind the hip, more toe lift ahead of it; a walker standing still puts
/// its feet flat and lowers its pelvis instead. A planted foot only rolls
/// further about the point its scheduled roll already stands on (where its
/// ray was cast), so a flat planted foot does not rock. Records the targets
/// in `ik`.
fn place_feet(
    ik: &mut FootIK,
    body: &CharacterBody,
    gait: &Gait,
    rays: &FootRays,
    hips: &[Vec3; 2],
    forward: Vec3,
    dt: f32,
) -> [FootPlacement; 2] {
    let reach = REACH_MARGIN * body.leg_reach();
    let mut flat_heights = [0.0; 2];
    let feet = [0, 1].map(|k| {
        let plan = &gait.feet[k];
        let mut frame = FootFrame::new(&rays.feet[k], plan);
        if let (Some(last), true) = (ik.flat_heights, dt > 0.0) {
            frame.centre.y = frame.centre.y.max(last[k] - MAX_FOOT_FALL_SPEED * dt);
        }
        flat_heights[k] = frame.centre.y;
        let trailing = (frame.centre - hips[k]).dot(forward) < 0.0;
        let swinging = plan.phase != FootPhase::Stance;
        let rolls = if trailing {
            plan.contact_along > 0.0
        } else {
            plan.contact_along < 0.0
        };
        let pitch = if !gait.stopped && (swinging || rolls) {
            frame.roll_to_reach(body, hips[k], reach, plan.pitch, trailing)
        } else {
            plan.pitch
        };
        let mut wanted = pitch - plan.pitch;
        // A planted foot rolls only about the part its ray stands on (a roll
        // about the other part unwinds at the pitch rate, never at once).
        if !swinging {
            wanted = if plan.contact_along > 0.0 {
                wanted.min(0.0)
            } else {
                wanted.max(0.0)
            };
        }
        let rate = if swinging {
            MAX_PITCH_RATE
        } else if gait.stopped {
            MAX_STANDING_PITCH_RATE
        } else {
            MAX_PLANTED_PITCH_RATE
        };
        let step = if dt > 0.0 { rate * dt } else { f32::INFINITY };
        let last = ik.extra_pitch[k];
        ik.extra_pitch[k] = wanted.clamp(last - step, last + step);
        frame.place(body, plan.pitch + ik.extra_pitch[k])
    });
    ik.flat_heights = Some(flat_heights);
    ik.sole_targets = [feet[0].centre, feet[1].centre];
    feet
}

/// Moves the pelvis follower one step and returns how far the pelvis is
/// below its walking height over the body's ground raised by
/// [`FootIK::step_up`]. The target is lowered as far as the farther foot needs
/// (less the give a foot bearing little weight need not reach, see
/// [`unloaded_give`]), and raised (as far as every planted leg allows)
/// where the planted legs would bend more than a standing leg does, as
/// behind the hip on a downhill; a swinging foot landing lower than its leg
/// reaches (see [`landing_drop`]) lowers it further, in time for the
/// landing. The bounds are relative to the ground's rise under the walk;
/// the pelvis may climb a step in one step's time, and lower faster for a
/// landing (see [`descent_speed`]).
fn follow_pelvis(
    ik: &mut FootIK,
    body: &CharacterBody,
    gait: &Gait,
    rays: &FootRays,
    hips: &[Vec3; 2],
    feet: &[FootPlacement; 2],
    dt: f32,
) -> f32 {
    let reach = REACH_MARGIN * body.leg_reach();
    let deepest = MAX_PELVIS_DROP * body.leg_reach();
    let rise = |k: usize, length: f32| rise_to_reach(hips[k], feet[k].ankle, length);
    let needed = (0..2)
        .map(|k| -rise(k, reach) - unloaded_give(gait, rays, k))
        .fold(0.0f32, f32::max)
        .min(deepest);
    let standing = STANDING_LEG * body.leg_reach();
    let raise = (0..2)
        .filter(|&k| gait.feet[k].phase == FootPhase::Stance)
        .map(|k| rise(k, standing))
        .fold(f32::INFINITY, f32::min)
        .clamp(0.0, MAX_PELVIS_RAISE * body.leg_reach());
    let ground_y = rays.body.point.y + ik.step_up;
    let ground_rate = rise_along(rays.body.normal, gait.velocity);
    let landing = (0..2)
        .filter_map(|k| landing_drop(body, gait, rays, hips[k], k, ground_rate))
        .max_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(drop, time)| (drop.min(deepest), time));
    // A landing lower than the walking height reaches lowers the pelvis by
    // what it lacks beyond the planted legs' own need, in time for it.
    let (beyond, time) = landing.map_or((0.0, 0.0), |(d, time)| {
        ((d - needed - LANDING_SLACK).max(0.0), time)
    });
    let drop = needed - raise + beyond;
    let lowered = ground_y - ik.pelvis.height;
    let descent = if beyond > 0.0 {
        descent_speed(drop - lowered, time, gait.bob_rate())
    } else {
        0.0
    };
    let extra = ExtraSpeed {
        climb: climb_speed(ik.step_up, 0.5 * gait.params.cycle_time(), gait.bob_rate()),
        descent,
    };
    ground_y - ik.pelvis.follow(ground_y - drop, ground_rate, extra, dt)
}

/// How far the pelvis must come down by the time swinging foot `k` lands,
/// for its leg to reach the landing surface, metres (negative: it reaches
/// with room to spare), and the seconds left until then; `None` for a
/// planted foot, a walker standing still, or a landing no ray found.
///
/// The hip at landing is `hip` carried along the walk's velocity and the
/// ground's rise under the body (`ground_rate`, m/s), with the bob of the
/// landing; the foot may roll toe up ahead of that hip (or heel up behind
/// it) to reach, as a landing foot does. A landing lower than that, down a
/// dune's lee face or off an edge, lowers the pelvis during the swing, the
/// stance knee bending as it does stepping down a stair, so the foot does
/// not land out of reach and hang above its floor.
fn landing_drop(
    body: &CharacterBody,
    gait: &Gait,
    rays: &FootRays,
    hip: Vec3,
    k: usize,
    ground_rate: f32,
) -> Option<(f32, f32)> {
    let plan = &gait.feet[k];
    let support = &rays.support[k];
    if gait.stopped || plan.phase == FootPhase::Stance || !support.hit {
        return None;
    }
    let time = gait.time_to_landing(k);
    let travel = gait.velocity * time;
    let rise = ground_rate * time + gait.bob_at_landing(k) - gait.bob;
    let hip = hip + Vec3::new(travel.x, rise, travel.y);
    let normal = support.landing.normal;
    let frame = FootFrame {
        centre: support.landing.point,
        normal,
        along: sole_direction(plan.foothold_heading, normal),
        contact_along: 0.0,
    };
    let trailing = (frame.centre - hip).dot(gait.pelvis.heading3()) < 0.0;
    let reach = REACH_MARGIN * body.leg_reach();
    let pitch = frame.roll_to_reach(body, hip, reach, 0.0, trailing);
    let ankle = frame.place(body, pitch).ankle;
    Some((-rise_to_reach(hip, ankle, reach), time))
}

/// The lowest a swinging foot on `key` may be pushed this step: into the
/// ground under its sole no deeper than the ground gives in `dt` (its whole
/// give over [`SINK_TIME_S`]), as carving presses it; never below its floor,
/// nor below a platform under it.
fn reachable_floor(key: &GroundKey, dt: f32) -> f32 {
    let pressed = (dt / SINK_TIME_S).min(1.0);
    let floor = key
        .floor
        .max(key.surface - (key.surface - key.floor) * pressed);
    floor.max(key.platform.unwrap_or(f32::MIN))
}

/// What the legs are solved for this step (left first).
struct Legs<'a> {
    /// The hips, lowered by the pelvis drop.
    hips: &'a [Vec3; 2],
    /// The feet as placed on their keys.
    feet: &'a [FootPlacement; 2],
    /// Which feet are planted.
    planted: [bool; 2],
    /// The most each knee may bend this step, radians (see [`knee_limit`]).
    knee_limits: [f32; 2],
}

/// Solves both legs from the (lowered) hips to their
/// ankles, the knees within their limits and speed, into `pose`; returns the
/// feet as placed on the ankles the legs really reached (unrolled where a
/// knee could not bend fast enough, see [`unroll_to_length`]). A `planted`
/// foot the leg cannot reach is lifted straight up to the leg's reach, never
/// pulled towards the hip: it stays where it stands, above its floor, and
/// does not slide.
fn solve_legs(
    ik: &mut FootIK,
    pose: &mut Pose,
    body: &CharacterBody,
    legs: &Legs,
    forward: Vec3,
    dt: f32,
) -> [FootPlacement; 2] {
    let Legs {
        hips,
        feet,
        planted,
        knee_limits,
    } = *legs;
    let joints = [
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
    let mut placed = *feet;
    let mut knees = [0.0; 2];
    for (k, &(hip, knee, ankle, toe)) in joints.iter().enumerate() {
        let hip_at = hips[k];
        let pole = hip_at + forward * body.leg_reach();
        let (l1, l2) = (body.thigh, body.shank);
        // The knee's range, then its speed.
        let mut ankle_target = clamp_flexion(hip_at, feet[k].ankle, 0.0, knee_limits[k], l1, l2);
        if !planted[k] && ankle_target != feet[k].ankle {
            // A swinging foot the knee cannot lift goes straight down where
            // it is in its swing, onto the ground its floor was read from.
            let length = ankle_target.distance(hip_at);
            ankle_target = lift_to_reach(hip_at, feet[k].ankle, length).unwrap_or(ankle_target);
        }
        if let (Some(last), true) = (ik.knee_flexion, dt > 0.0) {
            let (least, most) = flexion_reach(last[k], dt);
            ankle_target = clamp_flexion(hip_at, ankle_target, least, most, l1, l2);
        }
        let length = ankle_target.distance(hip_at).min(l1 + l2);
        let foot = unroll_to_length(body, hip_at, &feet[k], length);
        if foot.pitch != feet[k].pitch {
            ankle_target = hip_at + (foot.ankle - hip_at).normalize_or_zero() * length;
        }
        if planted[k] && foot.ankle.distance(hip_at) > length {
            ankle_target = lift_to_reach(hip_at, foot.ankle, length).unwrap_or(ankle_target);
        }
        let s = solve_two_bone(hip_at, ankle_target, pole, l1, l2);
        knees[k] = flexion_at_distance(s.end.distance(hip_at), l1, l2);
        // The foot follows the ankle the IK really reached.
        placed[k] = foot.moved(s.end - foot.ankle);
        pose.joints[hip as usize] = hip_at;
        pose.joints[knee as usize] = s.mid;
        pose.joints[ankle as usize] = s.end;
        pose.joints[toe as usize] = placed[k].sole.toe + placed[k].normal * foot_radius;
    }
    ik.knee_flexion = Some(knees);
    placed
}

/// Poses the trunk, head and arms over `pelvis`, rotated by the proxy's
/// tilt and lean (along and about the direction of `travel`) about the hips.
fn pose_upper_body(
    pose: &mut Pose,
    body: &CharacterBody,
    gait: &Gait,
    proxy: &RigidProxy,
    pelvis: Vec3,
    travel: Vec3,
    right: Vec3,
) {
    let lean = proxy.body_rotation(travel);
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
}

/// True when a swinging foot `placed` where its leg reached is more than
/// [`PLOUGH_DEPTH`] below where its swing `aimed` it: a knee at the end of
/// its range cannot lift the foot over deep loose ground, so the foot
/// ploughs through it and presses what it meets, as a short leg does in
/// deep snow.
fn ploughs(aimed: &FootPlacement, placed: &FootPlacement) -> bool {
    placed.lowest.y < aimed.lowest.y - PLOUGH_DEPTH
}

/// Each foot's state after the pose (left first); records the lowest sole
/// points and the ankles in `ik`. A foot `ploughing` presses the ground
/// (see [`ploughs`]).
fn foot_states(
    ik: &mut FootIK,
    pose: &Pose,
    gait: &Gait,
    rays: &FootRays,
    feet: &[FootPlacement; 2],
    ploughing: [bool; 2],
    dt: f32,
) -> [FootState; 2] {
    let ankles = [pose.joint(Joint::AnkleLeft), pose.joint(Joint::AnkleRight)];
    ik.contact_points = [feet[0].lowest, feet[1].lowest];
    let states = Side::BOTH.map(|side| {
        let k = side.index();
        FootState {
            side,
            sole: feet[k].sole,
            ankle: ankles[k],
            velocity: if dt > 0.0 {
                (ankles[k] - ik.last_ankles[k]) / dt
            } else {
                Vec3::ZERO
            },
            phase: gait.feet[k].phase,
            contact: rays.feet[k].hit && gait.feet[k].phase == FootPhase::Stance,
            pressing: rays.feet[k].hit && (rays.feet[k].pressing || ploughing[k]),
        }
    });
    ik.last_ankles = ankles;
    states
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::character::CharacterDesc;

    /// A flat foot frame on level ground at height 0, pointing along +X.
    fn level_frame(contact_along: f32) -> FootFrame {
        FootFrame {
            centre: Vec3::ZERO,
            normal: Vec3::Y,
            along: Vec3::X,
            contact_along,
        }
    }

    #[test]
    fn a_knee_too_slow_for_a_heel_rise_unrolls_the_foot_about_its_toe() {
        let body = CharacterBody::new(CharacterDesc::adult()).unwrap();
        let frame = level_frame(0.5 * body.foot_length);
        let lifted = frame.place(&body, -0.6);
        // A hip behind and above the foot, as over a trailing leg at toe-off:
        // the knee may not bend as far as the heel rise asks, so the leg is
        // 3 cm longer than the lifted foot needs.
        let hip = lifted.ankle + Vec3::new(-0.3, 0.75, 0.0);
        let length = lifted.ankle.distance(hip) + 0.03;
        let foot = unroll_to_length(&body, hip, &lifted, length);
        assert!(
            foot.pitch > lifted.pitch && foot.pitch < 0.0,
            "{}",
            foot.pitch
        );
        assert!(foot.sole.toe.distance(lifted.sole.toe) < 1e-5);
        assert!((foot.ankle.distance(hip) - length).abs() < 2e-3);
        assert!(foot.sole.heel.y >= -1e-5 && foot.sole.toe.y >= -1e-5);
    }

    #[test]
    fn a_foot_the_leg_leaves_below_its_swing_ploughs() {
        let body = CharacterBody::new(CharacterDesc::adult()).unwrap();
        let aimed = level_frame(0.0).place(&body, 0.0);
        assert!(!ploughs(&aimed, &aimed));
        assert!(!ploughs(
            &aimed,
            &aimed.moved(Vec3::NEG_Y * (0.5 * PLOUGH_DEPTH))
        ));
        assert!(ploughs(
            &aimed,
            &aimed.moved(Vec3::NEG_Y * (2.0 * PLOUGH_DEPTH))
        ));
        // Higher than aimed (a leg that cannot reach down) is not ploughing.
        assert!(!ploughs(&aimed, &aimed.moved(Vec3::Y * 0.1)));
    }

    #[test]
    fn a_ploughing_foot_goes_into_the_ground_as_fast_as_it_gives() {
        let key = GroundKey {
            point: Vec3::ZERO,
            normal: Vec3::Y,
            hit: true,
            pressing: false,
            floor: -0.3,
            surface: 0.0,
            platform: None,
        };
        // A tenth of the press time: a tenth of the give, at most.
        let step = reachable_floor(&key, 0.1 * SINK_TIME_S);
        assert!((step + 0.03).abs() < 1e-6, "{step}");
        // Never below the floor, however long the step; not at all at dt 0.
        assert_eq!(reachable_floor(&key, 2.0 * SINK_TIME_S), -0.3);
        assert_eq!(reachable_floor(&key, 0.0), 0.0);
        // A platform holds the foot up.
        let held = GroundKey {
            platform: Some(0.05),
            ..key
        };
        assert_eq!(reachable_floor(&held, 0.1), 0.05);
    }

    /// An adult walking along +X at 1 m/s over level ground at height 0,
    /// its left foot planted and its right foot coming down onto a landing
    /// `below` metres under that ground; the right hip at walking height.
    fn landing_below(below: f32) -> (CharacterBody, Gait, FootRays, Vec3) {
        use crate::character::support::SupportPoint;
        use crate::character::{GaitModifiers, WalkPath};
        use crate::ground::FlatGround;
        let body = CharacterBody::new(CharacterDesc::adult()).unwrap();
        let path = WalkPath::straight(Vec3::ZERO, Vec3::X, 5.0).unwrap();
        let mut gait = Gait::new(&body, &path, &GaitModifiers::default());
        gait.velocity = Vec2::X;
        gait.feet[0].phase = FootPhase::Stance;
        gait.feet[1].phase = FootPhase::SwingDown;
        gait.feet[1].foothold = Vec2::new(0.5 * gait.params.stride, 0.1);
        let mut rays = FootRays::new(&gait, &body, &FlatGround(0.0));
        let at = gait.feet[1].foothold;
        rays.support[1].landing = SupportPoint::rigid(Vec3::new(at.x, -below, at.y));
        rays.support[1].hit = true;
        let pelvis = gait.pelvis.position;
        let height = gait.params.walking_hip_height(&body) + gait.bob;
        let hip = Vec3::new(pelvis.x, height, pelvis.y + body.hip_half_width);
        (body, gait, rays, hip)
    }

    #[test]
    fn a_landing_below_the_legs_reach_asks_the_pelvis_down_before_the_foot_lands() {
        let (body, gait, rays, hip) = landing_below(0.0);
        let (level, time) = landing_drop(&body, &gait, &rays, hip, 1, 0.0).unwrap();
        assert!(level <= 0.0, "level ground is within reach: {level}");
        assert!((time - gait.time_to_landing(1)).abs() < 1e-6);
        let (body, gait, rays, hip) = landing_below(0.3);
        let (low, _) = landing_drop(&body, &gait, &rays, hip, 1, 0.0).unwrap();
        assert!(low > 0.15 && low < 0.3, "{low}");
        // Ground falling under the body as fast brings the hip down with it.
        let falling = -0.3 / gait.time_to_landing(1);
        let (carried, _) = landing_drop(&body, &gait, &rays, hip, 1, falling).unwrap();
        assert!((carried - level).abs() < 0.02, "{carried} vs {level}");
        // A planted foot, or a walker standing still, asks for nothing.
        assert!(landing_drop(&body, &gait, &rays, hip, 0, 0.0).is_none());
        let stopped = Gait {
            stopped: true,
            ..gait
        };
        assert!(landing_drop(&body, &stopped, &rays, hip, 1, 0.0).is_none());
    }

    #[test]
    fn a_foot_is_left_alone_when_unrolling_cannot_lengthen_the_leg() {
        let body = CharacterBody::new(CharacterDesc::adult()).unwrap();
        let flat = level_frame(0.0).place(&body, 0.0);
        let hip = flat.ankle + Vec3::new(0.0, 0.8, 0.0);
        let same = unroll_to_length(&body, hip, &flat, 0.9);
        assert_eq!(same.pitch, 0.0);
        assert_eq!(same.ankle, flat.ankle);
        // A leg already long enough keeps its lifted heel.
        let lifted = level_frame(0.5 * body.foot_length).place(&body, -0.4);
        let near = lifted.ankle.distance(hip);
        assert_eq!(unroll_to_length(&body, hip, &lifted, near).pitch, -0.4);
    }
}
