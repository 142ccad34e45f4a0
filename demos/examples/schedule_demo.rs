//! A demo written as a system schedule.
//!
//! Builds a world by hand with `SimBuilder` (a sand-and-snow terrain, a patch
//! of grass, one walker), prints the resolved system order, adds a user system
//! that logs the centre of mass once per simulated second right after the foot
//! IK, runs the steps and renders the last frame with `WorldView`.
//!
//! ```text
//! cargo run --release -p demos --example schedule_demo [OUT_DIR] [STEPS]
//! ```
//!
//! Writes `final.png` to `OUT_DIR` (default `target/examples/schedule_demo/`).

mod common;

use std::error::Error;

use engine::ecs::World;
use engine::geom::GridRect;
use engine::output::save_png;
use engine::schedule::{App, Time};
use glam::{Vec2, Vec3};
use image::RgbaImage;
use softwalk_systems::character::{CharacterBody, CharacterDesc, Pose, WalkPath};
use softwalk_systems::sim::{CharacterName, SimBuilder, WalkerMetrics, labels, run_steps};
use softwalk_systems::terrain::{Heightfield, MaterialTable, generate};
use softwalk_systems::vegetation::{GrassSettings, XzRect};
use softwalk_systems::view::{CameraRig, ViewSettings, WorldView};

/// Fixed step: 60 Hz.
const DT: f32 = 1.0 / 60.0;
/// Steps run when none is given on the command line (7 s).
const DEFAULT_STEPS: u64 = 420;
/// Frame size of the final picture.
const FRAME: (u32, u32) = (640, 360);

fn main() -> Result<(), Box<dyn Error>> {
    let out = common::output_dir("schedule_demo")?;
    let steps = match std::env::args().nth(2) {
        Some(text) => text.parse()?,
        None => DEFAULT_STEPS,
    };

    let mut app = build_world()?;

    // A user system, ordered against the pipeline by label: after the foot
    // IK, when this step's pose is final, and before the terrain set. Without
    // the `before`, ties resolve by insertion order and it would run last.
    app.add_system("log_com", log_com_each_second)
        .after(labels::FOOT_IK)
        .before(labels::SET_TERRAIN);
    app.schedule.build()?;
    println!("resolved system order:");
    app.schedule.print_order();

    run_steps(&mut app, steps)?;

    let image = render_final_frame(&app.world)?;
    let path = out.join("final.png");
    save_png(&path, &image)?;
    println!("wrote {}", path.display());
    Ok(())
}

/// An 8 x 4 m terrain of gentle sandy hills with a snow band in the middle,
/// medium grass on the last third, and an adult walking along +X.
fn build_world() -> Result<App, Box<dyn Error>> {
    let spec = generate::GridSpec {
        origin: Vec2::ZERO,
        cell: 0.02,
        nx: 401,
        nz: 201,
    };
    let hills = generate::NoiseParams {
        base: 1.0,
        amplitude: 0.12,
        feature_size: 3.0,
        seed: 7,
        ..Default::default()
    };
    let table = MaterialTable::with_presets();
    let (sand, snow) = (table.id("sand")?, table.id("snow")?);
    let mut terrain = Heightfield::from_grid(generate::noise(spec, hills)?, table, sand)?;
    // Columns 100..200 are x in [2, 4) m.
    terrain.paint_rect(GridRect::new(100, 0, 200, spec.nz), snow)?;

    let mut sim = SimBuilder::new(DT)?;
    sim.terrain(terrain)?; // first: grass and walkers are placed on it
    sim.grass(
        XzRect::new(Vec2::new(5.4, 1.2), Vec2::new(7.8, 2.8)),
        GrassSettings::medium(),
    )?;
    let path = WalkPath::straight(Vec3::new(0.5, 0.0, 2.0), Vec3::X, 7.2)?;
    sim.character("walker", CharacterDesc::adult(), path)?;
    Ok(sim.build()?)
}

/// User system: prints each walker's centre of mass at every whole second.
fn log_com_each_second(world: &mut World) {
    let time = *world.resource::<Time>();
    let steps_per_second = (1.0 / f64::from(time.dt)).round() as u64;
    if !time.step.is_multiple_of(steps_per_second) {
        return;
    }
    for (name, pose, body) in world
        .query::<(&CharacterName, &Pose, &CharacterBody)>()
        .iter()
    {
        let com = pose.center_of_mass(body);
        println!(
            "t = {:4.1} s  {}: COM ({:.2}, {:.2}, {:.2})",
            time.elapsed, name.0, com.x, com.y, com.z
        );
    }
}

/// Draws the world with [`WorldView`]: the camera looks down and back along
/// the trail from ahead of the first walker.
fn render_final_frame(world: &World) -> Result<RgbaImage, Box<dyn Error>> {
    let com = world
        .query::<&WalkerMetrics>()
        .iter()
        .next()
        .map_or(Vec3::new(4.0, 1.0, 2.0), |m| m.character.com);
    let rig = CameraRig::fixed(
        com + Vec3::new(1.2, 2.0, 2.4),
        com + Vec3::new(-1.6, -1.2, 0.0),
    );
    let settings = ViewSettings {
        width: FRAME.0,
        height: FRAME.1,
        ..ViewSettings::default()
    };
    Ok(WorldView::new(world, rig, &settings)?.render(world, 0.0)?)
}
