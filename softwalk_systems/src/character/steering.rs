//! Steering: a character whose path is generated from input.
//!
//! A [`Steering`] holds a desired planar velocity. Each step [`steer_stage`]
//! turns it into the [`WalkPath`] the gait follows, starting at the pelvis
//! and continuing the distance already walked:
//! - a desired direction within [`SteeringSettings::pivot_start`] of the
//!   heading gives an arc towards it (radius from the speed, never below
//!   `min_radius`) and then a straight run;
//! - a direction further round turns on the spot first (a
//!   [`PathSegment::Pivot`]) until the heading is within `pivot_end`;
//! - a slow wish (up to `backward_max_speed`) further than `backward_start`
//!   from the heading steps backward: the walker keeps facing forward and
//!   walks a path [walked backward](WalkPath::walked_backward), slower
//!   (`backward_speed_factor`) and in the gait's short backward steps;
//! - a speed below `stop_speed` fixes a stop a short way ahead; the gait
//!   halts there with both feet planted, and starts again on the next
//!   desired velocity.
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
use super::path::{PathSegment, WalkPath};

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
    /// How far beyond the pelvis a stop is placed, metres.
    pub stop_ahead: f32,
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
            stop_ahead: 0.2,
            stop_speed: 0.05,
            speed_change_rate: 1.0,
            backward_start: 135f32.to_radians(),
            backward_max_speed: 1.3,
            backward_speed_factor: 0.5,
        }
    }
}

/// A character steered by a desired velocity (component).
#[derive(Debug, Clone, PartialEq)]
pub struct Steering {
    desired: Vec2,
    pivoting: bool,
    stopping: bool,
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
}

/// The signed angle from `heading` to `direction`, radians, positive to the left.
pub fn turn_angle(heading: Vec2, direction: Vec2) -> f32 {
    let left = Vec2::new(heading.y, -heading.x);
    direction.dot(left).atan2(direction.dot(heading))
}

/// The curve radius at `speed`: `speed² / max_lateral_acceleration`, at
/// least `min_radius`.
pub fn curve_radius(settings: &SteeringSettings, speed: f32) -> f32 {
    (speed * speed / settings.max_lateral_acceleration.max(1.0e-3)).max(settings.min_radius)
}

/// Updates `path` from `steering` for a walker in state `gait`, and returns
/// the factor the walking speed must be scaled by this step of `dt` seconds
/// (multiply it into [`GaitModifiers::speed_scale`]); the factor follows the
/// wish at [`SteeringSettings::speed_change_rate`].
pub fn steer_stage(
    steering: &mut Steering,
    gait: &Gait,
    body: &CharacterBody,
    path: &mut WalkPath,
    dt: f32,
) -> f32 {
    let target = plan_path(steering, gait, body, path);
    let most = steering.settings.speed_change_rate.max(0.0) * clamp_dt(dt);
    let scale = &mut steering.speed_scale;
    *scale += (target - *scale).clamp(-most, most);
    *scale
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
        steering.pivoting = false;
        if !steering.stopping {
            steering.stopping = true;
            hold_stop(path, gait, s.stop_ahead);
        }
        return steering.speed_scale;
    }
    let natural = GaitParams::new(body, &GaitModifiers::default()).speed;
    let direction = steering.desired / speed;
    let angle = turn_angle(gait.pelvis.heading, direction);
    let backward = angle.abs() > s.backward_start && speed <= s.backward_max_speed;
    if backward != path.is_backward() {
        if !(gait.stopped && gait.roll == 0.0) {
            steering.pivoting = false;
            if !steering.stopping {
                steering.stopping = true;
                hold_stop(path, gait, s.stop_ahead);
            }
            return steering.speed_scale;
        }
        steering.speed_scale = wished_scale(steering, speed, natural, backward);
    }
    steering.stopping = false;
    if backward {
        steering.pivoting = false;
        let straight = PathSegment::Straight {
            length: s.lookahead.max(1.0e-3),
        };
        replace_path(path, gait, &[straight], true);
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
    let segments: Vec<PathSegment> = turn.into_iter().chain([straight]).collect();
    replace_path(path, gait, &segments, false);
    wished_scale(steering, speed, natural, false)
}

/// The speed scale a wish of `speed` m/s asks of a walk whose natural speed
/// is `natural`: slower backward, and never below the pivot's minimum while
/// turning on the spot.
fn wished_scale(steering: &Steering, speed: f32, natural: f32, backward: bool) -> f32 {
    let s = &steering.settings;
    let scale = speed / natural.max(1.0e-3);
    if backward {
        scale * s.backward_speed_factor
    } else if steering.pivoting {
        scale.max(s.pivot_min_speed_scale)
    } else {
        scale
    }
}

/// Replaces `path` by a stop `ahead` metres beyond the pelvis, or at the
/// pelvis when the walker is already at rest; the stop keeps the path's
/// direction of travel.
fn hold_stop(path: &mut WalkPath, gait: &Gait, ahead: f32) {
    const AT_REST_M: f32 = 1.0e-3;
    let backward = path.is_backward();
    if gait.velocity == Vec2::ZERO {
        let travel = if backward {
            -gait.pelvis.heading
        } else {
            gait.pelvis.heading
        };
        let back = gait.pelvis.position - travel * AT_REST_M;
        let rest = [PathSegment::Straight { length: AT_REST_M }];
        if let Ok(p) = walk_path(back, gait.pelvis.heading, &rest, backward) {
            *path = p.with_origin(gait.distance - AT_REST_M);
        }
        return;
    }
    let stop = [PathSegment::Straight {
        length: ahead.max(AT_REST_M),
    }];
    replace_path(path, gait, &stop, backward);
}

/// Replaces `path` by `segments` from the pelvis, continuing the gait's
/// distance, walked forward or `backward` with the walker's facing.
fn replace_path(path: &mut WalkPath, gait: &Gait, segments: &[PathSegment], backward: bool) {
    let (at, facing) = (gait.pelvis.position, gait.pelvis.heading);
    if let Ok(p) = walk_path(at, facing, segments, backward) {
        *path = p.with_origin(gait.distance);
    }
}

/// A path of `segments` from `at` (x, z) for a walker facing `facing`
/// (x, z), walked forward or `backward`.
fn walk_path(
    at: Vec2,
    facing: Vec2,
    segments: &[PathSegment],
    backward: bool,
) -> Result<WalkPath, CharacterError> {
    let start = Vec3::new(at.x, 0.0, at.y);
    let facing = Vec3::new(facing.x, 0.0, facing.y);
    if backward {
        WalkPath::walked_backward(start, facing, segments.to_vec())
    } else {
        WalkPath::new(start, facing, segments.to_vec(), false)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::character::CharacterDesc;

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

    #[test]
    fn a_sideways_wish_curves_and_a_fast_backward_one_pivots() {
        let (body, gait, mut path) = standing();
        let mut steering = Steering::new();
        steering.set_desired_velocity(Vec2::new(1.2, 0.0)).unwrap();
        let scale = steer_stage(&mut steering, &gait, &body, &mut path, DT);
        assert!(!steering.is_pivoting());
        assert!((scale - 1.0).abs() <= DT + 1e-6, "eases from 1: {scale}");
        let far = path.point_at(path.end_distance());
        assert!((far.heading - Vec2::X).length() < 1e-4);
        assert!(far.position.x > 4.0, "{far:?}");

        steering.set_desired_velocity(Vec2::new(0.0, -1.8)).unwrap();
        steer_stage(&mut steering, &gait, &body, &mut path, DT);
        assert!(steering.is_pivoting());
        let mid = path.point_at(path.origin() + 0.5);
        assert_eq!(mid.position, gait.pelvis.position);
    }

    #[test]
    fn a_slow_backward_wish_stops_then_steps_back_facing_forward() {
        let (body, mut gait, mut path) = standing();
        let mut steering = Steering::new();
        steering.set_desired_velocity(Vec2::new(0.2, -1.2)).unwrap();
        steer_stage(&mut steering, &gait, &body, &mut path, DT);
        assert!(!path.is_backward(), "not yet stopped: holds a stop first");
        assert!(!steering.is_pivoting());
        gait.stopped = true;
        gait.roll = 0.0;
        let scale = steer_stage(&mut steering, &gait, &body, &mut path, DT);
        assert!(path.is_backward());
        let natural = GaitParams::new(&body, &GaitModifiers::default()).speed;
        let wished = 0.5 * Vec2::new(0.2, -1.2).length() / natural;
        assert!(
            (scale - wished).abs() < 1e-5,
            "starts at the backward speed: {scale}"
        );
        let back = path.point_at(path.origin() + 1.0);
        assert!((back.position - Vec2::new(0.0, -1.0)).length() < 1e-5);
        assert_eq!(back.heading, Vec2::Y, "keeps facing forward");

        steering.set_desired_velocity(Vec2::ZERO).unwrap();
        gait.velocity = Vec2::new(0.0, -0.6);
        steer_stage(&mut steering, &gait, &body, &mut path, DT);
        assert!(path.is_backward(), "a stop keeps stepping back");
        let stop = path.point_at(path.end_distance()).position;
        assert!((stop - Vec2::new(0.0, -0.2)).length() < 1e-5, "{stop}");
        steering = Steering::new();
        gait.velocity = Vec2::ZERO;
        steer_stage(&mut steering, &gait, &body, &mut path, DT);
        assert!(path.is_backward() && path.is_finished(gait.distance));
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
        steering.set_desired_velocity(Vec2::Y).unwrap();
        steer_stage(&mut steering, &gait, &body, &mut path, DT);
        steering.set_desired_velocity(Vec2::ZERO).unwrap();
        gait.velocity = Vec2::Y;
        steer_stage(&mut steering, &gait, &body, &mut path, DT);
        let stop = path.clone();
        assert!((stop.end_distance() - gait.distance - 0.2).abs() < 1e-6);
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
