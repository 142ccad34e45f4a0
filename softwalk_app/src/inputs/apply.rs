//! Applying input events to a running simulation.

use engine::ecs::{Entity, World};
use glam::Vec2;
use softwalk_systems::character::{Gait, Steering};
use softwalk_systems::sim::GroundState;
use softwalk_systems::vegetation::{GrassPatch, GrassSettings, XzRect};

use super::script::{InputAction, InputError};

/// How far ahead of the pelvis the material brush is centred, metres.
pub const BRUSH_AHEAD_M: f32 = 1.5;
/// Radius of the material brush, metres.
pub const BRUSH_RADIUS_M: f32 = 1.5;
/// The brush that plants grass (small, 0.5 m) instead of painting a material.
pub const GRASS_BRUSH: &str = "grass";
/// Half the side of the square of grass the grass brush plants, metres: from
/// half a metre ahead of the pelvis, so no blade grows under a planted foot.
pub const GRASS_HALF_SIDE_M: f32 = 1.0;

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
            InputAction::Brush(name) if name == GRASS_BRUSH => {
                return plant_grass_ahead(world, walker);
            }
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

/// The point [`BRUSH_AHEAD_M`] ahead of `walker`'s pelvis along its travel.
fn brush_centre(world: &World, walker: Entity) -> Result<Vec2, InputError> {
    world
        .get::<Gait>(walker)
        .map(|g| g.pelvis.position + g.travel_heading() * BRUSH_AHEAD_M)
        .map_err(|e| InputError::Apply {
            what: "brush".into(),
            reason: e.to_string(),
        })
}

/// Paints material `name` on a disc ahead of `walker`.
fn paint_ahead(world: &mut World, walker: Entity, name: &str) -> Result<(), InputError> {
    let ahead = brush_centre(world, walker)?;
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

/// Plants a square of small grass ahead of `walker`, rooted on the terrain
/// (the part of the square over the terrain; nothing when none is).
fn plant_grass_ahead(world: &mut World, walker: Entity) -> Result<(), InputError> {
    let ahead = brush_centre(world, walker)?;
    let failed = |reason: String| InputError::Apply {
        what: format!("brush {GRASS_BRUSH:?}"),
        reason,
    };
    let patch = {
        let ground = world
            .get_resource::<GroundState>()
            .ok_or_else(|| failed("the scene has no terrain".into()))?;
        let grid = ground.terrain().grid();
        let (lo, hi) = (grid.origin(), grid.origin() + grid.extent());
        let half = Vec2::splat(GRASS_HALF_SIDE_M);
        let (a, b) = ((ahead - half).max(lo), (ahead + half).min(hi));
        if a.cmpge(b).any() {
            return Ok(());
        }
        GrassPatch::with_height_fn(XzRect::new(a, b), GrassSettings::small(), |x, z| {
            grid.height_at(x, z)
        })
        .map_err(|e| failed(e.to_string()))?
    };
    world.spawn((patch,));
    Ok(())
}
