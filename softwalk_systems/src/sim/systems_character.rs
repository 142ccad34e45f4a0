//! The character systems: ground response, gait, foot rays, balance, foot IK, metrics.

use engine::ecs::World;
use engine::schedule::Time;

use super::components::{BaseGains, Feet, Platforms, SystemFault, WalkerMetrics};
use super::ground_state::GroundState;
use super::labels;
use super::sole_ground::under_soles;
use crate::character::{
    Balance, CharacterBody, CharacterMetrics, FootIK, FootRays, Gait, GaitModifiers, Pose,
    RigidProxy, Steering, WalkPath, balance_stage, brake_modifiers, foot_ik_stage,
    foot_raycast_stage, gait_stage,
};
use crate::terrain::GaitResponse;
use crate::vegetation::{GrassPatch, PlatformSettings, VegetationFriction};

/// Characters per parallel batch of the per-character systems: a character's
/// stage costs a few microseconds, so a batch amortises the task overhead.
pub(crate) const CHARACTER_BATCH: usize = 4;

/// The fixed step of the current run.
pub(crate) fn step_dt(world: &World) -> f32 {
    world.get_resource::<Time>().map_or(0.0, |t| t.dt)
}

/// The vegetation at `(x, z)`: the tallest patch there and its height, or
/// `None` outside every patch.
pub(crate) fn vegetation_at<'a>(
    patches: &[&'a GrassPatch],
    x: f32,
    z: f32,
) -> Option<(&'a GrassPatch, f32)> {
    patches
        .iter()
        .map(|&p| (p, p.height_at(x, z)))
        .filter(|&(_, h)| h > 0.0)
        .max_by(|a, b| a.1.total_cmp(&b.1))
}

/// Vegetation height at `(x, z)`, 0 outside every patch.
pub(crate) fn sensed_vegetation(patches: &[&GrassPatch], x: f32, z: f32) -> f32 {
    vegetation_at(patches, x, z).map_or(0.0, |(_, h)| h)
}

/// Platform settings of the vegetation at `(x, z)`, or the defaults outside vegetation.
pub(crate) fn platform_settings_at(patches: &[&GrassPatch], x: f32, z: f32) -> PlatformSettings {
    vegetation_at(patches, x, z)
        .map_or_else(PlatformSettings::default, |(p, _)| p.settings().platform)
}

/// System `ground_response`: the material under the pelvis sets the gait
/// modifiers (data of [`crate::terrain::TerrainMaterial::gait`]); the vegetation
/// height under it scales `beta` by the paper's law (6 bare -> 4 at 0.9 m).
pub fn ground_response_system(world: &mut World) {
    let friction = world
        .get_resource::<VegetationFriction>()
        .map(|f| *f)
        .unwrap_or_default();
    let ground = world.get_resource::<GroundState>();
    let terrain = ground.as_deref().map(GroundState::terrain);
    let mut patch_query = world.query::<&GrassPatch>();
    let patches: Vec<&GrassPatch> = patch_query.iter().collect();
    let fault = std::sync::Mutex::new(None);
    let mut walkers = world.query::<(
        &Gait,
        &FootRays,
        &mut GaitModifiers,
        &mut Balance,
        &BaseGains,
    )>();
    walkers.par_for_each(CHARACTER_BATCH, |(gait, rays, modifiers, balance, base)| {
        let p = gait.pelvis.position;
        let response = terrain
            .and_then(|t| t.material_at(p.x, p.y))
            .map_or(GaitResponse::NEUTRAL, |m| m.gait);
        *modifiers = GaitModifiers {
            speed_scale: response.speed_scale,
            step_length_scale: response.step_length_scale,
            extra_clearance: response.extra_clearance,
            ..GaitModifiers::default()
        }
        .on_ground(rays.body.normal, gait.travel_heading());
        let h = sensed_vegetation(&patches, p.x, p.y);
        let beta = base.beta * friction.beta(h) / friction.beta_bare;
        if let Err(e) = balance.set_gains(base.alpha, beta) {
            report_fault(&fault, e.to_string());
        }
    });
    if let Some(message) = fault.into_inner().unwrap_or_else(|e| e.into_inner()) {
        world
            .resource_mut::<SystemFault>()
            .report(labels::GROUND_RESPONSE, message);
    }
}

/// Keeps the smallest message reported by the characters of a parallel
/// system (so the fault does not depend on the thread count).
fn report_fault(fault: &std::sync::Mutex<Option<String>>, message: String) {
    let mut slot = fault.lock().unwrap_or_else(|e| e.into_inner());
    if slot.as_ref().is_none_or(|m| message < *m) {
        *slot = Some(message);
    }
}

/// System `steer`: each character with a [`Steering`] gets its path from
/// its desired velocity, and its walking speed scaled to match (and, while
/// braking for a stop, the deceleration its balance leans back against).
pub fn steer_system(world: &mut World) {
    let dt = step_dt(world);
    world
        .query_mut::<(
            &mut Steering,
            &Gait,
            &CharacterBody,
            &mut WalkPath,
            &mut GaitModifiers,
        )>()
        .par_for_each(
            CHARACTER_BATCH,
            |(steering, gait, body, path, modifiers)| {
                *modifiers = brake_modifiers(steering, gait, body, path, *modifiers, dt);
            },
        );
}

/// System `gait`: advances every character's walk cycle.
pub fn gait_system(world: &mut World) {
    let dt = step_dt(world);
    world
        .query_mut::<(&mut Gait, &CharacterBody, &WalkPath, &GaitModifiers)>()
        .par_for_each(CHARACTER_BATCH, |(gait, body, path, modifiers)| {
            gait_stage(gait, body, path, modifiers, dt);
        });
}

/// System `foot_raycast`: vertical rays through the ground BVH (terrain and meshes).
pub fn foot_raycast_system(world: &mut World) {
    let Some(state) = world.get_resource::<GroundState>() else {
        return;
    };
    let ground = state.view();
    world
        .query::<(&mut FootRays, &Gait, &CharacterBody)>()
        .par_for_each(CHARACTER_BATCH, |(rays, gait, body)| {
            foot_raycast_stage(rays, gait, body, &ground);
        });
}

/// System `balance`: eq. 1 on each character's rigid proxy.
pub fn balance_system(world: &mut World) {
    let dt = step_dt(world);
    world
        .query_mut::<(&mut RigidProxy, &Balance, &CharacterBody, &Gait, &FootRays)>()
        .par_for_each(CHARACTER_BATCH, |(proxy, balance, body, gait, rays)| {
            balance_stage(proxy, balance, body, gait, rays, dt);
        });
}

/// System `foot_ik`: legs to the keys, pelvis drop, tilt; writes [`Feet`]
/// (and holds the landing of a foot that ploughs, in [`FootRays`]).
pub fn foot_ik_system(world: &mut World) {
    let dt = step_dt(world);
    world
        .query_mut::<(
            &mut FootIK,
            &mut Pose,
            &CharacterBody,
            &Gait,
            &mut FootRays,
            &RigidProxy,
            &mut Feet,
        )>()
        .par_for_each(
            CHARACTER_BATCH,
            |(ik, pose, body, gait, rays, proxy, feet)| {
                feet.0 = foot_ik_stage(ik, pose, body, gait, rays, proxy, dt);
            },
        );
}

/// System `metrics`: records each character's [`WalkerMetrics`] for this step,
/// with the ground heights under each sole (x, z clamped into the grid; a
/// static mesh under a sole counts, see `sole_ground::under_soles`).
pub fn metrics_system(world: &mut World) {
    let mut patch_query = world.query::<&GrassPatch>();
    let patches: Vec<&GrassPatch> = patch_query.iter().collect();
    let ground_state = world.get_resource::<GroundState>();
    let ground = ground_state.as_deref();
    let mut walkers = world.query::<(
        &CharacterBody,
        &Pose,
        &RigidProxy,
        &FootIK,
        &Feet,
        &Gait,
        &FootRays,
        Option<&WalkPath>,
        Option<&Platforms>,
        &mut WalkerMetrics,
    )>();
    walkers.par_for_each(CHARACTER_BATCH, |item| {
        let (body, pose, proxy, ik, feet, gait, rays, path, platforms, out) = item;
        let character = CharacterMetrics::capture(body, pose, proxy, ik, &feet.0);
        let platform_y = match platforms {
            Some(p) => p.0.each_ref().map(|pl| {
                let at = pl.centre();
                pl.top(&platform_settings_at(&patches, at.x, at.y))
                    .map(|t| t.top_y)
            }),
            None => [None, None],
        };
        let sole_ground = under_soles(ground, &character.soles);
        *out = WalkerMetrics {
            character,
            platform_y,
            grass_height: sensed_vegetation(&patches, character.com.x, character.com.z),
            ground_y: rays.body.point.y,
            velocity: glam::Vec3::new(gait.velocity.x, 0.0, gait.velocity.y),
            sole_ground,
            path_distance: gait.distance,
            path_finished: path.is_some_and(|p| p.is_finished(gait.distance)),
        };
    });
}
