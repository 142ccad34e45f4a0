//! The pipeline's schedule: each system named, in its set, chained in the paper's order.

use engine::ecs::World;
use engine::schedule::Schedule;

use super::labels::*;
use super::systems_character::{
    balance_system, foot_ik_system, foot_raycast_system, gait_system, ground_response_system,
    metrics_system, steer_system,
};
use super::systems_terrain::{carve_system, refit_system, settle_system, smooth_system};
use super::systems_vegetation::{grass_deform_system, platform_system};
use super::timing::timed;

type SystemFn = fn(&mut World);

/// The pipeline, in order: `(name, set, system)`.
const PIPELINE: [(&str, Option<&str>, SystemFn); 13] = [
    (GROUND_RESPONSE, Some(SET_CHARACTER), ground_response_system),
    (STEER, Some(SET_CHARACTER), steer_system),
    (GAIT, Some(SET_CHARACTER), gait_system),
    (FOOT_RAYCAST, Some(SET_CHARACTER), foot_raycast_system),
    (PLATFORM, Some(SET_CHARACTER), platform_system),
    (BALANCE, Some(SET_CHARACTER), balance_system),
    (FOOT_IK, Some(SET_CHARACTER), foot_ik_system),
    (CARVE, Some(SET_TERRAIN), carve_system),
    (SMOOTH, Some(SET_TERRAIN), smooth_system),
    (SETTLE, Some(SET_TERRAIN), settle_system),
    (REFIT, Some(SET_TERRAIN), refit_system),
    (GRASS_DEFORM, Some(SET_VEGETATION), grass_deform_system),
    (METRICS, None, metrics_system),
];

/// Adds the pipeline's systems to `schedule`, each after the previous one and
/// in its set; the sets are ordered `character` -> `terrain` -> `vegetation`.
/// Each system's time per call is recorded in [`super::SystemTimings`] when that
/// resource exists.
pub fn add_pipeline(schedule: &mut Schedule) {
    let mut previous: Option<&'static str> = None;
    for (name, set, system) in PIPELINE {
        let mut config = schedule.add_system(name, timed(name, system));
        if let Some(set) = set {
            config = config.in_set(set);
        }
        if let Some(prev) = previous {
            config.after(prev);
        }
        previous = Some(name);
    }
    schedule.configure_set(SET_TERRAIN).after(SET_CHARACTER);
    schedule.configure_set(SET_VEGETATION).after(SET_TERRAIN);
}
