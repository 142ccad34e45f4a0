//! The vegetation systems: virtual platforms under the feet, grass deformation.

use engine::ecs::World;

use super::components::{Feet, Platforms};
use super::systems_character::{CHARACTER_BATCH, step_dt, vegetation_at};
use crate::character::FootRays;
use crate::foot::FootState;
use crate::vegetation::GrassPatch;
use crate::vegetation::PlatformSettings;

/// System `platform`: advances each foot's virtual platform (paper §3.2) from
/// the foot's last state and the ground under its key, then lets the
/// foot see it: where a standing platform's top covers the foot's sole
/// centre and lies above the key, the sole stays on or above it
/// ([`crate::character::GroundKey::platform`]).
pub fn platform_system(world: &mut World) {
    let dt = step_dt(world);
    let mut patch_query = world.query::<&GrassPatch>();
    let patches: Vec<&GrassPatch> = patch_query.iter().collect();
    let mut walkers = world.query::<(&mut Platforms, &mut FootRays, &Feet)>();
    walkers.par_for_each(CHARACTER_BATCH, |(platforms, rays, feet)| {
        for (k, platform) in platforms.0.iter_mut().enumerate() {
            let foot = &feet.0[k];
            let at = foot.sole.center();
            let vegetation = vegetation_at(&patches, at.x, at.z);
            let settings =
                vegetation.map_or_else(PlatformSettings::default, |(p, _)| p.settings().platform);
            let height = vegetation.map_or(0.0, |(_, h)| h);
            let key = &mut rays.feet[k];
            platform.update(foot, key.point.y, height, dt, &settings);
            key.platform = platform
                .top(&settings)
                .filter(|top| top.covers(at.x, at.z) && top.top_y > key.point.y)
                .map(|top| top.top_y);
        }
    });
}

/// System `grass_deform`: eq. 2 for every foot of every character on every
/// patch; bent blades recover, broken ones stay down.
pub fn grass_deform_system(world: &mut World) {
    let dt = step_dt(world);
    let mut feet_query = world.query::<&Feet>();
    let feet: Vec<FootState> = feet_query.iter().flat_map(|f| f.0).collect();
    drop(feet_query);
    for patch in world.query_mut::<&mut GrassPatch>() {
        patch.deform(&feet, dt);
    }
}
