//! The paper's pipeline as named systems on the engine's ECS.
//!
//! One fixed step runs these systems, in this order (see [`labels`]):
//!
//! | # | system | what it does |
//! |---|---|---|
//! | 0 | `ground_response` | senses the material and vegetation under each character: gait modifiers and the vegetation `beta` |
//! | 1 | `steer` | characters with a `Steering`: their path from the desired velocity, their speed scaled to it |
//! | 2 | `gait` | walk-cycle phase, footholds, swing trajectories |
//! | 3 | `foot_raycast` | vertical rays through the BVH onto the deformed ground and meshes: the IK keys |
//! | 4 | `platform` | the virtual platforms' state machines; a platform above the ground becomes the key |
//! | 5 | `balance` | eq. 1 torque on the rigid proxy, integrated |
//! | 6 | `foot_ik` | two-bone IK, pelvis drop, tilt; the final pose and the feet |
//! | 7 | `carve` | stance feet imprint the ground (d_t, c_t) |
//! | 8 | `smooth` | Gaussian filter of strength s_t in the dirty windows |
//! | 9 | `settle` | slopes above the angle of repose slump |
//! | 10 | `refit` | closes the step's change log: its rectangles become stale BVH tiles (refit lazily) and the renderer's re-meshing |
//! | 11 | `grass_deform` | eq. 2 on the blades near every foot; recovery |
//! | 12 | `metrics` | what the step recorded, per character |
//!
//! Systems are grouped in the sets `character` (0–6), `terrain` (7–10) and
//! `vegetation` (11), so a user can put a system before or after a whole set,
//! or replace one by name ([`engine::schedule::Schedule::replace`]).
//!
//! ```
//! use softwalk_systems::sim::{SimBuilder, labels};
//! use softwalk_systems::character::{CharacterDesc, WalkPath};
//! use softwalk_systems::terrain::{Heightfield, MaterialTable, generate};
//! use glam::Vec3;
//!
//! let table = MaterialTable::with_presets();
//! let snow = table.id("snow").unwrap();
//! let grid = generate::flat(generate::GridSpec::square(4.0, 201), 1.0).unwrap();
//! let mut sim = SimBuilder::new(1.0 / 60.0).unwrap();
//! sim.terrain(Heightfield::from_grid(grid, table, snow).unwrap()).unwrap();
//! let path = WalkPath::straight(Vec3::new(0.5, 0.0, 2.0), Vec3::X, 3.0).unwrap();
//! sim.character("walker", CharacterDesc::adult(), path).unwrap();
//! let mut app = sim.build().unwrap();
//! assert_eq!(app.schedule.order()[2], labels::GAIT);
//! softwalk_systems::sim::run_steps(&mut app, 60).unwrap();
//! ```

mod builder;
mod components;
mod error;
mod ground_state;
mod ground_view;
pub mod labels;
mod pipeline;
mod rig_attach;
mod run;
mod sole_ground;
mod standing_prints;
mod systems_character;
mod systems_terrain;
mod systems_vegetation;
mod timing;
mod world_hash;

pub use builder::SimBuilder;
pub use components::{
    BaseGains, CharacterName, Feet, FootPrints, Platforms, Props, SystemFault, WalkerMetrics,
};
pub use error::SimError;
pub use ground_state::GroundState;
pub use ground_view::SceneGround;
pub use pipeline::add_pipeline;
pub use rig_attach::{MassSource, attach_rig, attach_rig_with};
pub use run::{run_steps, step};
pub use sole_ground::{SoleGround, clamped_height, sole_ends};
pub use systems_character::{
    balance_system, foot_ik_system, foot_raycast_system, gait_system, ground_response_system,
    metrics_system, steer_system,
};
pub use systems_terrain::{carve_system, refit_system, settle_system, smooth_system};
pub use systems_vegetation::{grass_deform_system, platform_system};
pub use timing::SystemTimings;
pub use world_hash::{WorldHasher, world_hash};
