//! Where a [`super::WorldView`]'s camera stands and what it looks at.

use engine::ecs::Entity;
use glam::Vec3;

/// How a view's camera is placed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum CameraRig {
    /// A camera standing still.
    Fixed {
        /// Where it stands.
        eye: Vec3,
        /// What it looks at.
        target: Vec3,
    },
    /// A camera following a character's centre of mass, smoothly.
    Follow {
        /// The followed character (an entity with walker metrics).
        character: Entity,
        /// Eye position relative to the centre of mass.
        offset: Vec3,
    },
}

impl CameraRig {
    /// A camera at `eye` looking at `target`.
    pub fn fixed(eye: impl Into<Vec3>, target: impl Into<Vec3>) -> CameraRig {
        CameraRig::Fixed {
            eye: eye.into(),
            target: target.into(),
        }
    }

    /// A camera following `character` from `offset`.
    pub fn follow(character: Entity, offset: impl Into<Vec3>) -> CameraRig {
        CameraRig::Follow {
            character,
            offset: offset.into(),
        }
    }
}
