//! Steering: a character whose path is generated from input.
//!
//! A [`Steering`] holds a desired planar velocity. Each step [`brake_modifiers`]
//! turns it into the [`WalkPath`] the gait follows, starting at the pelvis
//! and continuing the distance already walked:
//! - a desired direction within [`SteeringSettings::pivot_start`] of the
//!   heading gives an arc towards it (radius from the speed, never below
//!   `min_radius`) and then a straight run;
//! - a direction further round turns on the spot first (a
//!   [`PathSegment::Pivot`]) until the heading is within `pivot_end`;
//! - a wish (up to `backward_max_speed`) further than `backward_start`
//!   from the heading steps backward: the walker keeps facing forward and
//!   walks a path [stepped back](WalkPath::stepped_back) towards the wish
//!   (straight behind or aslant, so S with A or D steps back diagonally),
//!   slower (`backward_speed_factor`, at most `backward_top_speed`) and in
//!   the gait's short backward steps;
//! - a speed below `stop_speed` brakes: a stop is placed where the walker
//!   comes to rest as its closing foot lands ([`stop_distance`]: from its
//!   speed and the time until that landing, [`closing_time`]) and the
//!   walking speed falls from the first step, at a constant deceleration,
//!   to the stop (a [`Brake`]), while the walk keeps its cadence
//!   ([`GaitModifiers::cadence_hold`]): the steps shorten, the step being taken ends, and
//!   the closing step lands beside it; the gait halts there with both feet
//!   flat, and starts again on the next desired velocity, speeding up from
//!   its braked speed at `speed_change_rate` (the bob grows with it).
//!
//! Switching between walking forward and backward goes through a stop:
//! the walker halts, its feet roll flat, and then it walks the other way.
//!
//! Footholds are still planned at lift-off and locked for the stance, so a
//! turn never slides a planted foot.

use glam::{Vec2, Vec3};

use super::body::CharacterBody;
use super::error::CharacterError;
use super::gait::{Gait, GaitModifiers, GaitParams, clamp_dt};
use super::path::{PathSegment, WalkPath, turn_angle};

/// How a [`Steering`] shapes the paths it generates.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SteeringSettings {
    /// Sideways acceleration a curve may ask for, m/s² (sets the radius
    /// `v² / a` at speed `v`).
    pub max_lateral_acceleration: f32,
    /// The tightest curve radius, metres.
    pub min_radius: f32,
    /// A desired direction further than this from the heading (radians)
    /// starts a turn on the spot.
    pub pivot_start: f32,
    /// A turn on the spot ends once the heading is within this (radians).
    pub pivot_end: f32,
    /// Distance walked per radian turned on the spot, metres.
    pub pivot_reach: f32,
    /// The smallest speed scale of a turn on the spot (so slow input still
    /// turns at a walking cadence).
    pub pivot_min_speed_scale: f32,
    /// Length of the straight run after the turn, metres (beyond the
    /// farthest foothold the gait plans).
    pub lookahead: f32,
    /// The hardest deceleration a stop asks for, m/s²: sets the shortest
    /// distance to a stop, `v² / (2 a)` at speed `v`.
    pub stop_deceleration: f32,
    /// The shortest distance to a stop, metres.
    pub stop_min_distance: f32,
    /// The smallest speed scale while braking.
    pub stop_speed_floor: f32,
    /// Desired speeds below this stop the walk, m/s.
    pub stop_speed: f32,
    /// How fast the speed scale follows the wish, per second (a sudden
    /// change of speed would jump the pelvis bob, which scales with speed).
    pub speed_change_rate: f32,
    /// A wish further than this from the heading (radians) and no faster
    /// than `backward_max_speed` steps backward instead of turning round.
    pub backward_start: f32,
    /// The fastest wish that steps backward, m/s; faster ones turn round.
    pub backward_max_speed: f32,
    /// Backward walking speed as a fraction of the wished speed.
    pub backward_speed_factor: f32,
    /// The fastest backward walk, m/s (a hurried step back stays short).
    pub backward_top_speed: f32,
}

impl Default for SteeringSettings {
    fn default() -> Self {
        SteeringSettings {
            max_lateral_acceleration: 2.5,
            min_radius: 0.6,
            pivot_start: 100f32.to_radians(),
            pivot_end: 15f32.to_radians(),
            pivot_reach: 0.9,
            pivot_min_speed_scale: 0.7,
            lookahead: 5.0,
            stop_deceleration: 3.0,
            stop_min_distance: 0.05,
            stop_speed_floor: 0.25,
            stop_speed: 0.05,
            speed_change_rate: 1.0,
            backward_start: 120f32.to_radians(),
            backward_max_speed: 2.0,
            backward_speed_factor: 0.5,
            backward_top_speed: 0.9,
        }
    }
}

/// A character steered by a desired velocity (component).
#[derive(Debug, Clone, PartialEq)]
pub struct Steering {
    desired: Vec2,
    pivoting: bool,
    stopping: bool,
    brake: Option<Brake>,
    speed_scale: f32,
    /// How the paths are shaped.
    pub settings: SteeringSettings,
}

impl Default for Steering {
    fn default() -> Self {
        Steering {
            desired: Vec2::ZERO,
            pivoting: false,
            stopping: false,
            brake: None,
            speed_scale: 1.0,
            settings: SteeringSettings::default(),
        }
    }
}

impl Steering {
    /// A steering standing still, with the default settings.
    pub fn new() -> Self {
        Self::default()
    }

    /// Asks for a planar velocity `(x, z)` in m/s; zero stops. A non-finite
    /// velocity is refused and the previous one kept.
    pub fn set_desired_velocity(&mut self, velocity: Vec2) -> Result<(), CharacterError> {
        if !velocity.is_finite() {
            return Err(CharacterError::InvalidField {
                field: "desired_velocity",
                reason: format!("{velocity} is not finite"),
            });
        }
        self.desired = velocity;
        Ok(())
    }

    /// The velocity asked for, m/s (x, z).
    pub fn desired_velocity(&self) -> Vec2 {
        self.desired
    }

    /// True while turning on the spot.
    pub fn is_pivoting(&self) -> bool {
        self.pivoting
    }

    /// The stop being braked for, if any.
    pub fn brake(&self) -> Option<&Brake> {
        self.brake.as_ref()
    }
}

/// A stop being braked for: the walking speed falls from `from_scale` at
/// `distance` metres before the stop, with its square proportional to the
/// distance left (a constant deceleration), to the settings' floor.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Brake {
    /// The speed scale when the stop was asked for.
    pub from_scale: f32,
    /// The distance to the stop when it was asked for, metres.
    pub distance: f32,
    /// The deceleration, m/s² (the walking speed then over `2 · distance`).
    pub deceleration: f32,
}

impl Brake {
    /// The speed scale `left` metres before the stop, at least `floor`.
    pub fn scale_at(&self, left: f32, floor: f32) -> f32 {
        let share = (left / self.distance).clamp(0.0, 1.0);
        (self.from_scale * share.sqrt()).max(floor.min(self.from_scale))
    }
}

/// How far ahead a walker at `speed` m/s comes to rest, metres: where a
/// constant deceleration brings it to rest as its closing foot lands
/// (`speed · t / 2`, with `t` from [`closing_time`]), so the stop takes the
/// step being taken and one more at the walk's cadence; but at least
/// `speed² / (2 stop_deceleration)` and `stop_min_distance`.
pub fn stop_distance(settings: &SteeringSettings, gait: &Gait, speed: f32) -> f32 {
    let shortest = (speed * speed / (2.0 * settings.stop_deceleration.max(1.0e-3)))
        .max(settings.stop_min_distance);
    (0.5 * speed * closing_time(gait)).max(shortest)
}

/// Seconds until the foot that closes a stop lands, at the walk's cadence:
/// the planted foot that lifts next (the one furthest into its stance)
/// swings to the stop, landing when its phase comes round.
pub fn closing_time(gait: &Gait) -> f32 {
    (0..2)
        .filter(|&k| gait.local_phase(k) < gait.params.duty)
        .map(|k| gait.time_to_landing(k))
        .fold(gait.params.cycle_time(), f32::min)
}

/// The curve radius at `speed`: `speed² / max_lateral_acceleration`, at
/// least `min_radius`.
pub fn curve_radius(settings: &SteeringSettings, speed: f32) -> f32 {
    (speed * speed / settings.max_lateral_acceleration.max(1.0e-3)).max(settings.min_radius)
}

/// Updates `path` from `steering` for a walker in state `gait`, and returns
/// the factor the walking speed must be scaled by this step of `dt` seconds
/// (multiply it into [`GaitModifiers::speed_scale`]); the factor follows the
/// wish at [`SteeringSettings::speed_change_rate`], or the [`Brake`] of a stop.
/// A stop also needs the braking and the cadence held in the gait's
/// modifiers, which [`brake_modifiers`] (the stage callers run) sets.
fn steer_stage(
    steering: &mut Steering,
    gait: &Gait,
    body: &CharacterBody,
    path: &mut WalkPath,
    dt: f32,
) -> f32 {
    let target = plan_path(steering, gait, body, path);
    let scale = &mut steering.speed_scale;
    let dt = clamp_dt(dt);
    if let Some(brake) = &steering.brake {
        let s = &steering.settings;
        *scale = if gait.stopped || path.is_finished(gait.distance) {
            *scale
        } else {
            let moved = gait.velocity.length() * dt;
            let left = path.end_distance() - gait.distance - moved;
            brake.scale_at(left, s.stop_speed_floor)
        };
        return *scale;
    }
    let most = steering.settings.speed_change_rate.max(0.0) * dt;
    *scale += (target - *scale).clamp(-most, most);
    *scale
}

/// The steering stage: runs `steer_stage` and returns `base` with its walking speed scaled by
/// the steering's factor, the deceleration braked at
/// ([`GaitModifiers::braking`]) and the cadence held
/// ([`GaitModifiers::cadence_hold`]) this step.
pub fn brake_modifiers(
    steering: &mut Steering,
    gait: &Gait,
    body: &CharacterBody,
    path: &mut WalkPath,
    base: GaitModifiers,
    dt: f32,
) -> GaitModifiers {
    let scale = steer_stage(steering, gait, body, path, dt);
    GaitModifiers {
        speed_scale: base.speed_scale * scale,
        braking: braking(steering, gait, path),
        cadence_hold: cadence_hold(steering, gait),
        ..base
    }
}

/// The deceleration `steering` brakes at this step, m/s² (0 when not
/// braking, or once at the stop).
fn braking(steering: &Steering, gait: &Gait, path: &WalkPath) -> f32 {
    match &steering.brake {
        Some(b) if !path.is_finished(gait.distance) => b.deceleration,
        _ => 0.0,
    }
}

/// The [`GaitModifiers::cadence_hold`] of `steering` this step: until the
/// stop is reached and both feet are planted, the walk keeps the cadence it
/// had when braking began (`from_scale` over the braked speed scale); 1
/// otherwise.
fn cadence_hold(steering: &Steering, gait: &Gait) -> f32 {
    match &steering.brake {
        Some(b) if !gait.stopped => b.from_scale / steering.speed_scale.max(1.0e-3),
        _ => 1.0,
    }
}

/// Updates `path` from `steering` and returns the speed scale it wishes for.
fn plan_path(
    steering: &mut Steering,
    gait: &Gait,
    body: &CharacterBody,
    path: &mut WalkPath,
) -> f32 {
    let s = steering.settings;
    let speed = steering.desired.length();
    if speed < s.stop_speed {
        stop(steering, gait, path);
        return steering.speed_scale;
    }
    let natural = GaitParams::new(body, &GaitModifiers::default()).speed;
    let direction = steering.desired / speed;
    let angle = turn_angle(gait.pelvis.heading, direction);
    let backward = angle.abs() > s.backward_start && speed <= s.backward_max_speed;
    if backward != path.is_backward() {
        if !(gait.stopped && gait.roll == 0.0) {
            stop(steering, gait, path);
            return steering.speed_scale;
        }
        steering.speed_scale = wished_scale(steering, speed, natural, backward);
    }
    steering.stopping = false;
    steering.brake = None;
    if backward {
        steering.pivoting = false;
        let straight = PathSegment::Straight {
            length: s.lookahead.max(1.0e-3),
        };
        replace_path(path, gait, Walked::Back(direction), vec![straight]);
        return wished_scale(steering, speed, natural, true);
    }
    if angle.abs() > s.pivot_start {
        steering.pivoting = true;
    } else if angle.abs() < s.pivot_end {
        steering.pivoting = false;
    }
    let straight = PathSegment::Straight {
        length: s.lookahead.max(1.0e-3),
    };
    let turn = if angle.abs() < 1.0e-4 {
        None
    } else if steering.pivoting {
        Some(PathSegment::Pivot {
            reach: s.pivot_reach.max(1.0e-3),
            angle,
        })
    } else {
        Some(PathSegment::Arc {
            radius: curve_radius(&s, speed),
            angle,
        })
    };
    let segments = turn.into_iter().chain([straight]).collect();
    replace_path(path, gait, Walked::Forward, segments);
    wished_scale(steering, speed, natural, false)
}

/// The speed scale a wish of `speed` m/s asks of a walk whose natural speed
/// is `natural`: slower backward (and no faster than its top speed), and
/// never below the pivot's minimum while turning on the spot.
fn wished_scale(steering: &Steering, speed: f32, natural: f32, backward: bool) -> f32 {
    let s = &steering.settings;
    let natural = natural.max(1.0e-3);
    let scale = speed / natural;
    if backward {
        (scale * s.backward_speed_factor).min(s.backward_top_speed / natural)
    } else if steering.pivoting {
        scale.max(s.pivot_min_speed_scale)
    } else {
        scale
    }
}

/// Starts a stop, once: braking to where the walker comes to rest.
fn stop(steering: &mut Steering, gait: &Gait, path: &mut WalkPath) {
    steering.pivoting = false;
    if steering.stopping {
        return;
    }
    steering.stopping = true;
    steering.brake = hold_stop(path, gait, &steering.settings, steering.speed_scale);
}

/// Replaces `path` by a stop [`stop_distance`] beyond the pelvis, braked
/// for from `scale`, or at the pelvis when the walker is already at rest
/// (no brake); the stop keeps the path's direction of travel.
fn hold_stop(
    path: &mut WalkPath,
    gait: &Gait,
    settings: &SteeringSettings,
    scale: f32,
) -> Option<Brake> {
    const AT_REST_M: f32 = 1.0e-3;
    let travel = gait.travel_heading();
    let walked = if path.is_backward() {
        Walked::Back(travel)
    } else {
        Walked::Forward
    };
    let speed = gait.velocity.length();
    if speed == 0.0 {
        let back = gait.pelvis.position - travel * AT_REST_M;
        let rest = vec![PathSegment::Straight { length: AT_REST_M }];
        if let Ok(p) = walk_path(back, gait.pelvis.heading, walked, rest) {
            *path = p.with_origin(gait.distance - AT_REST_M);
        }
        return None;
    }
    let distance = stop_distance(settings, gait, speed).max(AT_REST_M);
    let straight = PathSegment::Straight { length: distance };
    replace_path(path, gait, walked, vec![straight]);
    Some(Brake {
        from_scale: scale,
        distance,
        deceleration: speed * speed / (2.0 * distance),
    })
}

/// Which way a generated path is walked.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Walked {
    /// Forward, along the walker's facing.
    Forward,
    /// Backward, the walker keeping its facing, towards this travel (x, z).
    Back(Vec2),
}

/// Replaces `path` by `segments` from the pelvis, continuing the gait's
/// distance, `walked` with the walker's facing.
fn replace_path(path: &mut WalkPath, gait: &Gait, walked: Walked, segments: Vec<PathSegment>) {
    let (at, facing) = (gait.pelvis.position, gait.pelvis.heading);
    if let Ok(p) = walk_path(at, facing, walked, segments) {
        *path = p.with_origin(gait.distance);
    }
}

/// A path of `segments` from `at` (x, z) for a walker facing `facing`
/// (x, z), `walked` forward or back.
fn walk_path(
    at: Vec2,
    facing: Vec2,
    walked: Walked,
    segments: Vec<PathSegment>,
) -> Result<WalkPath, CharacterError> {
    let flat = |v: Vec2| Vec3::new(v.x, 0.0, v.y);
    let start = flat(at);
    match walked {
        Walked::Back(travel) => WalkPath::stepped_back(start, flat(facing), flat(travel), segments),
        Walked::Forward => WalkPath::new(start, flat(facing), segments, false),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::character::{CharacterDesc, MAX_BACKWARD_ASLANT};
    use crate::foot::FootPhase;

    const DT: f32 = 1.0 / 60.0;

    fn standing() -> (CharacterBody, Gait, WalkPath) {
        let body = CharacterBody::new(CharacterDesc::adult()).unwrap();
        let path = WalkPath::straight(Vec3::ZERO, Vec3::Z, 1.0).unwrap();
        let gait = Gait::new(&body, &path, &GaitModifiers::default());
        (body, gait, path)
    }

    #[test]
    fn turn_angle_is_positive_to_the_left() {
        // Facing +Z with Y up, the character's left is +X.
        assert!((turn_angle(Vec2::Y, Vec2::X) - std::f32::consts::FRAC_PI_2).abs() < 1e-6);
        assert!(turn_angle(Vec2::Y, Vec2::NEG_X) < 0.0);
        assert!(turn_angle(Vec2::Y, Vec2::Y).abs() < 1e-6);
    }

    #[test]
    fn curves_tighten_to_the_minimum_radius_at_low_speed() {
        let s = SteeringSettings::default();
        assert_eq!(curve_radius(&s, 0.3), s.min_radius);
        assert!((curve_radius(&s, 2.5) - 2.5).abs() < 1e-5);
    }

    /// The wish `degrees` left of facing +z (x, z), at `speed` m/s.
    fn wish(degrees: f32, speed: f32) -> Vec2 {
        let (sin, cos) = degrees.to_radians().sin_cos();
        Vec2::new(sin, cos) * speed
    }

    /// `gait` stopped with its feet rolled flat.
    fn at_rest(gait: &mut Gait) {
        gait.stopped = true;
        gait.roll = 0.0;
    }

    #[test]
    fn a_sideways_wish_curves_and_a_wish_further_round_pivots() {
        let (body, gait, mut path) = standing();
        let mut steering = Steering::new();
        steering.set_desired_velocity(Vec2::new(1.2, 0.0)).unwrap();
        let scale = steer_stage(&mut steering, &gait, &body, &mut path, DT);
        assert!(!steering.is_pivoting());
        assert!((scale - 1.0).abs() <= DT + 1e-6, "eases from 1: {scale}");
        let far = path.point_at(path.end_distance());
        assert!((far.heading - Vec2::X).length() < 1e-4);
        assert!(far.position.x > 4.0, "{far:?}");

        // Past `pivot_start` but short of `backward_start`: turns on the spot.
        steering.set_desired_velocity(wish(110.0, 1.2)).unwrap();
        steer_stage(&mut steering, &gait, &body, &mut path, DT);
        assert!(steering.is_pivoting());
        let mid = path.point_at(path.origin() + 0.5);
        assert_eq!(mid.position, gait.pelvis.position);
        // Behind, but faster than `backward_max_speed`: turns round too.
        steering.set_desired_velocity(wish(180.0, 2.4)).unwrap();
        steer_stage(&mut steering, &gait, &body, &mut path, DT);
        assert!(steering.is_pivoting() && !path.is_backward());
    }

    #[test]
    fn a_backward_wish_stops_then_steps_back_facing_forward() {
        let (body, mut gait, mut path) = standing();
        let mut steering = Steering::new();
        steering.set_desired_velocity(Vec2::new(0.0, -1.2)).unwrap();
        steer_stage(&mut steering, &gait, &body, &mut path, DT);
        assert!(!path.is_backward(), "not yet stopped: holds a stop first");
        assert!(!steering.is_pivoting());
        at_rest(&mut gait);
        let scale = steer_stage(&mut steering, &gait, &body, &mut path, DT);
        assert!(path.is_backward());
        let natural = GaitParams::new(&body, &GaitModifiers::default()).speed;
        let wished = 0.5 * 1.2 / natural;
        assert!(
            (scale - wished).abs() < 1e-5,
            "starts at the backward speed: {scale}"
        );
        let back = path.point_at(path.origin() + 1.0);
        assert!((back.position - Vec2::new(0.0, -1.0)).length() < 1e-5);
        assert_eq!(back.heading, Vec2::Y, "keeps facing forward");

        steering.set_desired_velocity(Vec2::ZERO).unwrap();
        gait.stopped = false;
        gait.pelvis = path.point_at(gait.distance);
        gait.velocity = Vec2::new(0.0, -0.6);
        steer_stage(&mut steering, &gait, &body, &mut path, DT);
        assert!(path.is_backward(), "a stop keeps stepping back");
        let stop = path.point_at(path.end_distance()).position;
        let braking = stop_distance(&steering.settings, &gait, 0.6);
        assert!((stop - Vec2::new(0.0, -braking)).length() < 1e-5, "{stop}");
        steering = Steering::new();
        gait.velocity = Vec2::ZERO;
        steer_stage(&mut steering, &gait, &body, &mut path, DT);
        assert!(path.is_backward() && path.is_finished(gait.distance));
    }

    #[test]
    fn back_with_a_side_key_steps_back_aslant_facing_forward() {
        let (body, mut gait, mut path) = standing();
        at_rest(&mut gait);
        let mut steering = Steering::new();
        // S with A, camera behind: back and to the walker's left (+x), as
        // far aslant as a step back goes.
        steering.set_desired_velocity(wish(135.0, 1.2)).unwrap();
        steer_stage(&mut steering, &gait, &body, &mut path, DT);
        assert!(path.is_backward() && !steering.is_pivoting());
        let aslant = 180.0 - MAX_BACKWARD_ASLANT.to_degrees();
        let back = path.point_at(path.origin() + 1.0);
        let expected = wish(aslant, 1.0);
        assert!((back.position - expected).length() < 1e-5, "{back:?}");
        assert!((back.heading - Vec2::Y).length() < 1e-6, "keeps facing +z");
        assert!((back.travel - expected).length() < 1e-5);
        // To the right, and within the bound: as wished.
        steering.set_desired_velocity(wish(-150.0, 1.2)).unwrap();
        steer_stage(&mut steering, &gait, &body, &mut path, DT);
        let back = path.point_at(path.origin() + 1.0);
        assert!(
            (back.position - wish(-150.0, 1.0)).length() < 1e-5,
            "{back:?}"
        );
        assert!((back.heading - Vec2::Y).length() < 1e-6);
    }

    #[test]
    fn a_hurried_step_back_is_faster_but_bounded() {
        let (body, mut gait, path) = standing();
        at_rest(&mut gait);
        let natural = GaitParams::new(&body, &GaitModifiers::default()).speed;
        let mut scales = Vec::new();
        for speed in [1.2, 1.8, 1.95] {
            let mut path = path.clone();
            let mut steering = Steering::new();
            steering.set_desired_velocity(wish(180.0, speed)).unwrap();
            scales.push(steer_stage(&mut steering, &gait, &body, &mut path, DT));
            assert!(path.is_backward() && !steering.is_pivoting());
        }
        let top = SteeringSettings::default().backward_top_speed / natural;
        assert!(scales[1] > scales[0], "Shift steps back faster: {scales:?}");
        assert!((scales[1] - top).abs() < 1e-6 && (scales[2] - top).abs() < 1e-6);
        let backward = GaitParams::new(
            &body,
            &GaitModifiers {
                speed_scale: top,
                step_length_scale: crate::character::gait::BACKWARD_STEP_SCALE,
                ..GaitModifiers::default()
            },
        );
        let forward = GaitParams::new(&body, &GaitModifiers::default());
        assert!(
            backward.stride < 0.85 * forward.stride,
            "short steps: {} m against {} m",
            backward.stride,
            forward.stride
        );
    }

    /// A walker at full speed along +z at cycle phase `phase`, its
    /// footholds planned by the gait.
    fn walking_at(phase: f32) -> (CharacterBody, Gait, WalkPath) {
        let body = CharacterBody::new(CharacterDesc::adult()).unwrap();
        let path = WalkPath::straight(Vec3::ZERO, Vec3::Z, 20.0).unwrap();
        let mods = GaitModifiers::default();
        let mut gait = Gait::new(&body, &path, &mods);
        while gait.distance < 3.0 || (gait.phase - phase).abs() > 0.01 {
            crate::character::gait_stage(&mut gait, &body, &path, &mods, DT);
        }
        (body, gait, path)
    }

    #[test]
    fn a_stop_brakes_from_the_first_step_and_closes_in_one_step_at_the_cadence() {
        let s = SteeringSettings::default();
        for phase in [0.05, 0.2, 0.4, 0.7] {
            let (body, mut gait, mut path) = walking_at(phase);
            let speed = gait.velocity.length();
            let shortest = speed * speed / (2.0 * s.stop_deceleration);
            let closing = closing_time(&gait);
            let distance = stop_distance(&s, &gait, speed);
            assert!(
                (distance - (0.5 * speed * closing).max(shortest)).abs() < 1e-6,
                "phase {phase}: {distance} m"
            );
            let mut steering = Steering::new();
            steering.set_desired_velocity(Vec2::ZERO).unwrap();
            let mut speeds = vec![speed];
            let (mut landings, mut stopped_after) = (0, None);
            let mods = GaitModifiers::default();
            for step in 1..=240 {
                let m = brake_modifiers(&mut steering, &gait, &body, &mut path, mods, DT);
                let swinging = gait.feet.map(|f| f.phase != FootPhase::Stance);
                crate::character::gait_stage(&mut gait, &body, &path, &m, DT);
                landings += (0..2)
                    .filter(|&k| swinging[k] && gait.feet[k].phase == FootPhase::Stance)
                    .count();
                speeds.push(gait.velocity.length());
                if gait.stopped && stopped_after.is_none() {
                    stopped_after = Some(step as f32 * DT);
                }
            }
            assert!(speeds[1] < speeds[0], "phase {phase}: slows at once");
            assert!(gait.stopped && gait.double_support(), "phase {phase}");
            let rested = (gait.pelvis.position.y - path.point_at(path.origin()).position.y).abs();
            assert!(
                (rested - distance).abs() < 1e-4,
                "phase {phase}: {rested} m"
            );
            let seconds = stopped_after.unwrap();
            assert!(
                (seconds - closing).abs() <= 2.5 * DT && landings <= 2,
                "phase {phase}: at rest after {seconds} s and {landings} landings, \
                 closing in {closing} s"
            );
            let floor = s.stop_speed_floor * speed;
            let slowing = speeds.windows(2).all(|w| w[1] <= w[0] + 1e-4);
            let last_moving = speeds.iter().rev().find(|&&v| v > 0.0).unwrap();
            assert!(slowing, "phase {phase}: {speeds:?}");
            assert!(
                *last_moving <= floor + 1e-3,
                "phase {phase}: {last_moving} m/s"
            );
        }
    }

    #[test]
    fn zero_velocity_places_one_stop_and_bad_input_is_refused() {
        let (body, mut gait, mut path) = standing();
        let mut steering = Steering::new();
        steer_stage(&mut steering, &gait, &body, &mut path, DT);
        assert!(
            path.is_finished(gait.distance),
            "at rest: stop where it stands"
        );
        assert!(steering.brake().is_none());
        steering.set_desired_velocity(Vec2::Y).unwrap();
        steer_stage(&mut steering, &gait, &body, &mut path, DT);
        steering.set_desired_velocity(Vec2::ZERO).unwrap();
        gait.velocity = Vec2::Y;
        steer_stage(&mut steering, &gait, &body, &mut path, DT);
        let stop = path.clone();
        let brake = *steering.brake().unwrap();
        assert!((stop.end_distance() - gait.distance - brake.distance).abs() < 1e-6);
        assert!((brake.deceleration - 1.0 / (2.0 * brake.distance)).abs() < 1e-5);
        steer_stage(&mut steering, &gait, &body, &mut path, DT);
        assert_eq!(path, stop, "a held stop is not moved");
        let e = steering.set_desired_velocity(Vec2::NAN).unwrap_err();
        assert!(matches!(
            e,
            CharacterError::InvalidField {
                field: "desired_velocity",
                ..
            }
        ));
    }
}
