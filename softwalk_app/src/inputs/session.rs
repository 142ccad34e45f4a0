//! An input script driving a running scene: which character it steers and
//! what it has asked so far.

use engine::ecs::Entity;
use engine::schedule::App;
use softwalk_systems::sim::GroundState;

use super::apply::{GRASS_BRUSH, InputState, steer_character};
use super::script::{InputAction, InputError, InputScript};
use crate::scene::{Scene, SceneError};

/// Why a step's inputs could not be applied.
#[derive(Debug, thiserror::Error)]
pub enum SessionError {
    /// An event could not be applied.
    #[error(transparent)]
    Input(#[from] InputError),
    /// A reset could not rebuild the scene.
    #[error("reset: cannot rebuild the scene")]
    Reset(#[source] SceneError),
}

/// A script steering one character of a scene.
#[derive(Debug)]
pub struct InputSession<'a> {
    script: &'a InputScript,
    walker: usize,
    state: InputState,
}

impl<'a> InputSession<'a> {
    /// Starts `script` on a world built from `scene`: the named character (or
    /// the first) becomes steered. Fails for an unknown name, a scene
    /// without characters or a brush of a material the terrain lacks.
    pub fn start(
        script: &'a InputScript,
        scene: &Scene,
        app: &mut App,
        walkers: &[Entity],
    ) -> Result<Self, InputError> {
        let walker = match &script.character {
            Some(name) => scene.characters.iter().position(|c| &c.name == name),
            None => (!scene.characters.is_empty()).then_some(0),
        }
        .filter(|&k| k < walkers.len())
        .ok_or_else(|| InputError::Apply {
            what: "character".into(),
            reason: match &script.character {
                Some(name) => format!("the scene has no character {name:?}"),
                None => "the scene has no character to steer".into(),
            },
        })?;
        check_brushes(script, app)?;
        steer_character(&mut app.world, walkers[walker])?;
        Ok(InputSession {
            script,
            walker,
            state: InputState::default(),
        })
    }

    /// Index of the steered character in the scene.
    pub fn walker(&self) -> usize {
        self.walker
    }

    /// Applies the events of `step` before it runs. A reset rebuilds `app`
    /// and `walkers` from `scene` (steered again, standing still) and
    /// returns true.
    pub fn before_step(
        &mut self,
        step: u64,
        scene: &Scene,
        app: &mut App,
        walkers: &mut Vec<Entity>,
    ) -> Result<bool, SessionError> {
        let mut reset = false;
        for event in self.script.at(step) {
            reset |= self.apply(&event.action, scene, app, walkers)?;
        }
        Ok(reset)
    }

    /// Applies one `action` now (a live input); returns true for a reset,
    /// which rebuilds `app` and `walkers` as [`InputSession::before_step`] does.
    pub fn apply(
        &mut self,
        action: &InputAction,
        scene: &Scene,
        app: &mut App,
        walkers: &mut Vec<Entity>,
    ) -> Result<bool, SessionError> {
        if *action != InputAction::Reset {
            self.state
                .apply(action, &mut app.world, walkers[self.walker])?;
            return Ok(false);
        }
        let (fresh, entities) = scene.build_sim().map_err(SessionError::Reset)?;
        *app = fresh;
        *walkers = entities;
        steer_character(&mut app.world, walkers[self.walker])?;
        self.state = InputState::default();
        Ok(true)
    }

    /// What the inputs so far ask.
    pub fn state(&self) -> InputState {
        self.state
    }
}

/// Refuses a script whose brush names a material the terrain does not have
/// (or [`GRASS_BRUSH`]), before the first step.
fn check_brushes(script: &InputScript, app: &App) -> Result<(), InputError> {
    let ground = app.world.get_resource::<GroundState>();
    let Some(table) = ground.as_deref().map(|g| g.terrain().table()) else {
        return Ok(());
    };
    for event in &script.events {
        if let InputAction::Brush(name) = &event.action
            && name != GRASS_BRUSH
        {
            table.id(name).map_err(|e| InputError::Apply {
                what: format!("brush {name:?} at step {}", event.step),
                reason: e.to_string(),
            })?;
        }
    }
    Ok(())
}
