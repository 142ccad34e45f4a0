use engine::geom::GeomError;
use engine::schedule::{AppError, ScheduleError};
use thiserror::Error;

use crate::character::{CharacterError, ModelError};
use crate::terrain::TerrainError;
use crate::vegetation::VegetationError;

/// Errors raised while building or stepping a simulation.
#[derive(Debug, Error)]
pub enum SimError {
    /// A character could not be built.
    #[error("character `{name}`: {source}")]
    Character {
        /// The character's name.
        name: String,
        /// Why.
        #[source]
        source: CharacterError,
    },
    /// A character's model could not be attached.
    #[error("character `{name}`: its model: {source}")]
    Model {
        /// The character's name.
        name: String,
        /// Why (boxed: a model error is large).
        #[source]
        source: Box<ModelError>,
    },
    /// The terrain could not be built or stepped.
    #[error("terrain: {0}")]
    Terrain(#[from] TerrainError),
    /// A grass patch could not be built.
    #[error("grass patch {index}: {source}")]
    Vegetation {
        /// Index of the patch.
        index: usize,
        /// Why.
        #[source]
        source: VegetationError,
    },
    /// A mesh could not be added to the ray-cast scene.
    #[error("geometry: {0}")]
    Geometry(#[from] GeomError),
    /// The schedule could not be built or run.
    #[error("schedule: {0}")]
    Schedule(#[from] ScheduleError),
    /// The fixed-step app refused its settings.
    #[error("app: {0}")]
    App(#[from] AppError),
    /// The simulation has no terrain.
    #[error("the scene has no terrain: call SimBuilder::terrain first")]
    NoTerrain,
    /// A system reported a fault during a step.
    #[error("system `{system}` failed at step {step}: {message}")]
    System {
        /// The system's name.
        system: &'static str,
        /// The step it failed at.
        step: u64,
        /// What went wrong.
        message: String,
    },
}
