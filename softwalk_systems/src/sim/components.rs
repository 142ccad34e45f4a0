//! Components and resources the pipeline adds beside the paper's own types.

use glam::Vec3;

use super::sole_ground::SoleGround;
use crate::character::CharacterMetrics;
use crate::foot::FootState;
use crate::terrain::FootPrint;
use crate::vegetation::VirtualPlatform;

/// A character's display name (metrics rows and overlays use it).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CharacterName(pub String);

/// Each foot's state after the last IK step (left first).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Feet(pub [FootState; 2]);

/// Each foot's print in progress on the ground (left first).
#[derive(Debug, Clone, Default)]
pub struct FootPrints(pub [FootPrint; 2]);

/// Each foot's virtual platform (left first); idle outside vegetation.
#[derive(Debug, Clone, PartialEq)]
pub struct Platforms(pub [VirtualPlatform; 2]);

/// The gains a character was given; vegetation scales `beta` from these each step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BaseGains {
    /// The paper's alpha.
    pub alpha: f32,
    /// The paper's beta with no vegetation.
    pub beta: f32,
}

/// Everything one character recorded this step: the character's own metrics
/// plus what the ground and vegetation add.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WalkerMetrics {
    /// The character's own metrics (COM, tilt, torque, feet, knees, ...).
    pub character: CharacterMetrics,
    /// Top of each foot's virtual platform, when one stands.
    pub platform_y: [Option<f32>; 2],
    /// Vegetation height sensed under the character's centre of mass.
    pub grass_height: f32,
    /// Ground height under the pelvis.
    pub ground_y: f32,
    /// Velocity of the centre of mass over the path (world XZ, y = 0).
    pub velocity: Vec3,
    /// Ground heights (terrain, or a prop just above it) under each sole's heel, centre and toe (left first).
    pub sole_ground: [SoleGround; 2],
    /// Distance the gait has covered along its path, metres.
    pub path_distance: f32,
    /// True once the gait has reached the end of its path (never for a looped path).
    pub path_finished: bool,
}

/// Resource: the first fault a system reported; [`crate::sim::step`] turns it into an error.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SystemFault(pub Option<(&'static str, String)>);

impl SystemFault {
    /// Records a fault unless one is already recorded.
    pub fn report(&mut self, system: &'static str, message: impl Into<String>) {
        if self.0.is_none() {
            self.0 = Some((system, message.into()));
        }
    }
}

/// Resource: the static meshes (rocks, steps) the feet can stand on, as
/// given to [`super::SimBuilder::mesh`], for drawing.
#[derive(Debug, Clone, Default)]
pub struct Props(pub Vec<engine::geom::TriMesh>);
