//! Snapshot tests on rendered frames (goldens in `tests/snapshots/`).
//!
//! - the built-in `default` scene's first second, through the real run
//!   (`softwalk_app::runner::run`: scene -> pipeline -> `SceneView` with overlays);
//! - a lit bumpy height grid with a real footprint, a mesh and grass blades,
//!   through the engine's renderer alone.
//!
//! `UPDATE_SNAPSHOTS=1 cargo test -p softwalk_tests --test snapshot_scene`
//! blesses intended changes; with `CI` set a missing golden fails.

use std::f32::consts::PI;

use engine::geom::HeightGrid;
use engine::render::{
    Camera, FrameScene, GrassBlade, Lighting, MeshInstance, Renderer, SampleColors, Sun,
    TerrainRenderer, TerrainStyle,
};
use engine::snapshot::Tolerance;
use glam::{Mat4, Vec2, Vec3};
use image::RgbaImage;
use softwalk_app::output::LastFrame;
use softwalk_app::runner::{RunOptions, run};
use softwalk_app::scene::Scene;
use softwalk_systems::character::capsule;
use softwalk_systems::terrain::{FootPrint, FootSize, Heightfield, MaterialTable, plant_foothold};

/// Pixels past the colour threshold that may still differ: room for last-bit
/// float differences between machines, far below any real change.
const TOLERANCE: Tolerance = Tolerance {
    threshold: 0.1,
    max_diff_pixels: 24,
};

/// The last frame of the default scene's first 60 steps, drawn at 200 x 112
/// every 2nd step (the follow camera moves as in a real run) with `threads`.
fn default_scene_frame(threads: usize) -> RgbaImage {
    default_scene_after(60, (200, 112), threads)
}

/// The last frame of the default scene's first `steps` steps at `size`,
/// drawn every 2nd step with `threads`.
fn default_scene_after(steps: u64, size: (u32, u32), threads: usize) -> RgbaImage {
    let scene = Scene::builtin("default").expect("built-in scene");
    let options = RunOptions {
        steps,
        width: size.0,
        height: size.1,
        render_every: 2,
        threads,
        ..RunOptions::from_scene(&scene)
    };
    let mut last = LastFrame::default();
    run(&scene, &options, &mut last).expect("the default scene runs");
    last.into_image().expect("frames were rendered")
}

#[test]
fn default_scene_first_second_matches_its_golden() {
    let image = default_scene_frame(1);
    assert_eq!(image.dimensions(), (200, 112));
    engine::snapshot!("default_scene_first_second")
        .tolerance(TOLERANCE)
        .assert_matches(&image);
}

#[test]
fn default_scene_first_frame_shows_the_skinned_human() {
    let image = default_scene_after(1, (320, 180), 1);
    engine::snapshot!("default_scene_first_frame_human")
        .tolerance(TOLERANCE)
        .assert_matches(&image);
}

#[test]
fn default_scene_frame_is_the_same_on_two_threads() {
    assert!(default_scene_frame(1) == default_scene_frame(2));
}

/// A 3 x 3 m bumpy sand grid with one real footprint (planted through the
/// terrain stages), its disturbed mask darkening the print.
fn printed_bumpy_ground() -> Heightfield {
    let grid = HeightGrid::from_fn(Vec2::ZERO, 0.02, 151, 151, |x, z| {
        0.5 + 0.06 * (2.1 * x).sin() * (1.7 * z).cos() + 0.03 * (5.3 * x + 1.1 * z).sin()
    })
    .expect("valid grid");
    let table = MaterialTable::with_presets();
    let sand = table.id("sand").expect("sand preset");
    let mut hf = Heightfield::from_grid(grid, table, sand).expect("valid terrain");
    let mut print = FootPrint::new();
    plant_foothold(
        &mut hf,
        &mut print,
        Vec2::new(1.3, 1.5),
        Vec2::X,
        FootSize::default(),
        18,
        1.0 / 60.0,
    )
    .expect("the foot lands on the grid");
    hf
}

/// Blades on a 0.6 x 0.5 m patch, from a fixed linear congruential sequence.
fn grass_blades(ground: &HeightGrid) -> Vec<GrassBlade> {
    let mut state = 0x2545_f491_u32;
    let mut next = move || {
        state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
        (state >> 8) as f32 / (1u32 << 24) as f32
    };
    (0..220)
        .map(|_| {
            let (x, z) = (1.9 + 0.6 * next(), 1.6 + 0.5 * next());
            let root = Vec3::new(x, ground.height_at(x, z).expect("on the grid"), z);
            let height = 0.28 + 0.12 * next();
            let lean = Vec3::new(0.12 * (next() - 0.5), 0.0, 0.12 * (next() - 0.5));
            GrassBlade {
                root,
                mid: root + Vec3::Y * (0.5 * height) + 0.3 * lean,
                tip: root + Vec3::Y * height + lean,
                width: 0.012,
                color: Vec3::new(0.22, 0.42 + 0.1 * next(), 0.12),
            }
        })
        .collect()
}

#[test]
fn lit_bumpy_ground_with_print_mesh_and_blades_matches_its_golden() {
    let hf = printed_bumpy_ground();
    let grid = hf.grid();
    let albedo = vec![Vec3::new(0.72, 0.58, 0.36); grid.nx() * grid.nz()];
    let disturbed: Vec<f32> = hf
        .disturbed()
        .iter()
        .map(|&d| f32::from(d) / 255.0)
        .collect();
    let colors = SampleColors {
        nx: grid.nx(),
        albedo: &albedo,
        disturbed: &disturbed,
    };
    // A low sun from behind the print, so its walls cast shadows.
    let lighting = Lighting {
        sun: Sun::from_angles(0.8 * PI, 0.35, Vec3::new(1.0, 0.95, 0.85), Vec3::splat(0.2)),
        ..Lighting::default()
    };
    let mut terrain = TerrainRenderer::new(grid, TerrainStyle::default()).expect("renderer");
    terrain
        .update(grid, &colors, &lighting)
        .expect("lit terrain");

    let post = capsule(0.07, 0.35);
    let base = Vec3::new(0.95, grid.height_at(0.95, 1.25).expect("on the grid"), 1.25);
    let meshes = [MeshInstance::new(
        &post,
        Mat4::from_translation(base),
        Vec3::new(0.7, 0.25, 0.2),
    )];
    let blades = grass_blades(grid);
    let scene = FrameScene {
        terrain: Some(&terrain),
        meshes: &meshes,
        blades: &blades,
        lighting,
        shadows: true,
    };
    let camera = Camera::perspective(0.8, 192, 144, 0.05, 50.0)
        .expect("camera")
        .look_at(
            Vec3::new(1.5, 1.55, 2.9),
            Vec3::new(1.55, 0.5, 1.55),
            Vec3::Y,
        );
    let image = Renderer::new(192, 144)
        .expect("renderer")
        .render(&scene, &camera);
    engine::snapshot!("bumpy_ground_print_mesh_blades")
        .tolerance(TOLERANCE)
        .assert_matches(&image);
}
