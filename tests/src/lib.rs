//! Shared helpers for the integration tests in `tests/tests/`: small scenes
//! built on the full pipeline (`softwalk_systems::sim`), walked and measured.
//! It also compiles the Rust blocks of the README and the tutorial as doctests.

pub mod glb_writer;
pub mod rig_variants;
pub mod sole_contact;
pub mod stop_figures;

use engine::schedule::App;
use glam::{Vec2, Vec3};
use softwalk_systems::character::{CharacterDesc, WalkPath};
use softwalk_systems::sim::{SimBuilder, WalkerMetrics, run_steps};
use softwalk_systems::terrain::{Heightfield, MaterialTable, generate};
use softwalk_systems::vegetation::{GrassSettings, XzRect};

/// The fixed step of every test scene.
pub const DT: f32 = 1.0 / 60.0;

pub use softwalk_app::paper::variants::rigid_material as rigid;

/// What a test scene is made of.
#[derive(Clone)]
pub struct TestScene {
    /// Material of the whole terrain (a preset name or "rigid").
    pub material: &'static str,
    /// Terrain slope along +X, degrees.
    pub slope_deg: f32,
    /// Grass over the walk, if any.
    pub grass: Option<GrassSettings>,
    /// The walker.
    pub body: CharacterDesc,
    /// Balance controller on or off.
    pub controller: bool,
}

impl TestScene {
    /// Flat ground of `material`, an adult walking along +X.
    pub fn flat(material: &'static str) -> Self {
        TestScene {
            material,
            slope_deg: 0.0,
            grass: None,
            body: CharacterDesc::adult(),
            controller: true,
        }
    }
}

/// Terrain: 9 x 3 m at 2 cm, origin (0, 0); the walk starts at (1, 1.5) heading +X for 6 m.
pub fn build(scene: &TestScene) -> App {
    let mut table = MaterialTable::with_presets();
    table.add(rigid()).unwrap();
    let id = table.id(scene.material).unwrap();
    let spec = generate::GridSpec {
        origin: Vec2::ZERO,
        cell: 0.02,
        nx: 451,
        nz: 151,
    };
    let grid = generate::slope(spec, 1.0, scene.slope_deg, Vec2::X).unwrap();
    let mut sim = SimBuilder::new(DT).unwrap();
    sim.terrain(Heightfield::from_grid(grid, table, id).unwrap())
        .unwrap();
    if let Some(settings) = scene.grass {
        sim.grass(
            XzRect::new(Vec2::new(0.0, 0.8), Vec2::new(9.0, 2.2)),
            settings,
        )
        .unwrap();
    }
    let path = WalkPath::straight(Vec3::new(1.0, 0.0, 1.5), Vec3::X, 6.0).unwrap();
    let walker = sim.character("walker", scene.body, path).unwrap();
    let app = sim.build().unwrap();
    app.world
        .get_mut::<softwalk_systems::character::Balance>(walker)
        .unwrap()
        .enabled = scene.controller;
    app
}

/// Runs `steps` steps and returns each step's metrics of the first character.
pub fn walk(app: &mut App, steps: usize) -> Vec<WalkerMetrics> {
    (0..steps)
        .map(|_| {
            run_steps(app, 1).unwrap();
            let mut q = app.world.query::<&WalkerMetrics>();
            *q.iter().next().unwrap()
        })
        .collect()
}

pub use softwalk_app::paper::stats::{mean, std_dev};

/// The steepest wall slope (m/m) across a print walked along +X: between
/// neighbouring samples along Z within 0.2 m of `c`, on the column through it.
pub fn steepest_wall_across(grid: &engine::geom::HeightGrid, c: Vec2) -> f32 {
    let i = grid.to_grid(c.x, c.y).round().x as usize;
    let j0 = grid.to_grid(c.x, c.y - 0.2).y as usize;
    let j1 = grid.to_grid(c.x, c.y + 0.2).y as usize;
    (j0..j1)
        .map(|j| (grid.height(i, j + 1) - grid.height(i, j)).abs() / grid.cell_size())
        .fold(0.0, f32::max)
}

/// The README's Rust blocks, compiled and run by `cargo test --doc`.
#[cfg(doctest)]
#[doc = include_str!("../../README.md")]
pub struct ReadmeDoctests;

/// The tutorial's Rust blocks, compiled (and run, unless `no_run`) by
/// `cargo test --doc`.
#[cfg(doctest)]
#[doc = include_str!("../../docs/tutorial.md")]
pub struct TutorialDoctests;

/// The world hash after `steps` steps of `scene` run on `threads` threads,
/// rendering small frames every 15 steps when `render` is set.
pub fn world_hash_after(
    scene: &softwalk_app::scene::Scene,
    steps: u64,
    render: bool,
    threads: usize,
) -> u64 {
    use softwalk_app::runner::{RunOptions, run};
    let mut options = RunOptions::from_scene(scene);
    options.steps = steps;
    options.render = render;
    options.width = 96;
    options.height = 54;
    options.render_every = 15;
    options.threads = threads;
    options.hash = true;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("a thread pool");
    let summary = pool
        .install(|| run(scene, &options, &mut ()))
        .expect("the scene runs");
    summary.world_hash.expect("a hash was asked for")
}

/// A walker of `height` metres (mass by the square of the height, a body
/// mass index of 22) walking at Froude number `froude`.
pub fn walker_body(height: f32, froude: f32) -> CharacterDesc {
    CharacterDesc {
        froude,
        ..CharacterDesc::new(height, 22.0 * height * height)
    }
}
