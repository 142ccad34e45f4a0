//! Stage 1, the walk cycle: a parametric walk (Boulic et al. 1990, speed from
//! a Froude number) driven by the distance walked along a [`WalkPath`], with
//! footholds planned along the path at step length.

use std::f32::consts::{PI, TAU};

use glam::{Vec2, Vec3};

use super::body::CharacterBody;
use super::clip_gait::CLIP_DUTY_RANGE;
use super::error::CharacterError;
use super::gravity::GRAVITY;
use super::path::{PathPoint, WalkPath};
use crate::foot::{FootPhase, Side};
use crate::ground::rise_along;

/// The largest time step a stage accepts; longer steps are clamped to it.
pub const MAX_STEP_DT: f32 = 0.05;

/// Foot pitch at heel strike (toe up, about the heel), radians (about 20°).
pub const HEEL_STRIKE_PITCH: f32 = 0.35;
/// Scheduled foot pitch at toe-off (heel up, about the toe), radians (about 34°).
pub const TOE_OFF_PITCH: f32 = 0.6;
/// Fraction of the stance by which the foot is flat after heel strike (loading response).
const FOOT_FLAT_AT: f32 = 0.15;
/// Fraction of the stance at which the heel starts to rise (terminal stance).
const HEEL_RISE_AT: f32 = 0.7;
/// Midstance leg length (hip to ankle) as a fraction of the leg reach: nearly straight (knee flexion about 0.2 rad).
const MIDSTANCE_LEG: f32 = 0.995;
/// How much steps shorten per unit of downhill grade (a 10° descent
/// shortens them by about a fifth, a 20° one by about a third), as
/// people's do.
pub const DOWNHILL_STEP_SHORTENING: f32 = 1.5;
/// How far the duty of a walk at rest stays past its later foot's phase.
const PLANTED_MARGIN: f32 = 1.0e-4;
/// Time over which the feet roll flat once the walk has stopped, seconds.
const STOP_SETTLE_TIME: f32 = 0.25;
/// Fastest change of the pelvis bob's amplitude, m/s: a ground that changes
/// the walking speed at once (stepping from snow onto rigid ground) changes
/// the bob over a few steps, so the pelvis does not jump.
pub const BOB_AMPLITUDE_RATE: f32 = 0.05;
/// Stride factor while walking backward: people step back in short steps.
pub const BACKWARD_STEP_SCALE: f32 = 0.7;
/// Fraction of the scheduled foot roll applied while walking backward (the
/// short steps need less roll to reach).
const BACKWARD_ROLL: f32 = 0.5;

/// Hermite ease from 0 to 1 over `t` in `[0, 1]` (clamped outside).
pub(crate) fn smoothstep(t: f32) -> f32 {
    let t = t.clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// The scheduled foot roll at a foot's own phase `p` (see [`Gait::local_phase`])
/// for a stance fraction `duty`: pitch in radians, positive with the toe up
/// (the foot turns about its heel), negative with the heel up (about its toe).
///
/// Stance: heel strike at `HEEL_STRIKE_PITCH`, rolling flat by 15 % of the
/// stance, flat until 70 %, then heel rise to `TOE_OFF_PITCH` at toe-off.
/// Swing: back to flat at mid-swing, then toe up again for the next strike.
pub fn scheduled_pitch(p: f32, duty: f32) -> f32 {
    if p < duty {
        let s = p / duty;
        if s < FOOT_FLAT_AT {
            HEEL_STRIKE_PITCH * (1.0 - smoothstep(s / FOOT_FLAT_AT))
        } else {
            -TOE_OFF_PITCH * smoothstep((s - HEEL_RISE_AT) / (1.0 - HEEL_RISE_AT))
        }
    } else {
        let u = (p - duty) / (1.0 - duty);
        if u < 0.5 {
            -TOE_OFF_PITCH * (1.0 - smoothstep(2.0 * u))
        } else {
            HEEL_STRIKE_PITCH * smoothstep(2.0 * u - 1.0)
        }
    }
}

/// Share of the scheduled heel rise (negative pitch) a body's feet make: 1
/// for legs of standard length or longer, the leg length factor for
/// shorter legs (the feet keep their length). The heel then lifts the ankle
/// about as far, for the leg's length, as on a standard body, and a short
/// leg's knee bends no further at toe-off.
fn heel_rise_share(body: &CharacterBody) -> f32 {
    body.desc.leg_length_factor.min(1.0)
}

/// The foot roll of a backward step at a foot's own phase `p` for a stance
/// fraction `duty`: [`scheduled_pitch`] run backward in time and scaled down,
/// so the foot lands on its toe, rolls flat, lifts its toe before the heel
/// leaves the ground, and reaches back toe-down through the swing.
pub fn backward_pitch(p: f32, duty: f32) -> f32 {
    BACKWARD_ROLL * scheduled_pitch((duty - p).rem_euclid(1.0), duty)
}

/// The step duration a stage really uses: `dt` clamped to `[0, MAX_STEP_DT]`,
/// with NaN and negative values read as 0 (a no-op step).
pub fn clamp_dt(dt: f32) -> f32 {
    if dt.is_finite() && dt > 0.0 {
        dt.min(MAX_STEP_DT)
    } else {
        0.0
    }
}

/// Per-step changes of the gait asked for by terrain and vegetation systems.
/// The default is neutral.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GaitModifiers {
    /// Multiplies the walking speed (clamped to `[0.1, 2]`; non-finite reads as 1).
    pub speed_scale: f32,
    /// Multiplies the stride length (clamped to `[0.3, 1.5]`; non-finite reads as 1).
    pub step_length_scale: f32,
    /// Added to the swing-foot clearance, metres (clamped to `[0, 0.5]`).
    pub extra_clearance: f32,
    /// Grade of the ground along the walking direction under the body (rise
    /// over run, negative downhill; non-finite reads as 0): steps shorten
    /// downhill, as people's do.
    pub grade: f32,
    /// Deceleration of the walk along its path, m/s² (0 at a steady speed;
    /// steering sets it while braking for a stop; clamped to `[0, 10]`).
    pub braking: f32,
    /// How many times faster than `speed_scale` the walk's timing runs (its
    /// cycle time and stance fraction; clamped to `[1, 10]`, 1 by default):
    /// while braking for a stop, steering keeps the cadence of the walk
    /// before the stop, so the steps shorten instead of slowing down.
    pub cadence_hold: f32,
}

impl GaitModifiers {
    /// These modifiers on ground of unit `normal`, walking along `heading` (x, z).
    pub fn on_ground(self, normal: Vec3, heading: Vec2) -> Self {
        GaitModifiers {
            grade: rise_along(normal, heading),
            ..self
        }
    }
}

impl Default for GaitModifiers {
    fn default() -> Self {
        GaitModifiers {
            speed_scale: 1.0,
            step_length_scale: 1.0,
            extra_clearance: 0.0,
            grade: 0.0,
            braking: 0.0,
            cadence_hold: 1.0,
        }
    }
}

fn sane(value: f32, min: f32, max: f32, neutral: f32) -> f32 {
    if value.is_finite() {
        value.clamp(min, max)
    } else {
        neutral
    }
}

/// Where along the sole (metres from its centre towards the toe) a foot
/// rolled by `pitch` touches the ground: the heel while the toe is up, the toe
/// while the heel is up, the centre when flat.
pub fn contact_offset(pitch: f32, foot_length: f32) -> f32 {
    if pitch > 0.0 {
        -0.5 * foot_length
    } else if pitch < 0.0 {
        0.5 * foot_length
    } else {
        0.0
    }
}

/// The walk's timing and sizes for one body and one set of modifiers.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GaitParams {
    /// Walking speed along the path, m/s.
    pub speed: f32,
    /// Stride (two steps), metres.
    pub stride: f32,
    /// Fraction of the cycle a foot is in stance (above 0.5: double support).
    pub duty: f32,
    /// Peak height of the swing foot above the ground key, metres.
    pub clearance: f32,
    /// Vertical pelvis oscillation amplitude, metres.
    pub bob_amplitude: f32,
    /// Lateral pelvis sway amplitude, metres.
    pub sway_amplitude: f32,
    /// Arm swing amplitude at the shoulder, radians.
    pub arm_amplitude: f32,
    /// Deceleration along the path, m/s² (see [`GaitModifiers::braking`]).
    pub braking: f32,
}

impl GaitParams {
    /// Refuses a body whose legs cannot reach where its level walk lands a
    /// foot: half a stance's travel ahead of the hip, plus a quarter foot.
    pub fn check_reach(body: &CharacterBody) -> Result<(), CharacterError> {
        let gait = GaitParams::new(body, &GaitModifiers::default());
        let farthest = gait.duty * gait.stride / 2.0 + 0.25 * body.foot_length;
        if farthest > 0.9 * body.leg_reach() {
            return Err(CharacterError::InvalidField {
                field: "froude",
                reason: format!(
                    "the stride ({:.2} m) needs the legs to reach {farthest:.2} m ahead, \
                     more than they can ({:.2} m)",
                    gait.stride,
                    body.leg_reach()
                ),
            });
        }
        Ok(())
    }

    /// Boulic's walk for this body: v = sqrt(Fr g Ht), RV = v / Ht,
    /// stride = 1.346 sqrt(RV) Ht, support time 0.752 Dc - 0.143; or, when
    /// its description has a [`super::ClipGait`], the clip's walk scaled to it.
    /// The modifiers scale either. A [`GaitModifiers::cadence_hold`] times
    /// the walk at the held speed and shortens its stride to the real one.
    pub fn new(body: &CharacterBody, modifiers: &GaitModifiers) -> Self {
        let ht = body.hip_height;
        let speed_scale = sane(modifiers.speed_scale, 0.1, 2.0, 1.0);
        let hold = sane(modifiers.cadence_hold, 1.0, 10.0, 1.0);
        let timing_scale = sane(speed_scale * hold, 0.1, 2.0, 1.0);
        let (timed_speed, timed_stride, duty) = walk_timing(body, modifiers, timing_scale);
        let shorter = speed_scale / timing_scale;
        let speed = timed_speed * shorter;
        let rv = speed / ht;
        GaitParams {
            speed,
            stride: timed_stride * shorter,
            duty,
            clearance: 0.1 * ht + sane(modifiers.extra_clearance, 0.0, 0.5, 0.0),
            bob_amplitude: 0.015 * rv * ht,
            sway_amplitude: 0.032 * ht,
            arm_amplitude: (9.88 * rv).to_radians(),
            braking: sane(modifiers.braking, 0.0, 10.0, 0.0),
        }
    }

    /// Hip height above the ground at midstance, the top of the bob (before
    /// the IK drop): the stance leg is nearly straight (99.5 % of its reach)
    /// over a flat foot whose sole centre is under the hip. The ends of the
    /// stance are reached by the foot roll (heel strike, heel rise), not by
    /// lowering the whole walk.
    pub fn walking_hip_height(&self, body: &CharacterBody) -> f32 {
        let leg = MIDSTANCE_LEG * body.leg_reach();
        let behind = body.ankle_above_sole().z;
        body.ankle_height + (leg * leg - behind * behind).sqrt()
    }

    /// Duration of one walk cycle (two steps), seconds.
    pub fn cycle_time(&self) -> f32 {
        self.stride / self.speed
    }

    /// Duration of one foot's swing, seconds: the cycle less its stance.
    pub fn swing_time(&self) -> f32 {
        self.cycle_time() * (1.0 - self.duty)
    }
}

/// What the walk cycle asks of one foot this step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FootPlan {
    /// Which leg.
    pub side: Side,
    /// Stance, or the up/down half of the swing.
    pub phase: FootPhase,
    /// Where the last stance was (x, z of the sole centre).
    pub from: Vec2,
    /// The planned (in stance: the locked) foothold, x and z of the sole centre.
    pub foothold: Vec2,
    /// Swing progress in `[0, 1]` (0 in stance).
    pub swing: f32,
    /// Sole centre (x, z) the foot should be at this step.
    pub target: Vec2,
    /// Height of the sole's lowest point above the ground key, metres (0 in stance).
    pub lift: f32,
    /// Scheduled foot roll, radians: toe up (> 0, about the heel) or heel
    /// up (< 0, about the toe); see [`scheduled_pitch`].
    pub pitch: f32,
    /// Path heading (x, z) where the last stance was.
    pub from_heading: Vec2,
    /// Path heading (x, z) at the planned foothold.
    pub foothold_heading: Vec2,
    /// Unit direction (x, z) from heel to toe this step: locked in stance
    /// (so a planted foot does not turn), turning during the swing.
    pub heading: Vec2,
    /// Where along the sole the foot's ray is cast, metres from the sole
    /// centre towards the toe: the part that touches, or will touch, the
    /// ground. In stance under the heel pad for the first half and under the
    /// ball for the second (both touch while the foot is flat), in the swing
    /// under the part [`contact_offset`] picks for the scheduled roll.
    pub contact_along: f32,
    /// That point (x, z) on the horizontal heading (the ray is cast where
    /// the sole, lying along the ground, puts it).
    pub contact: Vec2,
}

/// The walk-cycle state of one character.
#[derive(Debug, Clone, PartialEq)]
pub struct Gait {
    /// Distance walked along the path, metres.
    pub distance: f32,
    /// Walk-cycle phase in `[0, 1)`: 0 is the left foot's landing.
    pub phase: f32,
    /// Timing and sizes used this step.
    pub params: GaitParams,
    /// The two feet, left first.
    pub feet: [FootPlan; 2],
    /// The path point under the pelvis (its heading is the facing direction).
    pub pelvis: PathPoint,
    /// True while walking a path backward: short steps against the facing
    /// direction, the feet rolling toe first.
    pub backward: bool,
    /// Lateral pelvis offset along the character's right, metres.
    pub sway: f32,
    /// Vertical pelvis offset (<= 0), metres.
    pub bob: f32,
    /// Amplitude of the bob, metres: it follows the walk's
    /// [`GaitParams::bob_amplitude`] at `BOB_AMPLITUDE_RATE`.
    pub bob_amplitude: f32,
    /// Left arm swing angle, radians (positive forward; the right arm is opposite).
    pub arm_swing: f32,
    /// Horizontal velocity of the pelvis along the path, m/s (x, z).
    pub velocity: Vec2,
    /// True once the path has ended and both feet are planted.
    pub stopped: bool,
    /// How much of the scheduled foot roll is applied: 1 while walking,
    /// falling to 0 over a quarter second once stopped (the feet roll flat,
    /// the sway and arm swing settle) and rising back over a quarter second
    /// when the walk starts again.
    pub roll: f32,
}

impl Gait {
    /// A character standing at the start of `path` in double support, left foot ahead.
    pub fn new(body: &CharacterBody, path: &WalkPath, modifiers: &GaitModifiers) -> Self {
        let params = walk_params(body, path, modifiers);
        let pelvis = path.point_at(0.0);
        let mut gait = Gait {
            distance: 0.0,
            phase: 0.0,
            params,
            feet: Side::BOTH.map(|side| FootPlan {
                side,
                phase: FootPhase::Stance,
                from: pelvis.position,
                foothold: pelvis.position,
                swing: 0.0,
                target: pelvis.position,
                lift: 0.0,
                pitch: 0.0,
                from_heading: pelvis.heading,
                foothold_heading: pelvis.heading,
                heading: pelvis.heading,
                contact_along: 0.0,
                contact: pelvis.position,
            }),
            pelvis,
            backward: path.is_backward(),
            sway: 0.0,
            bob: 0.0,
            bob_amplitude: params.bob_amplitude,
            arm_swing: 0.0,
            velocity: Vec2::ZERO,
            stopped: false,
            roll: 1.0,
        };
        for k in 0..2 {
            let p = gait.local_phase(k);
            let (duty, stride) = (params.duty, params.stride);
            let last = gait.foothold_at(body, path, k, stride * (duty / 2.0 - p));
            let next = if p >= duty {
                gait.foothold_at(body, path, k, stride * (1.0 + duty / 2.0 - p))
            } else {
                last
            };
            let plan = &mut gait.feet[k];
            (plan.from, plan.from_heading) = last;
            (plan.foothold, plan.foothold_heading) = next;
            if p >= duty {
                plan.phase = FootPhase::SwingUp;
            }
        }
        gait.update_feet(body, path);
        gait.update_body(0.0);
        gait
    }

    /// The foot's own phase: the right foot runs half a cycle behind the left.
    pub fn local_phase(&self, foot: usize) -> f32 {
        (self.phase + 0.5 * foot as f32).fract()
    }

    /// Seconds until `foot`'s phase comes round to its landing (the end of
    /// its swing), at the walk's cadence.
    pub fn time_to_landing(&self, foot: usize) -> f32 {
        (1.0 - self.local_phase(foot)) * self.params.cycle_time()
    }

    /// The pelvis bob when `foot` lands (at the end of its swing), metres,
    /// at the bob's current amplitude.
    pub fn bob_at_landing(&self, foot: usize) -> f32 {
        bob_at(self.bob_amplitude, (1.0 - 0.5 * foot as f32).fract())
    }

    /// The unit direction of travel (x, z): the facing direction, or (while
    /// walking backward) away from it.
    pub fn travel_heading(&self) -> Vec2 {
        self.pelvis.travel
    }

    /// The share of the body's weight `foot` bears, in `[0, 1]`: none in its
    /// swing, all of it alone on the ground (or standing still), and passed
    /// smoothly from the trailing foot to the leading one over the double
    /// support after each landing.
    pub fn load_share(&self, foot: usize) -> f32 {
        if self.feet[foot].phase != FootPhase::Stance {
            return 0.0;
        }
        if self.stopped {
            return 1.0;
        }
        let p = self.local_phase(foot);
        let overlap = (self.params.duty - 0.5).max(f32::EPSILON);
        if p < overlap {
            smoothstep(p / overlap)
        } else if p > 0.5 {
            1.0 - smoothstep((p - 0.5) / overlap)
        } else {
            1.0
        }
    }

    /// How fast the bob raises the pelvis this step, m/s (negative while it
    /// lowers it; 0 standing still).
    pub fn bob_rate(&self) -> f32 {
        if self.stopped {
            return 0.0;
        }
        let phase_rate = self.params.speed / self.params.stride.max(f32::EPSILON);
        let swing = bob_angle(self.phase).cos();
        self.bob_amplitude * 2.0 * TAU * phase_rate * swing
    }

    /// True while both feet are in stance.
    pub fn double_support(&self) -> bool {
        self.feet.iter().all(|f| f.phase == FootPhase::Stance)
    }

    /// The sole-centre foothold of `foot` at `ahead` metres from the current
    /// distance, and the path heading there.
    fn foothold_at(
        &self,
        body: &CharacterBody,
        path: &WalkPath,
        foot: usize,
        ahead: f32,
    ) -> (Vec2, Vec2) {
        let mut s = self.distance + ahead;
        if !path.is_looped() {
            s = s.min(path.end_distance());
        }
        let p = path.point_at(s);
        let right = Vec2::new(-p.heading.y, p.heading.x);
        let sign = if foot == 0 { -1.0 } else { 1.0 };
        (p.position + right * (sign * body.hip_half_width), p.heading)
    }

    /// Raises the duty, where the ground has shortened it, to just past the
    /// later foot's phase: a walk at rest has both feet planted, and the
    /// ground settling under them must not put one in a swing.
    fn keep_feet_planted(&mut self) {
        let latest = self.local_phase(0).max(self.local_phase(1));
        self.params.duty = self.params.duty.max(latest + PLANTED_MARGIN);
    }

    /// Sets each foot's phase, target and lift from the cycle phase, planning
    /// a new foothold at lift-off.
    fn update_feet(&mut self, body: &CharacterBody, path: &WalkPath) {
        let GaitParams {
            duty,
            stride,
            clearance,
            ..
        } = self.params;
        for k in 0..2 {
            let p = self.local_phase(k);
            let in_stance = p < duty;
            if !in_stance && self.feet[k].phase == FootPhase::Stance {
                let next = self.foothold_at(body, path, k, stride * (1.0 + duty / 2.0 - p));
                let plan = &mut self.feet[k];
                plan.from = plan.foothold;
                plan.from_heading = plan.foothold_heading;
                (plan.foothold, plan.foothold_heading) = next;
            }
            let scheduled = if self.backward {
                backward_pitch(p, duty)
            } else {
                scheduled_pitch(p, duty)
            };
            let pitch = self.roll * scheduled.max(scheduled * heel_rise_share(body));
            let plan = &mut self.feet[k];
            plan.pitch = pitch;
            if in_stance {
                plan.phase = FootPhase::Stance;
                plan.swing = 0.0;
                plan.target = plan.foothold;
                plan.heading = plan.foothold_heading;
                plan.lift = 0.0;
            } else {
                let u = ((p - duty) / (1.0 - duty)).clamp(0.0, 1.0);
                let eased = u * u * (3.0 - 2.0 * u);
                plan.phase = if u < 0.5 {
                    FootPhase::SwingUp
                } else {
                    FootPhase::SwingDown
                };
                plan.swing = u;
                plan.target = plan.from.lerp(plan.foothold, eased);
                plan.heading = plan
                    .from_heading
                    .lerp(plan.foothold_heading, eased)
                    .try_normalize()
                    .unwrap_or(plan.foothold_heading);
                plan.lift = clearance * (PI * u).sin();
            }
            plan.contact_along = if in_stance {
                let half = 0.5 * body.foot_length;
                let heel_first = !self.backward;
                if (p < 0.5 * duty) == heel_first {
                    -half
                } else {
                    half
                }
            } else {
                contact_offset(plan.pitch, body.foot_length)
            };
            plan.contact = plan.target + plan.heading * plan.contact_along;
        }
    }

    /// Brings the landing of a foot still rising in its swing back to the
    /// path's end when it was planned beyond it (the path was cut short: a
    /// stop), so the walker's feet come to rest side by side. The swing
    /// stays continuous: its start is moved so the foot is where it was.
    /// A foot already coming down keeps its landing: moving the start of a
    /// swing that far along would swing it backward first.
    fn shorten_rising_swings(&mut self, body: &CharacterBody, path: &WalkPath) {
        let travel = self.travel_heading();
        let left = path.end_distance() - self.distance;
        for k in 0..2 {
            let plan = &self.feet[k];
            let ahead = (plan.foothold - self.pelvis.position).dot(travel);
            if plan.phase != FootPhase::SwingUp || ahead <= left + 1.0e-4 {
                continue;
            }
            let (end, end_heading) = self.foothold_at(body, path, k, f32::INFINITY);
            let beyond = (plan.foothold - end).dot(travel) > 1.0e-4;
            if !beyond || (end - plan.target).dot(travel) <= 0.0 {
                continue;
            }
            let eased = smoothstep(plan.swing);
            let keep = |now: Vec2, to: Vec2| (now - to * eased) / (1.0 - eased);
            let plan = &mut self.feet[k];
            plan.from = keep(plan.target, end);
            plan.from_heading = keep(plan.heading, end_heading)
                .try_normalize()
                .unwrap_or(end_heading);
            (plan.foothold, plan.foothold_heading) = (end, end_heading);
        }
    }

    /// Pelvis bob and sway and arm swing from the cycle phase (Boulic's
    /// curves); sway and arms as far as the foot roll is applied (they
    /// settle with the feet at a stop), the arms against the legs, so
    /// backward the other way round.
    fn update_body(&mut self, dt: f32) {
        let p = &self.params;
        let (phi, r) = (self.phase, self.roll);
        let most = BOB_AMPLITUDE_RATE * dt;
        self.bob_amplitude += (p.bob_amplitude - self.bob_amplitude).clamp(-most, most);
        let a = self.bob_amplitude;
        self.bob = bob_at(a, phi);
        self.sway = r * -p.sway_amplitude * (TAU * (phi - 0.1)).sin();
        let arms = if self.backward { -r } else { r };
        self.arm_swing = arms * p.arm_amplitude * (TAU * (phi - 0.15)).sin();
    }
}

/// The walk's speed (m/s), stride (m) and stance fraction at `speed_scale`
/// (see [`GaitParams::new`]).
fn walk_timing(
    body: &CharacterBody,
    modifiers: &GaitModifiers,
    speed_scale: f32,
) -> (f32, f32, f32) {
    let ht = body.hip_height;
    let length_scale = sane(modifiers.step_length_scale, 0.3, 1.5, 1.0);
    let grade = sane(modifiers.grade, -2.0, 2.0, 0.0);
    let slope_scale = 1.0 / (1.0 + DOWNHILL_STEP_SHORTENING * (-grade).max(0.0));
    match body.desc.clip_gait {
        Some(clip) => {
            let walk = clip.timing(body.leg_reach(), body.hip_height);
            let stride = walk.stride * length_scale * slope_scale;
            (walk.speed * speed_scale, stride, walk.duty)
        }
        None => {
            let speed = (body.desc.froude * GRAVITY * ht).sqrt() * speed_scale;
            let rv = speed / ht;
            let stride = 1.346 * rv.sqrt() * ht * length_scale * slope_scale;
            let cycle = stride / speed;
            let duty = (0.752 * cycle - 0.143) / cycle;
            (
                speed,
                stride,
                duty.clamp(CLIP_DUTY_RANGE.0, CLIP_DUTY_RANGE.1),
            )
        }
    }
}

/// The walk's parameters on `path`: backward, steps shorten by
/// [`BACKWARD_STEP_SCALE`].
fn walk_params(body: &CharacterBody, path: &WalkPath, modifiers: &GaitModifiers) -> GaitParams {
    if path.is_backward() {
        let shorter = GaitModifiers {
            step_length_scale: modifiers.step_length_scale * BACKWARD_STEP_SCALE,
            ..*modifiers
        };
        GaitParams::new(body, &shorter)
    } else {
        GaitParams::new(body, modifiers)
    }
}

/// The foot roll after a step of `dt` of the last step of a stop (the
/// pelvis at the path's end, a foot still swinging): it falls in
/// proportion to the time left until that foot lands, so the closing foot
/// lands flat and the planted one keeps its heel down.
fn closing_roll(gait: &Gait, dt: f32) -> f32 {
    let left = (0..2)
        .filter(|&k| gait.feet[k].phase != FootPhase::Stance)
        .map(|k| gait.time_to_landing(k))
        .fold(0.0f32, f32::max);
    if left > dt {
        gait.roll * (1.0 - dt / left)
    } else {
        0.0
    }
}

/// Stage 1: advances the walk cycle by `dt` (see [`clamp_dt`]) along `path`.
///
/// The phase advances with the distance walked (`speed * dt / stride`). At the
/// end of a path that does not loop the pelvis stops and the phase runs on
/// until both feet are planted, the feet rolling flat by that landing; then
/// the gait is `stopped` and keeps its timing, so no change of the ground
/// under a standing walker lifts a planted foot, until the path reaches
/// further (a steered path), when the walk starts again and the feet roll
/// back in over a quarter second. When the path's direction of travel
/// turns round (forward to backward or back), the cycle runs backward in
/// time from where it stands: the phase is mirrored about the stance, so the
/// foot that just landed ahead is the next to lift.
pub fn gait_stage(
    gait: &mut Gait,
    body: &CharacterBody,
    path: &WalkPath,
    modifiers: &GaitModifiers,
    dt: f32,
) {
    let dt = clamp_dt(dt);
    let finishing = path.is_finished(gait.distance);
    if !(gait.stopped && finishing) {
        gait.params = walk_params(body, path, modifiers);
    }
    if gait.backward != path.is_backward() {
        gait.backward = path.is_backward();
        gait.phase = (gait.params.duty - gait.phase).rem_euclid(1.0);
    }
    if gait.stopped && dt > 0.0 && !finishing {
        gait.stopped = false;
    }
    if dt == 0.0 || gait.stopped {
        gait.velocity = Vec2::ZERO;
        if gait.stopped && gait.roll > 0.0 {
            let settled = (gait.roll - dt / STOP_SETTLE_TIME).max(0.0);
            let k = settled / gait.roll;
            (gait.sway, gait.arm_swing) = (gait.sway * k, gait.arm_swing * k);
            gait.roll = settled;
            gait.update_feet(body, path);
        }
        return;
    }
    if finishing && gait.double_support() {
        gait.keep_feet_planted();
        gait.stopped = true;
        gait.velocity = Vec2::ZERO;
        return;
    }
    let step = gait.params.speed * dt;
    let before = gait.pelvis.position;
    if finishing {
        gait.roll = closing_roll(gait, dt);
    } else {
        gait.distance += step;
        if !path.is_looped() {
            gait.distance = gait.distance.min(path.end_distance());
        }
        if gait.roll < 1.0 {
            gait.roll = (gait.roll + dt / STOP_SETTLE_TIME).min(1.0);
        }
    }
    gait.phase = (gait.phase + step / gait.params.stride).fract();
    gait.pelvis = path.point_at(gait.distance);
    gait.velocity = (gait.pelvis.position - before) / dt;
    if !path.is_looped() {
        gait.shorten_rising_swings(body, path);
    }
    gait.update_feet(body, path);
    gait.update_body(dt);
}

/// The pelvis bob of amplitude `amplitude` at cycle phase `phase` (Boulic's
/// curve, twice per cycle), metres, between `-2 * amplitude` and 0.
fn bob_at(amplitude: f32, phase: f32) -> f32 {
    -amplitude + amplitude * bob_angle(phase).sin()
}

/// The angle of the bob's curve at cycle phase `phase`, radians (see [`bob_at`]).
fn bob_angle(phase: f32) -> f32 {
    TAU * (2.0 * phase - 0.35)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::character::CharacterDesc;

    /// An adult with the default modifiers, standing at the start of a
    /// straight `length` metres along +Z.
    fn adult_walk(length: f32) -> (CharacterBody, WalkPath, GaitModifiers, Gait) {
        let body = CharacterBody::new(CharacterDesc::adult()).unwrap();
        let path = WalkPath::straight(Vec3::ZERO, Vec3::Z, length).unwrap();
        let mods = GaitModifiers::default();
        let gait = Gait::new(&body, &path, &mods);
        (body, path, mods, gait)
    }

    #[test]
    fn adult_walk_matches_boulic_figures() {
        let body = CharacterBody::new(CharacterDesc::adult()).unwrap();
        let p = GaitParams::new(&body, &GaitModifiers::default());
        assert!((1.0..1.4).contains(&p.speed), "speed {}", p.speed);
        assert!((1.2..1.6).contains(&p.stride), "stride {}", p.stride);
        assert!((0.55..0.7).contains(&p.duty));
    }

    #[test]
    fn a_sudden_change_of_walking_speed_changes_the_bob_gradually() {
        let body = CharacterBody::new(CharacterDesc::adult()).unwrap();
        let path = WalkPath::straight(Vec3::ZERO, Vec3::Z, 20.0).unwrap();
        let (dt, slow) = (
            1.0 / 60.0,
            GaitModifiers {
                speed_scale: 0.65,
                ..GaitModifiers::default()
            },
        );
        let mut gait = Gait::new(&body, &path, &slow);
        for _ in 0..120 {
            gait_stage(&mut gait, &body, &path, &slow, dt);
        }
        // Onto ground that lets it walk at its own speed: the bob's
        // amplitude follows at its rate, so the pelvis does not jump.
        let fast = GaitModifiers::default();
        let mut worst = 0.0f32;
        for _ in 0..60 {
            let (bob, phase) = (gait.bob, gait.phase);
            gait_stage(&mut gait, &body, &path, &fast, dt);
            let steady = {
                let a = gait.bob_amplitude;
                bob_at(a, gait.phase) - bob_at(a, phase)
            };
            worst = worst.max((gait.bob - bob - steady).abs());
        }
        assert!(worst <= 2.0 * BOB_AMPLITUDE_RATE * dt + 1e-6, "{worst}");
        assert_eq!(gait.bob_amplitude, gait.params.bob_amplitude);
    }

    #[test]
    fn the_weight_passes_from_the_trailing_foot_to_the_leading_one_over_the_double_support() {
        let (body, path, mods, mut gait) = adult_walk(50.0);
        let (mut last, mut trailing_fell) = (gait.load_share(0), false);
        for _ in 0..240 {
            gait_stage(&mut gait, &body, &path, &mods, 1.0 / 60.0);
            let shares = [0, 1].map(|k| gait.load_share(k));
            assert!((shares[0] + shares[1] - 1.0).abs() < 1e-4, "{shares:?}");
            for (plan, &share) in gait.feet.iter().zip(&shares) {
                let swinging = plan.phase != FootPhase::Stance;
                assert!(!swinging || share == 0.0, "a swinging foot bears none");
                if !swinging && !gait.double_support() {
                    assert_eq!(share, 1.0, "alone on the ground, all of it");
                }
            }
            // Smoothly: no share jumps by more than a few percent a step.
            assert!((shares[0] - last).abs() < 0.25, "{last} -> {}", shares[0]);
            trailing_fell |= gait.double_support() && shares[0] > 0.0 && shares[0] < 1.0;
            last = shares[0];
        }
        assert!(trailing_fell, "shared during the double support");
    }

    #[test]
    fn a_short_legged_walker_lifts_its_heel_less_at_toe_off_and_its_toe_as_much() {
        // The deepest heel rise and the highest toe lift over two walk cycles.
        let extremes = |legs: f32| {
            let desc = CharacterDesc {
                leg_length_factor: legs,
                ..CharacterDesc::adult()
            };
            let body = CharacterBody::new(desc).unwrap();
            let path = WalkPath::straight(Vec3::ZERO, Vec3::Z, 50.0).unwrap();
            let mods = GaitModifiers::default();
            let mut gait = Gait::new(&body, &path, &mods);
            let (mut heel, mut toe) = (0.0f32, 0.0f32);
            for _ in 0..240 {
                gait_stage(&mut gait, &body, &path, &mods, 1.0 / 60.0);
                for plan in &gait.feet {
                    (heel, toe) = (heel.min(plan.pitch), toe.max(plan.pitch));
                }
            }
            (heel, toe)
        };
        let (standard_heel, standard_toe) = extremes(1.0);
        assert!(
            (standard_heel + TOE_OFF_PITCH).abs() < 0.02,
            "{standard_heel}"
        );
        let (short_heel, short_toe) = extremes(0.7);
        assert!(
            (short_heel - 0.7 * standard_heel).abs() < 0.02,
            "{short_heel}"
        );
        assert!((short_toe - standard_toe).abs() < 0.02, "{short_toe}");
        let (long_heel, _) = extremes(1.3);
        assert!((long_heel - standard_heel).abs() < 0.02, "{long_heel}");
    }

    #[test]
    fn dt_is_clamped_and_bad_dt_is_a_no_op() {
        assert_eq!(clamp_dt(1.0), MAX_STEP_DT);
        assert_eq!(clamp_dt(f32::NAN), 0.0);
        assert_eq!(clamp_dt(-1.0), 0.0);
        let (body, path, mods, mut gait) = adult_walk(5.0);
        let before = gait.clone();
        gait_stage(&mut gait, &body, &path, &mods, 0.0);
        assert_eq!(gait.distance, before.distance);
        gait_stage(&mut gait, &body, &path, &mods, 100.0);
        assert!((gait.distance - gait.params.speed * MAX_STEP_DT).abs() < 1e-5);
    }

    #[test]
    fn a_standing_walker_keeps_both_feet_planted_whatever_the_ground_asks() {
        let body = CharacterBody::new(CharacterDesc::adult()).unwrap();
        let mods = GaitModifiers::default();
        let asked = [
            GaitModifiers {
                speed_scale: 2.0,
                step_length_scale: 0.3,
                ..mods
            },
            GaitModifiers {
                speed_scale: 0.3,
                ..mods
            },
            GaitModifiers {
                grade: -1.0,
                ..mods
            },
        ];
        let long = WalkPath::straight(Vec3::ZERO, Vec3::Z, 20.0).unwrap();
        let mut gait = Gait::new(&body, &long, &mods);
        // Double support late in the left foot's stance, where a shorter
        // stance fraction would end it.
        while gait.distance < 3.0 || (gait.phase - 0.6).abs() > 0.01 {
            gait_stage(&mut gait, &body, &long, &mods, 1.0 / 60.0);
        }
        assert!(gait.double_support());
        let here = WalkPath::straight(Vec3::ZERO, Vec3::Z, gait.distance).unwrap();
        gait_stage(&mut gait, &body, &here, &mods, 1.0 / 60.0);
        assert!(gait.stopped && gait.roll > 0.0);
        let planted = gait.feet.map(|f| f.foothold);
        for m in &asked {
            for _ in 0..30 {
                gait_stage(&mut gait, &body, &here, m, 1.0 / 60.0);
                assert!(gait.double_support(), "{m:?}: a foot lifted");
                assert_eq!(gait.feet.map(|f| f.foothold), planted);
            }
        }
    }

    #[test]
    fn walk_stops_at_the_end_with_both_feet_planted() {
        let (body, path, mods, mut gait) = adult_walk(3.0);
        for _ in 0..600 {
            gait_stage(&mut gait, &body, &path, &mods, 1.0 / 60.0);
        }
        assert!(gait.stopped);
        assert!(gait.double_support());
        for f in &gait.feet {
            assert!((f.target.y - 3.0).abs() < 0.5 * gait.params.stride);
        }
        // The ground shortening the duty at rest (a quicker walk) leaves
        // both feet planted.
        let quicker = GaitModifiers {
            speed_scale: 1.8,
            ..mods
        };
        assert!(GaitParams::new(&body, &quicker).duty < gait.params.duty);
        for _ in 0..60 {
            gait_stage(&mut gait, &body, &path, &quicker, 1.0 / 60.0);
            assert!(gait.stopped && gait.double_support());
        }
    }
}
