//! Names of the pipeline's systems and sets, for ordering user systems against them.

/// Senses material and vegetation under each character (set `character`).
pub const GROUND_RESPONSE: &str = "ground_response";
/// Steered characters: paths from their desired velocity (set `character`).
pub const STEER: &str = "steer";
/// Walk-cycle phase, footholds, swing trajectories (set `character`).
pub const GAIT: &str = "gait";
/// Vertical foot rays onto the ground: the IK keys (set `character`).
pub const FOOT_RAYCAST: &str = "foot_raycast";
/// Virtual platforms in vegetation (set `character`).
pub const PLATFORM: &str = "platform";
/// The PD balance controller on the rigid proxy (set `character`).
pub const BALANCE: &str = "balance";
/// Two-bone foot IK, pelvis drop, tilt (set `character`).
pub const FOOT_IK: &str = "foot_ik";
/// Stance feet imprint the ground (set `terrain`).
pub const CARVE: &str = "carve";
/// Gaussian smoothing in the dirty windows (set `terrain`).
pub const SMOOTH: &str = "smooth";
/// Angle-of-repose settling (set `terrain`).
pub const SETTLE: &str = "settle";
/// BVH refit of the changed ground tiles (set `terrain`).
pub const REFIT: &str = "refit";
/// Grass deformation and recovery (set `vegetation`).
pub const GRASS_DEFORM: &str = "grass_deform";
/// Per-character metrics of the step.
pub const METRICS: &str = "metrics";

/// The set of character systems.
pub const SET_CHARACTER: &str = "character";
/// The set of terrain systems.
pub const SET_TERRAIN: &str = "terrain";
/// The set of vegetation systems.
pub const SET_VEGETATION: &str = "vegetation";
