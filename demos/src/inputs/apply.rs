//! Applying input events to a running simulation.

use engine::ecs::{Entity, World};
use glam::Vec2;
use softwalk_systems::character::{Gait, Steering};
use softwalk_systems::sim::GroundState;

use super::script::{InputAction, InputError};

/// How far ahead of the pelvis the material brush is centred, metres.
pub const BRUSH_AHEAD_M: f32 = 1.5;
/// Radius of the material brush, metres.
pub const BRUSH_RADIUS_M: f32 = 1.5;

/// What the inputs so far ask: a direction of travel and a speed factor.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InputState {
    /// Desired planar velocity (x, z), m/s, before the speed factor.
    pub velocity: Vec2,
    /// Factor on the velocity.
    pub speed: f32,
}

impl Default for InputState {
    fn default() -> Self {
        InputState {
            velocity: Vec2::ZERO,
            speed: 1.0,
        }
    }
}

impl InputState {
    /// The velocity asked of the character, m/s.
    pub fn desired_velocity(&self) -> Vec2 {
        self.velocity * self.speed
    }

    /// Applies `action` (anything but a reset, which rebuilds the world and
    /// is the caller's) to `walker`, a character given a [`Steering`] by
    /// [`steer_character`].
    pub fn apply(
        &mut self,
        action: &InputAction,
        world: &mut World,
        walker: Entity,
    ) -> Result<(), InputError> {
        match action {
            InputAction::Velocity([x, z]) => self.velocity = Vec2::new(*x, *z),
            InputAction::Speed(s) => self.speed = *s,
            InputAction::Brush(name) => return paint_ahead(world, walker, name),
            InputAction::Reset => return Ok(()),
        }
        let desired = self.desired_velocity();
        if let Ok(mut steering) = world.get_mut::<Steering>(walker) {
            steering
                .set_desired_velocity(desired)
                .map_err(|e| InputError::Apply {
                    what: "velocity".into(),
                    reason: e.to_string(),
                })?;
        }
        Ok(())
    }
}

/// Makes `walker` a steered character (its path from now on comes from its
/// [`Steering`], standing still until asked to move).
pub fn steer_character(world: &mut World, walker: Entity) -> Result<(), InputError> {
    world
        .insert(walker, (Steering::new(),))
        .map_err(|e| InputError::Apply {
            what: "character".into(),
            reason: e.to_string(),
        })
}

/// Paints material `name` on a disc ahead of `walker`.
fn paint_ahead(world: &mut World, walker: Entity, name: &str) -> Result<(), InputError> {
    let ahead = world
        .get::<Gait>(walker)
        .map(|g| g.pelvis.position + g.travel_heading() * BRUSH_AHEAD_M)
        .map_err(|e| InputError::Apply {
            what: "brush".into(),
            reason: e.to_string(),
        })?;
    let mut ground = world
        .get_resource_mut::<GroundState>()
        .ok_or_else(|| InputError::Apply {
            what: "brush".into(),
            reason: "the scene has no terrain".into(),
        })?;
    let brush = |e: softwalk_systems::terrain::TerrainError| InputError::Apply {
        what: format!("brush {name:?}"),
        reason: e.to_string(),
    };
    let id = ground.terrain().table().id(name).map_err(brush)?;
    ground.paint_disc(ahead, BRUSH_RADIUS_M, id).map_err(brush)
}
