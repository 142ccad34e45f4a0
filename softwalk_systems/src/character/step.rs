//! All of a character's components together, and the convenience step that
//! runs stages 1, 2, 4 and 5 in order against one ground.

use glam::Vec3;

use super::balance::{Balance, RigidProxy, balance_stage};
use super::body::CharacterBody;
use super::desc::CharacterDesc;
use super::error::CharacterError;
use super::foot_ik::{FootIK, foot_ik_stage};
use super::gait::{Gait, GaitModifiers, GaitParams, gait_stage};
use super::metrics::CharacterMetrics;
use super::path::WalkPath;
use super::pose::Pose;
use super::rays::{FootRays, foot_raycast_stage};
use crate::foot::FootState;
use crate::ground::Ground;

/// One walking character: every component the stages read and write.
#[derive(Debug, Clone, PartialEq)]
pub struct Character {
    /// Dimensions, masses, inertia.
    pub body: CharacterBody,
    /// Walk-cycle state.
    pub gait: Gait,
    /// Per-step gait changes from terrain and vegetation (neutral by default).
    pub modifiers: GaitModifiers,
    /// The ground keys.
    pub rays: FootRays,
    /// Controller settings.
    pub balance: Balance,
    /// The rigid proxy carrying the tilt.
    pub proxy: RigidProxy,
    /// Foot IK state.
    pub ik: FootIK,
    /// The final pose.
    pub pose: Pose,
    /// Each foot's state after the last step (left first).
    pub feet: [FootState; 2],
    /// What the last step recorded.
    pub metrics: CharacterMetrics,
}

impl Character {
    /// A character standing at the start of `path` on `ground`, posed.
    pub fn new(
        desc: CharacterDesc,
        path: &WalkPath,
        ground: &dyn Ground,
    ) -> Result<Self, CharacterError> {
        let body = CharacterBody::new(desc)?;
        GaitParams::check_reach(&body)?;
        let balance = Balance::new(desc.alpha, desc.beta)?;
        let modifiers = GaitModifiers::default();
        let gait = Gait::new(&body, path, &modifiers);
        let mut rays = FootRays::new(&gait, &body, ground);
        let proxy = RigidProxy::new(&body);
        let mut ik = FootIK::default();
        let mut pose = Pose::rest(&body, Vec3::ZERO);
        let feet = foot_ik_stage(&mut ik, &mut pose, &body, &gait, &mut rays, &proxy, 0.0);
        let metrics = CharacterMetrics::capture(&body, &pose, &proxy, &ik, &feet);
        Ok(Character {
            body,
            gait,
            modifiers,
            rays,
            balance,
            proxy,
            ik,
            pose,
            feet,
            metrics,
        })
    }
}

/// Runs one fixed step of `dt` seconds: gait, foot rays, balance, foot IK,
/// then records the metrics.
pub fn step_character(character: &mut Character, path: &WalkPath, ground: &dyn Ground, dt: f32) {
    let c = character;
    let modifiers = c
        .modifiers
        .on_ground(c.rays.body.normal, c.gait.travel_heading());
    gait_stage(&mut c.gait, &c.body, path, &modifiers, dt);
    foot_raycast_stage(&mut c.rays, &c.gait, &c.body, ground);
    balance_stage(&mut c.proxy, &c.balance, &c.body, &c.gait, &c.rays, dt);
    c.feet = foot_ik_stage(
        &mut c.ik,
        &mut c.pose,
        &c.body,
        &c.gait,
        &mut c.rays,
        &c.proxy,
        dt,
    );
    c.metrics = CharacterMetrics::capture(&c.body, &c.pose, &c.proxy, &c.ik, &c.feet);
}
