//! The walking character: description, body, walk cycle, foot rays, the rigid
//! proxy with the paper's balance controller (eq. 1), and foot IK.
//!
//! A [`Steering`] generates the path from a desired velocity ([`brake_modifiers`]).
//!
//! Each fixed step runs, in order (each stage is a plain function taking all
//! its state explicitly, so a schedule can run them as separate systems):
//! 1. [`gait_stage`]: walk-cycle phase, footholds, swing trajectories;
//! 2. [`foot_raycast_stage`]: vertical rays giving each foot's IK key;
//! 3. (vegetation's virtual platforms, outside this module);
//! 4. [`balance_stage`]: eq. 1 torque on the [`RigidProxy`], integrated, and
//!    the lateral axis leaning into turns;
//! 5. [`foot_ik_stage`]: legs, feet, pelvis drop, tilt; the final [`Pose`] and [`FootState`]s.
//!
//! [`step_character`] runs 1, 2, 4 and 5 against one ground:
//!
//! ```
//! use glam::Vec3;
//! use softwalk_systems::character::{Character, CharacterDesc, WalkPath, step_character};
//! use softwalk_systems::ground::FlatGround;
//!
//! let ground = FlatGround(0.0);
//! let path = WalkPath::straight(Vec3::ZERO, Vec3::Z, 3.0).unwrap();
//! let mut walker = Character::new(CharacterDesc::adult(), &path, &ground).unwrap();
//! for _ in 0..120 {
//!     step_character(&mut walker, &path, &ground, 1.0 / 60.0);
//! }
//! assert!(walker.gait.distance > 1.0);
//! ```
//!
//! [`FootState`]: crate::foot::FootState

mod balance;
mod body;
mod character_rig;
mod clip_gait;
mod clip_scratch;
mod clip_walk;
mod desc;
mod error;
mod foot_ik;
mod gait;
mod gravity;
mod ground_cross;
mod ik;
mod mesh;
mod metrics;
mod model_error;
mod model_units;
mod path;
mod pelvis;
mod pose;
mod rays;
pub(crate) mod rig_mass;
mod rig_pose;
mod skeleton;
mod stance_ground;
mod steering;
mod step;
mod support;
mod swing_knee;

pub use balance::{
    Balance, DEFAULT_LATERAL_DAMPING, DEFAULT_LATERAL_STIFFNESS, DEFAULT_LEAN_STIFFNESS,
    DEFAULT_LEAN_TIME_CONSTANT, DEFAULT_POSTURE_STIFFNESS, MAX_BRAKE_LEAN, MAX_TURN_LEAN,
    RigidProxy, animated_com, balance_stage, brake_lean, turn_lean,
};
pub use body::{BodyMass, CharacterBody};
pub use character_rig::{ArmChain, COARSE_MESH_CELL, CharacterRig};
pub use clip_gait::{CLIP_DUTY_RANGE, ClipGait, ClipTiming};
pub use clip_scratch::ClipScratch;
pub use clip_walk::ClipWalk;
pub use desc::{CharacterDesc, DEFAULT_PASSIVE_DAMPING};
pub use error::CharacterError;
pub use foot_ik::{FootIK, foot_ik_stage};
pub use gait::{
    DOWNHILL_STEP_SHORTENING, FootPlan, Gait, GaitModifiers, GaitParams, HEEL_STRIKE_PITCH,
    MAX_STEP_DT, TOE_OFF_PITCH, clamp_dt, contact_offset, gait_stage, scheduled_pitch,
};
pub use ik::{TwoBoneSolution, solve_two_bone};
pub use mesh::{capsule, character_mesh};
pub use metrics::CharacterMetrics;
pub use model_error::ModelError;
pub use model_units::{ModelUnits, STANDING_HEIGHT_M};
pub use path::{MAX_BACKWARD_ASLANT, PathPoint, PathSegment, WalkPath, turn_angle};
pub use pose::Pose;
pub use rays::{FootRays, GroundKey, foot_raycast_stage};
pub use rig_mass::RigMasses;
pub use rig_pose::RigPose;
pub use skeleton::{Bone, JOINT_COUNT, Joint};
pub use steering::{
    Brake, Steering, SteeringSettings, brake_modifiers, closing_time, curve_radius, stop_distance,
};
pub use step::{Character, step_character};
pub use support::{FootSupport, RIM_CLEARANCE, SupportPoint};
