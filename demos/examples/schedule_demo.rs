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
    let (app, image) = run_demo(steps, FRAME)?;
    println!("resolved system order:");
    app.schedule.print_order();
    let path = out.join("final.png");
    save_png(&path, &image)?;
    println!("wrote {}", path.display());
    Ok(())
}

/// Builds the world, adds the user system, runs `steps` steps and draws the
/// last frame at `frame` pixels.
fn run_demo(steps: u64, frame: (u32, u32)) -> Result<(App, RgbaImage), Box<dyn Error>> {
    let mut app = build_world()?;
    // A user system, ordered against the pipeline by label: after the foot
    // IK, when this step's pose is final, and before the terrain set. Without
    // the `before`, ties resolve by insertion order and it would run last.
    app.world.insert_resource(ComLog::default());
    app.add_system("log_com", log_com_each_second)
        .after(labels::FOOT_IK)
        .before(labels::SET_TERRAIN);
    app.schedule.build()?;
    run_steps(&mut app, steps)?;
    let image = render_final_frame(&app.world, frame)?;
    Ok((app, image))
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

/// Resource of the `log_com` system: `(seconds, centre of mass)` of each
/// walker at every whole second.
#[derive(Default)]
struct ComLog(Vec<(f64, Vec3)>);

/// User system: prints each walker's centre of mass at every whole second,
/// and keeps it in [`ComLog`].
fn log_com_each_second(world: &mut World) {
    let time = *world.resource::<Time>();
    let steps_per_second = (1.0 / f64::from(time.dt)).round() as u64;
    if !time.step.is_multiple_of(steps_per_second) {
        return;
    }
    let mut log = world.resource_mut::<ComLog>();
    for (name, pose, body) in world
        .query::<(&CharacterName, &Pose, &CharacterBody)>()
        .iter()
    {
        let com = pose.center_of_mass(body);
        println!(
            "t = {:4.1} s  {}: COM ({:.2}, {:.2}, {:.2})",
            time.elapsed, name.0, com.x, com.y, com.z
        );
        log.0.push((time.elapsed, com));
    }
}

/// Draws the world with [`WorldView`]: the camera looks down and back along
/// the trail from ahead of the first walker.
fn render_final_frame(world: &World, frame: (u32, u32)) -> Result<RgbaImage, Box<dyn Error>> {
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
        width: frame.0,
        height: frame.1,
        ..ViewSettings::default()
    };
    Ok(WorldView::new(world, rig, &settings)?.render(world, 0.0)?)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The user system runs between the foot IK and the terrain set, logs
    /// the walker once a second as it walks forward, and the frame shows the
    /// ground lit and shaded (not one flat colour).
    #[test]
    fn the_demo_logs_a_walker_moving_forward_and_draws_it() {
        let (app, image) = run_demo(150, (96, 54)).unwrap();
        let order = app.schedule.order();
        let position = |name: &str| order.iter().position(|s| *s == name).unwrap();
        assert!(position(labels::FOOT_IK) < position("log_com"));
        assert!(position("log_com") < position(labels::CARVE));

        let log = &app.world.resource::<ComLog>().0;
        let times: Vec<f64> = log.iter().map(|(t, _)| t.round()).collect();
        assert_eq!(times, [0.0, 1.0, 2.0]);
        let walked = log[2].1.x - log[1].1.x;
        assert!((0.5..2.5).contains(&walked), "walked {walked} m in 1 s");

        let colours: std::collections::BTreeSet<[u8; 4]> = image.pixels().map(|p| p.0).collect();
        assert!(colours.len() > 200, "{} colours", colours.len());
    }
}
