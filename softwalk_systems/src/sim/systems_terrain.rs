//! The terrain systems: carve, smooth, settle, refit. Each touches only the
//! dirty windows around the feet.

use engine::ecs::World;
use engine::geom::{GridRect, RayScene};

use super::components::{Feet, FootPrints, SystemFault, TerrainDirty, TerrainVolume};
use super::labels;
use super::systems_character::step_dt;
use crate::terrain::{Heightfield, carve, settle_pending, settle_step, smooth, stage_window};

/// Resource: the rectangles carving and smoothing changed this step, passed
/// from `carve` to `smooth` to `settle`.
#[derive(Debug, Clone, Default)]
pub struct TerrainWindows {
    /// One rectangle per foot that carved this step.
    pub carved: Vec<GridRect>,
    /// What smoothing changed for each carved rectangle (same order).
    pub smoothed: Vec<GridRect>,
}

/// System `carve`: every stance foot in contact presses its sole into the
/// ground; c_t of the displaced volume is compacted, the rest goes to the rim.
pub fn carve_system(world: &mut World) {
    let dt = step_dt(world);
    let mut windows = world.resource_mut::<TerrainWindows>();
    windows.carved.clear();
    windows.smoothed.clear();
    let mut terrains = world.query::<&mut Heightfield>();
    let Some(hf) = terrains.iter().next() else {
        return;
    };
    hf.begin_step();
    for (feet, prints) in world.query::<(&Feet, &mut FootPrints)>().iter() {
        for (foot, print) in feet.0.iter().zip(prints.0.iter_mut()) {
            match carve(hf, print, &foot.sole, foot.pressing, dt) {
                Ok(rect) if !rect.is_empty() => windows.carved.push(rect),
                Ok(_) => {}
                Err(e) => world
                    .resource_mut::<SystemFault>()
                    .report(labels::CARVE, e.to_string()),
            }
        }
    }
    let changes = hf.changes();
    world.resource_mut::<TerrainVolume>().0 += changes.rim_volume - changes.carved_volume;
}

/// System `smooth`: the Gaussian filter of strength s_t, conservative, in each carved window.
pub fn smooth_system(world: &mut World) {
    let dt = step_dt(world);
    let mut windows = world.resource_mut::<TerrainWindows>();
    let mut terrains = world.query::<&mut Heightfield>();
    let Some(hf) = terrains.iter().next() else {
        return;
    };
    let smoothed: Vec<GridRect> = windows
        .carved
        .iter()
        .map(|&rect| smooth(hf, rect, dt))
        .collect();
    windows.smoothed = smoothed;
}

/// System `settle`: slopes steeper than the angle of repose slump, mass-conserving,
/// inside each carved window grown by the settling margin. The work is spread
/// over steps ([`settle_step`]): what earlier steps left pending (a released
/// print still slumping) continues first.
pub fn settle_system(world: &mut World) {
    let dt = step_dt(world);
    let windows = world.resource::<TerrainWindows>();
    let mut terrains = world.query::<&mut Heightfield>();
    let Some(hf) = terrains.iter().next() else {
        return;
    };
    settle_pending(hf, dt);
    for (k, &carved) in windows.carved.iter().enumerate() {
        // Without a smooth system (removed or replaced), settling starts from the carved window.
        let seeds = windows.smoothed.get(k).copied().unwrap_or(carved);
        settle_step(hf, stage_window(hf, carved), seeds, dt);
    }
}

/// System `refit`: the ground BVH refits only the tiles the step changed.
pub fn refit_system(world: &mut World) {
    let mut terrains = world.query::<&mut Heightfield>();
    let Some(hf) = terrains.iter().next() else {
        return;
    };
    let rect = hf.take_dirty();
    if rect.is_empty() {
        return;
    }
    if let Some(mut scene) = world.get_resource_mut::<RayScene>() {
        scene.refit_grid(hf.grid(), rect);
    }
    let mut dirty = world.resource_mut::<TerrainDirty>();
    dirty.0 = dirty.0.union(&rect);
}
