//! What one character step records, for tests, plots and the paper's claims.

use glam::Vec3;

use super::balance::RigidProxy;
use super::body::CharacterBody;
use super::foot_ik::FootIK;
use super::pose::Pose;
use super::skeleton::Joint;
use crate::foot::{FootPhase, FootSole, FootState};

/// Measurements of one character after a step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CharacterMetrics {
    /// Whole-body centre of mass of the final pose (world).
    pub com: Vec3,
    /// Forward lean of the proxy, radians (positive: towards the walking direction).
    pub tilt: f32,
    /// Rate of the forward lean, rad/s.
    pub tilt_rate: f32,
    /// Controller torque of eq. 1, forward positive, N·m.
    pub torque: f32,
    /// Height of the pelvis (hip centre), metres.
    pub pelvis_y: f32,
    /// Lowest point of each sole (left first): the heel while the toe is up
    /// (heel strike), the toe while the heel is up (heel rise, toe-off), the
    /// sole centre when the foot is flat. In stance it is the point on the ground.
    pub feet: [Vec3; 2],
    /// Each sole after IK (left first), heel and toe.
    pub soles: [FootSole; 2],
    /// Whether each foot bears weight on ground (see [`FootState::contact`]).
    pub contact: [bool; 2],
    /// Whether each foot presses the ground (see [`FootState::pressing`]): a
    /// foot pushing into soft ground at the end of its swing presses it but
    /// bears no weight yet.
    pub pressing: [bool; 2],
    /// Whether each foot is planted: in the stance of its walk cycle.
    pub planted: [bool; 2],
    /// Height of each foot's IK target (sole centre: ground key plus swing lift).
    pub ik_target_y: [f32; 2],
    /// Knee flexion of each leg, radians (0 = straight).
    pub knee_flexion: [f32; 2],
    /// Ground slope under the pelvis along the walking direction, radians (uphill positive).
    pub ground_slope: f32,
}

impl CharacterMetrics {
    /// Reads the metrics from the outputs of a step.
    pub fn capture(
        body: &CharacterBody,
        pose: &Pose,
        proxy: &RigidProxy,
        ik: &FootIK,
        feet: &[FootState; 2],
    ) -> Self {
        CharacterMetrics {
            com: pose.center_of_mass(body),
            tilt: proxy.tilt,
            tilt_rate: proxy.tilt_rate,
            torque: proxy.torque,
            pelvis_y: pose.joint(Joint::Pelvis).y,
            feet: ik.contact_points,
            soles: feet.map(|f| f.sole),
            contact: feet.map(|f| f.contact),
            pressing: feet.map(|f| f.pressing),
            planted: feet.map(|f| f.phase == FootPhase::Stance),
            ik_target_y: ik.sole_targets.map(|t| t.y),
            knee_flexion: pose.knee_flexion(),
            ground_slope: proxy.slope,
        }
    }
}
