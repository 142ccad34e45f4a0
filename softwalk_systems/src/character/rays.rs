//! Stage 2, the foot rays: vertical rays onto the ground give each foot its
//! IK key (through its [`FootSupport`]) and the body its reference ground.

use glam::{Vec2, Vec3};

use super::body::CharacterBody;
use super::gait::Gait;
use super::ground_cross::GroundCross;
use super::support::{FootSupport, SupportPoint, sole_direction};
use crate::ground::Ground;

/// Height above everything a character could stand on, used for the very first rays.
const FIRST_RAY_HEIGHT: f32 = 1.0e4;
/// Distance from the pelvis of the four outer samples of the body's ground, metres.
const BODY_SAMPLE_REACH: f32 = 0.3;

/// What a foot stands on this step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GroundKey {
    /// The ground point under the part of the sole that touches (or will
    /// touch) the ground (see `FootPlan::contact_along`).
    pub point: Vec3,
    /// Unit ground normal.
    pub normal: Vec3,
    /// False when the ray found nothing this step (no ground there).
    pub hit: bool,
    /// True while the foot presses the ground: planted, pushing into its
    /// landing at the end of the swing, or rising out of its print.
    pub pressing: bool,
    /// The lowest the sole's lowest point may be pushed, metres: the floor
    /// under a swinging sole (the surface less what the ground gives), or
    /// the floor a planted foot stands on (see `SupportKey::floor`).
    pub floor: f32,
    /// The highest surface under a swinging sole (see
    /// `SupportKey::surface`), or the floor a planted foot stands on.
    pub surface: f32,
    /// Top of a virtual platform under the foot (set by the vegetation's
    /// platform system): the sole centre stays on or above it.
    pub platform: Option<f32>,
}

/// The ground keys of one character: one per foot (left first) and one under the pelvis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FootRays {
    /// The IK keys.
    pub feet: [GroundKey; 2],
    /// Where each foot stands or will land (left first).
    pub support: [FootSupport; 2],
    /// The body's ground: the floor a planted foot would sink to, the median
    /// over a cross of samples around the pelvis (so prints and rims under
    /// the pelvis do not jolt it), and the slope of the surface there.
    pub body: GroundKey,
}

impl FootRays {
    /// First keys for a gait, cast from high above, both feet standing in
    /// their own prints: on the floor of their footholds (the surface less
    /// what the ground gives under a planted foot), where the pelvis's floor
    /// is measured too, so a walker on deep loose ground starts upright, not
    /// crouched. A miss reads as height 0, normal up. The sim presses those
    /// prints before the first step (see `SimBuilder::build`).
    pub fn new(gait: &Gait, body: &CharacterBody, ground: &dyn Ground) -> Self {
        let blank = GroundKey {
            point: Vec3::ZERO,
            normal: Vec3::Y,
            hit: false,
            pressing: false,
            floor: 0.0,
            surface: 0.0,
            platform: None,
        };
        let mut rays = FootRays {
            feet: [blank; 2],
            support: [FootSupport::planted_on(SupportPoint::rigid(Vec3::ZERO)); 2],
            body: blank,
        };
        rays.body = body_ground(gait, ground, FIRST_RAY_HEIGHT, blank);
        for (support, plan) in rays.support.iter_mut().zip(&gait.feet) {
            let at = plan.from;
            let found = ground.cast_down(at.x, at.y, FIRST_RAY_HEIGHT);
            let point = found.map_or(
                SupportPoint::rigid(Vec3::new(at.x, rays.body.point.y, at.y)),
                SupportPoint::from_hit,
            );
            *support = FootSupport::planted_on(point);
        }
        rays.advance(gait, body, ground);
        rays
    }

    fn advance(&mut self, gait: &Gait, body: &CharacterBody, ground: &dyn Ground) {
        let from_y = self.body.point.y + body.desc.height + body.hip_height;
        self.body = body_ground(gait, ground, from_y, self.body);
        for k in 0..2 {
            let plan = &gait.feet[k];
            let key = self.support[k].advance(plan, &gait.params, body, ground, from_y);
            let along = sole_direction(plan.heading, key.normal);
            self.feet[k] = GroundKey {
                point: key.centre + along * plan.contact_along,
                normal: key.normal,
                hit: self.support[k].hit,
                pressing: key.pressing,
                floor: key.floor,
                surface: key.surface,
                platform: None,
            };
        }
    }
}

/// The body's ground: the median floor (surface minus give) of the pelvis
/// and four points around it ([`GroundCross::typical_floor`]), with the
/// normal of the patch's plane ([`GroundCross::normal`]: neither the edge
/// between two grounds of different give nor a print's wall is read as a
/// slope).
/// When every ray misses, `last` moves along.
fn body_ground(gait: &Gait, ground: &dyn Ground, from_y: f32, last: GroundKey) -> GroundKey {
    let at = gait.pelvis.position;
    let cast = |p: Vec2| ground.cast_down(p.x, p.y, from_y);
    let reach = BODY_SAMPLE_REACH;
    match GroundCross::sample(cast, at, gait.pelvis.heading, [reach, reach], &[]) {
        Some(cross) => GroundKey {
            point: Vec3::new(at.x, cross.typical_floor, at.y),
            normal: cross.normal,
            hit: true,
            pressing: false,
            floor: cross.typical_floor,
            surface: cross.typical_floor,
            platform: None,
        },
        None => GroundKey {
            point: Vec3::new(at.x, last.point.y, at.y),
            hit: false,
            ..last
        },
    }
}

/// Stage 2: advances each foot's support and casts the body's rays.
///
/// Rays start a body height above the body's ground; where nothing is found
/// a key keeps its last height and normal and reports `hit = false`; nothing
/// becomes NaN.
pub fn foot_raycast_stage(
    rays: &mut FootRays,
    gait: &Gait,
    body: &CharacterBody,
    ground: &dyn Ground,
) {
    rays.advance(gait, body, ground);
}
