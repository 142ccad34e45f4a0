//! Debug overlays drawn over a frame: centre of mass, support segment, torque,
//! foot rays, IK targets and virtual platforms (paper Fig. 2 and 3).

use super::OverlayLayers;
use crate::character::{FootIK, FootRays, Gait, RigidProxy};
use crate::sim::{Platforms, WalkerMetrics};
use engine::canvas::Overlay;
use engine::ecs::World;
use engine::render::Camera;
use glam::Vec3;
use image::{Rgba, RgbaImage};

const COM: Rgba<u8> = Rgba([255, 60, 40, 255]);
const SUPPORT: Rgba<u8> = Rgba([40, 220, 90, 255]);
const TORQUE: Rgba<u8> = Rgba([255, 200, 0, 255]);
const RAY: Rgba<u8> = Rgba([80, 170, 255, 255]);
const TARGET: Rgba<u8> = Rgba([255, 255, 255, 255]);
const PLATFORM: Rgba<u8> = Rgba([230, 80, 230, 255]);

/// Torque arrow length per N·m, metres.
const TORQUE_SCALE: f32 = 0.02;

/// Draws every character's overlay `layers` onto `image` as `camera` sees them.
pub fn draw_overlays(world: &World, camera: &Camera, image: &mut RgbaImage, layers: OverlayLayers) {
    let project = |p: Vec3| camera.project(p);
    let mut overlay = Overlay::new(image);
    let mut walkers = world.query::<(
        &RigidProxy,
        &FootRays,
        &FootIK,
        &Gait,
        &WalkerMetrics,
        Option<&Platforms>,
    )>();
    for (proxy, rays, ik, gait, metrics, platforms) in walkers.iter() {
        let com = metrics.character.com;
        let travel = gait.travel_heading();
        let travel = Vec3::new(travel.x, 0.0, travel.y);
        // Support segment: both feet on the ground, and the target at its midpoint.
        if layers.support {
            let [a, b] = rays.feet.map(|k| k.point);
            overlay.world_line(&project, a, b, SUPPORT, 3.0);
            overlay.world_circle(&project, (a + b) * 0.5, 5.0, SUPPORT, 2.0);
        }
        // Centre of mass and its projection on the ground.
        if layers.com {
            let ground = Vec3::new(com.x, rays.body.point.y, com.z);
            overlay.world_line(&project, com, ground, COM, 1.5);
            if let Some(c) = project(com) {
                overlay.fill_circle(c, 6.0, COM);
            }
        }
        // The proxy's torque about its right axis, drawn along the direction of travel.
        if layers.proxy {
            let tip = com + travel * proxy.torque * TORQUE_SCALE;
            overlay.world_arrow(&project, com, tip, TORQUE, 3.0);
        }
        // Foot rays from above each foot down to the key, and the IK targets.
        for k in (0..2).filter(|_| layers.ik_keys) {
            let key = rays.feet[k].point;
            overlay.world_line(&project, key + Vec3::Y * 0.6, key, RAY, 1.5);
            overlay.world_circle(&project, ik.sole_targets[k], 4.0, TARGET, 2.0);
        }
        if let Some(platforms) = platforms.filter(|_| layers.platforms) {
            for (k, y) in metrics.platform_y.iter().enumerate() {
                let (Some(y), Some(p)) = (y, platforms.0.get(k)) else {
                    continue;
                };
                let c = p.centre();
                let h = 0.15;
                let corners = [(-h, -h), (h, -h), (h, h), (-h, h), (-h, -h)]
                    .map(|(dx, dz)| Vec3::new(c.x + dx, *y, c.y + dz));
                overlay.world_polyline(&project, &corners, PLATFORM, 2.0);
            }
        }
    }
}
