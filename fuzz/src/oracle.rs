//! What one input does: a scene is parsed and validated and, when accepted,
//! built and stepped a few times in-process; a heightmap PNG is loaded alone
//! and as a scene's terrain; an OBJ is loaded and put into a BVH. Inputs over
//! the per-input memory budget are skipped before anything is allocated.

use std::path::Path;

use engine::geom::{MeshBvh, Ray};
use engine::glam::Vec3;
use softwalk_app::cli::error_line;
use softwalk_app::memory_estimate::MemoryEstimate;
use softwalk_app::runner::RunOptions;
use softwalk_app::scene::Scene;

use crate::png_input::declared_pixels;

/// Memory one input may need, bytes: an estimate above it is skipped.
pub const INPUT_BUDGET: u64 = 256 << 20;
/// Steps an accepted scene is run for.
pub const STEPS: u64 = 3;
/// Pixels a heightmap's header may declare before it is skipped (the loader allows 8192 x 8192).
pub const MAX_INPUT_PIXELS: u64 = 4 << 20;
/// Heaviest accepted scene that is stepped (grid samples plus grass blades); heavier
/// scenes are validated but their terrain is coarsened before the steps, to keep
/// the campaign fast.
pub const MAX_STEPPED_WORK: u64 = 300_000;

/// One fuzz input.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Input {
    /// A scene file's text.
    Scene(String),
    /// A heightmap PNG's bytes.
    Heightmap(Vec<u8>),
    /// An OBJ file's text.
    Obj(String),
}

impl Input {
    /// The file extension inputs of this kind are saved with.
    pub fn extension(&self) -> &'static str {
        match self {
            Input::Scene(_) => "toml",
            Input::Heightmap(_) => "png",
            Input::Obj(_) => "obj",
        }
    }

    /// The bytes saved for this input.
    pub fn bytes(&self) -> &[u8] {
        match self {
            Input::Scene(t) | Input::Obj(t) => t.as_bytes(),
            Input::Heightmap(b) => b,
        }
    }

    /// An input read back from a file, by extension (`None` for other files).
    pub fn from_file(path: &Path) -> Option<Input> {
        let bytes = std::fs::read(path).ok()?;
        let text = || String::from_utf8_lossy(&bytes).into_owned();
        match path.extension()?.to_str()? {
            "toml" => Some(Input::Scene(text())),
            "obj" => Some(Input::Obj(text())),
            "png" => Some(Input::Heightmap(bytes.clone())),
            _ => None,
        }
    }
}

/// How an input ended (a panic is caught by the caller).
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Outcome {
    /// A loader or validation refused it with an error.
    Rejected,
    /// Accepted, and the steps ran (or the mesh was built and cast against).
    Accepted,
    /// Accepted, but over the per-input memory budget: not run.
    OverBudget,
    /// Accepted by validation, then refused while building or stepping: a defect.
    FailedMidRun(String),
}

/// A scene whose terrain is the heightmap `h.png` in the scene's folder.
const HEIGHTMAP_SCENE: &str = r#"name = "fuzz-heightmap"
[terrain]
size_x = 8.0
size_z = 8.0
resolution = 64
max_height = 10.0
material = "sand"
shape = { kind = "heightmap", path = "h.png", height_scale = 2.0 }
[sim]
duration = 1.0
dt = 0.02
[[characters]]
name = "a"
body = { height = 1.75, mass = 70.0 }
path = { kind = "straight", start = [1.0, 4.0], heading_deg = 0.0, length = 5.0 }
"#;

/// Runs `input`; `dir` is a private scratch folder (scene paths resolve against it).
pub fn check(input: &Input, dir: &Path) -> Outcome {
    match input {
        Input::Scene(text) => check_scene(text, dir),
        Input::Heightmap(bytes) => {
            if declared_pixels(bytes).is_some_and(|px| px > MAX_INPUT_PIXELS) {
                return Outcome::OverBudget;
            }
            let path = dir.join("h.png");
            if std::fs::write(&path, bytes).is_err() {
                return Outcome::Rejected;
            }
            let alone = engine::asset::load_heightmap(&path, 1.0, 1.0).is_ok();
            match check_scene(HEIGHTMAP_SCENE, dir) {
                Outcome::Rejected if alone => {
                    Outcome::FailedMidRun("the heightmap loads alone but not in a scene".into())
                }
                other => other,
            }
        }
        Input::Obj(text) => check_obj(text),
    }
}

fn check_scene(text: &str, dir: &Path) -> Outcome {
    let Ok(mut scene) = Scene::from_toml_str(text, dir) else {
        return Outcome::Rejected;
    };
    let options = RunOptions {
        steps: STEPS,
        render: false,
        ..RunOptions::from_scene(&scene)
    };
    if MemoryEstimate::of(&scene, &options).total() > INPUT_BUDGET {
        return Outcome::OverBudget;
    }
    coarsen(&mut scene);
    match softwalk_app::runner::run(&scene, &options, &mut ()) {
        Ok(_) => Outcome::Accepted,
        Err(e) => Outcome::FailedMidRun(error_line(&e)),
    }
}

/// Lowers the terrain resolution of a heavy scene (the scene stays valid: no
/// limit depends on the resolution but memory).
fn coarsen(scene: &mut Scene) {
    let (nx, nz) = scene.terrain.grid_samples();
    let blades: f64 = scene.grass.iter().map(|g| g.blade_count()).sum();
    if (nx * nz) as u64 + blades as u64 <= MAX_STEPPED_WORK {
        return;
    }
    let mut coarse = scene.clone();
    coarse.terrain.resolution = coarse.terrain.resolution.min(128);
    // Grass and paths are checked against the grid's extent, which a coarser grid may shorten.
    if coarse.validate().is_ok() {
        *scene = coarse;
    }
}

fn check_obj(text: &str) -> Outcome {
    let Ok(mesh) = engine::asset::load_obj_from_str(text) else {
        return Outcome::Rejected;
    };
    if mesh.triangles.len() > 4 * crate::obj_input::MAX_FACES {
        return Outcome::OverBudget;
    }
    let Ok(bvh) = MeshBvh::build(&mesh) else {
        return Outcome::Rejected;
    };
    let b = bvh.bounds();
    let centre = (b.min + b.max) * 0.5;
    for dir in [Vec3::NEG_Y, Vec3::new(0.3, -1.0, 0.2).normalize()] {
        if let Ok(ray) = Ray::new(centre - dir * 10.0, dir) {
            let _ = bvh.cast(&ray, 1e6);
        }
    }
    Outcome::Accepted
}
