//! The vegetation systems: virtual platforms under the feet, grass deformation.

use engine::ecs::World;

use super::components::{Feet, Platforms};
use super::systems_character::{step_dt, vegetation_at};
use crate::character::FootRays;
use crate::foot::FootState;
use crate::vegetation::GrassPatch;
use crate::vegetation::PlatformSettings;

/// System `platform`: advances each foot's virtual platform (paper §3.2) from
/// the foot's last state and the real ground key, then lets the foot ray see
/// it: where a standing platform's top covers the foot's sole centre and
/// lies above the real ground, it becomes the IK key.
pub fn platform_system(world: &mut World) {
    let dt = step_dt(world);
    let mut patch_query = world.query::<&GrassPatch>();
    let patches: Vec<&GrassPatch> = patch_query.iter().collect();
    let mut walkers = world.query::<(&mut Platforms, &mut FootRays, &Feet)>();
    for (platforms, rays, feet) in walkers.iter() {
        for (k, platform) in platforms.0.iter_mut().enumerate() {
            let foot = &feet.0[k];
            let at = foot.sole.center();
            let vegetation = vegetation_at(&patches, at.x, at.z);
            let settings =
                vegetation.map_or_else(PlatformSettings::default, |(p, _)| p.settings().platform);
            let height = vegetation.map_or(0.0, |(_, h)| h);
            let key = &mut rays.feet[k];
            platform.update(foot, key.point.y, height, dt, &settings);
            if let Some(top) = platform.top(&settings)
                && top.covers(at.x, at.z)
                && top.top_y > key.point.y
            {
                key.point.y = top.top_y;
                key.normal = glam::Vec3::Y;
            }
        }
    }
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
