//! Stage 2, the foot rays: a vertical ray from above each foot (and one under
//! the pelvis) onto the ground. The hit under a foot is that leg's IK key.

use glam::{Vec2, Vec3};

use super::body::CharacterBody;
use super::foot_ik::sole_direction;
use super::gait::Gait;
use crate::ground::{Ground, GroundHit};

/// Height above everything a character could stand on, used for the very first rays.
const FIRST_RAY_HEIGHT: f32 = 1.0e4;

/// What a vertical ray found.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GroundKey {
    /// The ground point (when the ray missed: the last height found, at the new x, z).
    pub point: Vec3,
    /// Unit ground normal (when the ray missed: the last normal found).
    pub normal: Vec3,
    /// False when the ray found nothing this step (off the terrain).
    pub hit: bool,
}

impl GroundKey {
    fn update(&mut self, at: Vec2, found: Option<GroundHit>) {
        match found {
            Some(h) => {
                *self = GroundKey {
                    point: h.point,
                    normal: h.normal,
                    hit: true,
                }
            }
            None => {
                self.point = Vec3::new(at.x, self.point.y, at.y);
                self.hit = false;
            }
        }
    }
}

/// The ground keys of one character: one per foot (left first) and one under the pelvis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FootRays {
    /// Under the point where each sole touches the ground (see
    /// [`super::FootPlan::contact`]): the IK keys.
    pub feet: [GroundKey; 2],
    /// Under the pelvis: the reference height and slope of the body.
    pub body: GroundKey,
}

impl FootRays {
    /// First keys for a gait, cast from high above (a miss reads as height 0, normal up).
    pub fn new(gait: &Gait, ground: &dyn Ground) -> Self {
        let blank = GroundKey {
            point: Vec3::ZERO,
            normal: Vec3::Y,
            hit: false,
        };
        let mut rays = FootRays {
            feet: [blank; 2],
            body: blank,
        };
        rays.cast(gait, ground, |_| FIRST_RAY_HEIGHT);
        rays
    }

    fn cast(&mut self, gait: &Gait, ground: &dyn Ground, from_y: impl Fn(&GroundKey) -> f32) {
        for (key, plan) in self.feet.iter_mut().zip(&gait.feet) {
            // The sole lies along the ground: its contact point is
            // `contact_along` metres along the slope from the sole centre
            // (using last step's normal), which is less than that horizontally.
            let along = sole_direction(plan.heading, key.normal);
            let at = plan.target + Vec2::new(along.x, along.z) * plan.contact_along;
            key.update(at, ground.cast_down(at.x, at.y, from_y(key)));
        }
        let at = gait.pelvis.position;
        let found = ground.cast_down(at.x, at.y, from_y(&self.body));
        self.body.update(at, found);
    }
}

/// Stage 2: casts each foot's ray from a hip height above its last key.
///
/// Off the terrain (no hit) a key keeps its last height and normal and
/// reports `hit = false`; nothing becomes NaN.
pub fn foot_raycast_stage(
    rays: &mut FootRays,
    gait: &Gait,
    body: &CharacterBody,
    ground: &dyn Ground,
) {
    let above = body.hip_height;
    rays.cast(gait, ground, |key| key.point.y + above);
}
