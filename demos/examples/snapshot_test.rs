//! How to write a snapshot test on a rendered PNG.
//!
//! Renders a small frame (160 x 96) of a tiny scene — a snow field, one walker,
//! a fixed camera — after one simulated second, and compares it with the golden
//! `tests/snapshots/example_tiny_scene.png` through `engine::snapshot`.
//!
//! ```text
//! cargo run --release -p demos --example snapshot_test
//! UPDATE_SNAPSHOTS=1 cargo run --release -p demos --example snapshot_test   # bless a change
//! ```
//!
//! - The first run without a golden writes it (and says so on stderr): look at
//!   it, then commit it.
//! - `UPDATE_SNAPSHOTS=1` replaces a golden that differs (an intended change).
//! - With `CI` set, a missing golden is a failure, so CI never blesses itself.
//! - On a mismatch, `actual.png`, `expected.png` and `diff.png` are written
//!   under `target/snapshots/example_tiny_scene/` and the error names them.
//!
//! In a test file the same check is one line:
//! `engine::snapshot!("name").tolerance(..).assert_matches(&image)` (it panics
//! with the report); see `tests/tests/snapshot_scene.rs`.

use std::error::Error;
use std::path::Path;

use engine::snapshot::{Outcome, Snapshot, Tolerance};
use image::RgbaImage;
use softwalk_app::scene::Scene;
use softwalk_app::view::scene_view;
use softwalk_systems::sim::run_steps;

/// The scene, as a scene file would hold it (`softwalk scenes --dump default`
/// prints a complete one).
const TINY_SCENE: &str = r#"
name = "tiny"
description = "A few steps on a snow field"

[terrain]
size_x = 4.0
size_z = 2.0
resolution = 160
max_height = 2.0
material = "snow"
shape = { kind = "flat" }

[sim]
duration = 1.0
dt = 0.016666668

[camera]
fov_deg = 45.0
mode = { kind = "fixed", eye = [2.3, 1.4, 3.0], target = [0.9, 0.55, 1.0] }

[render]
width = 160
height = 96
every = 2
overlays = false

[[characters]]
name = "walker"
body = { height = 1.75, mass = 70.0 }
path = { kind = "straight", start = [0.4, 1.0], heading_deg = 0.0, length = 3.0 }
"#;

fn main() {
    // Report errors with their message (a mismatch names the artifact files).
    if let Err(e) = run() {
        eprintln!("error: {e}");
        std::process::exit(1);
    }
}

fn run() -> Result<(), Box<dyn Error>> {
    let check = tiny_scene_check();
    match check.check(&tiny_scene_frame()?)? {
        Outcome::Identical => println!("identical to {}", check.golden_path().display()),
        Outcome::WithinTolerance { diff_pixels, .. } => {
            println!("matches within tolerance ({diff_pixels} pixels differ)")
        }
        Outcome::Created(path) => {
            println!("new golden {}: look at it, then commit it", path.display())
        }
        Outcome::Updated(path) => println!("golden {} updated", path.display()),
    }
    Ok(())
}

/// The tiny scene's frame after its one simulated second.
fn tiny_scene_frame() -> Result<RgbaImage, Box<dyn Error>> {
    let scene = Scene::from_toml_str(TINY_SCENE, Path::new(""))?;
    let (mut app, walkers) = scene.build_sim()?;
    run_steps(&mut app, scene.steps())?;

    // Rendering reads the world and never changes it. One thread or many
    // give the same pixels.
    let mut view = scene_view(
        &scene,
        &app.world,
        &walkers,
        scene.render.width,
        scene.render.height,
        1,
    )?;
    Ok(view.render(&app.world, scene.sim.dt)?)
}

/// The golden check of the tiny scene. The tolerance absorbs last-bit
/// differences between machines: a pixel counts only past a YIQ delta of
/// 0.1, anti-aliased edges are forgiven, and up to 16 pixels may still differ.
fn tiny_scene_check() -> Snapshot {
    engine::snapshot!("example_tiny_scene").tolerance(Tolerance {
        threshold: 0.1,
        max_diff_pixels: 16,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The example passes against the committed golden (in a test, a
    /// mismatch panics with the paths of the actual, expected and diff PNGs).
    #[test]
    fn the_tiny_scene_matches_its_committed_golden() {
        assert!(tiny_scene_check().golden_path().exists());
        tiny_scene_check().assert_matches(&tiny_scene_frame().unwrap());
    }
}
