//! The terrain systems: carve, smooth, settle, refit. Each works on the
//! rectangles around the feet, one by one: two feet far apart cost two small
//! rectangles, never the box between them.

use engine::ecs::World;

use super::components::{Feet, FootPrints, SystemFault};
use super::ground_state::GroundState;
use super::labels;
use super::systems_character::step_dt;
use crate::terrain::{
    Pressed, ScratchPool, SettleScratch, SmoothScratch, deposit_rim, press, settle_each,
    smooth_each, stage_window,
};

/// System `carve`: every stance foot in contact presses its sole into the
/// ground, character by character in query order and left foot first (a
/// fixed order, whatever the thread count); c_t of the displaced volume is
/// compacted. Once every foot has pressed, the rest goes to each print's rim,
/// around every sole held this step. Starts the step's change log.
pub fn carve_system(world: &mut World) {
    let dt = step_dt(world);
    let Some(mut ground) = world.get_resource_mut::<GroundState>() else {
        return;
    };
    let hf = ground.terrain_mut();
    hf.begin_step();
    let mut query = world.query::<(&Feet, &mut FootPrints)>();
    let mut pressed = Vec::new();
    for (feet, prints) in query.iter() {
        for (foot, print) in feet.0.iter().zip(prints.0.iter_mut()) {
            match press(hf, print, &foot.sole, foot.pressing, dt) {
                Ok(p) => pressed.push(p),
                Err(e) => {
                    pressed.push(Pressed::default());
                    world
                        .resource_mut::<SystemFault>()
                        .report(labels::CARVE, e.to_string());
                }
            }
        }
    }
    let mut pressed = pressed.into_iter();
    for (_, prints) in query.iter() {
        for (print, p) in prints.0.iter_mut().zip(pressed.by_ref()) {
            deposit_rim(hf, print, p);
        }
    }
    let changes = hf.changes();
    let delta = changes.rim_volume - changes.carved_volume;
    ground.add_volume(delta);
}

/// System `smooth`: the Gaussian filter of strength s_t, conservative, in
/// each rectangle carved this step, rectangles apart in parallel
/// ([`smooth_each`]). Its work buffers are the [`ScratchPool`] of
/// [`SmoothScratch`] resource (fresh ones without it).
pub fn smooth_system(world: &mut World) {
    let dt = step_dt(world);
    let Some(mut ground) = world.get_resource_mut::<GroundState>() else {
        return;
    };
    let mut scratch = world.get_resource_mut::<ScratchPool<SmoothScratch>>();
    let mut fresh = ScratchPool::default();
    let scratch = scratch.as_deref_mut().unwrap_or(&mut fresh);
    let hf = ground.terrain_mut();
    let carved = hf.changes().carved.clone();
    smooth_each(hf, scratch, &carved, dt);
}

/// System `settle`: slopes steeper than the angle of repose slump, mass-conserving,
/// inside each carved rectangle grown by the settling margin. The work is spread
/// over steps ([`crate::terrain::settle_step`]): what earlier steps left pending (a released
/// print still slumping) continues first. Windows apart run in parallel
/// ([`settle_each`]). Its work buffers are the [`ScratchPool`] of
/// [`SettleScratch`] resource (fresh ones without it).
pub fn settle_system(world: &mut World) {
    let dt = step_dt(world);
    let Some(mut ground) = world.get_resource_mut::<GroundState>() else {
        return;
    };
    let mut scratch = world.get_resource_mut::<ScratchPool<SettleScratch>>();
    let mut fresh = ScratchPool::default();
    let scratch = scratch.as_deref_mut().unwrap_or(&mut fresh);
    let hf = ground.terrain_mut();
    let changes = hf.changes();
    let windows: Vec<_> = (changes.carved.iter().enumerate())
        // Without a smooth system (removed or replaced), settling starts from the carved rectangle.
        .map(|(k, &carved)| {
            let seeds = changes.smoothed.get(k).copied().unwrap_or(carved);
            (stage_window(hf, carved), seeds)
        })
        .collect();
    settle_each(hf, scratch, &windows, dt);
}

/// System `refit`: closes the step's change log. The rectangles it changed
/// join the grid BVH's stale tiles (refit when a general ray needs them,
/// [`GroundState::cast`]) and the rectangles the renderer re-meshes.
pub fn refit_system(world: &mut World) {
    if let Some(mut ground) = world.get_resource_mut::<GroundState>() {
        ground.end_step();
    }
}
