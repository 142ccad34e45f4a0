//! A custom terrain system and a user material, added to the pipeline's
//! schedule without editing it.
//!
//! - `wet-sand`: a material added as data to the `MaterialTable`;
//! - `rain`: a system placed after `settle` and before `refit` (so the foot
//!   rays of the next step see its change through the BVH). It slowly fills
//!   footprints: inside the windows the feet have trodden, every sample lower
//!   than the mean of its four neighbours is raised at the rain's rate (mass
//!   is added) through `GroundState::edit_heights`, which records the
//!   changed rectangle and the added volume. Its work follows the trodden
//!   area, never the terrain size;
//! - a third run also drops a pipeline system by name
//!   (`schedule.remove(labels::SETTLE)`): wet sand holds steep print walls.
//!
//! The same walk is run three times and the print depths are printed.
//!
//! ```text
//! cargo run --release -p demos --example custom_terrain_system [OUT_DIR]
//! ```
//!
//! Writes `prints.csv` (one row per run) to `OUT_DIR`
//! (default `target/examples/custom_terrain_system/`).

mod common;

use std::collections::BTreeSet;
use std::error::Error;

use engine::ecs::World;
use engine::geom::{GridRect, HeightGrid};
use engine::io::write_bytes_atomic;
use engine::schedule::{App, Time};
use glam::{Vec2, Vec3};
use softwalk_systems::character::{CharacterDesc, WalkPath};
use softwalk_systems::sim::{GroundState, SimBuilder, labels, run_steps};
use softwalk_systems::terrain::{
    DISTURBED_PRESSED, DirtyRects, GaitResponse, Heightfield, MaterialTable, TerrainMaterial,
    generate,
};

/// Fixed step: 60 Hz.
const DT: f32 = 1.0 / 60.0;
/// Steps of each run (5 s).
const STEPS: u64 = 300;
/// Rain rate, metres of height per second in a print's floor (a heavy,
/// sped-up downpour, so the effect shows within a few seconds).
const RAIN_RATE: f32 = 0.01;

/// Resource of the `rain` system: its rate, the windows trodden so far and the
/// volume it added.
struct Rain {
    /// Metres per second.
    rate: f32,
    /// Grid windows the feet changed, merged where they overlap or touch.
    windows: DirtyRects,
    /// Cubic metres added so far.
    added_volume: f64,
}

impl Rain {
    fn new(rate: f32) -> Self {
        Rain {
            rate,
            windows: DirtyRects::new(),
            added_volume: 0.0,
        }
    }
}

/// System `rain`: fills the footprints a little each step (see the file's doc).
fn rain_system(world: &mut World) {
    let dt = world.resource::<Time>().dt;
    let mut rain = world.resource_mut::<Rain>();
    let Some(mut ground) = world.get_resource_mut::<GroundState>() else {
        return;
    };
    // What carve/smooth/settle changed this step, and the samples under a
    // planted sole (the foot holds them; leave them alone).
    rain.windows.extend(&ground.changes().rects);
    let held: BTreeSet<usize> = ground.changes().held.all().iter().copied().collect();
    let fill = rain.rate * dt;
    let before = ground.volume();
    let windows: Vec<GridRect> = rain.windows.iter().collect();
    for window in windows {
        // Raises are computed from the heights before this pass (no order
        // dependence), then applied; the ground records the rectangle and
        // the volume.
        let raises = fill_raises(ground.terrain().grid(), window, fill, &held);
        if raises.is_empty() {
            continue;
        }
        let nx = ground.terrain().grid().nx();
        let mut next = raises.iter().peekable();
        ground.edit_heights(window, |i, j, h| {
            if let Some(&(_, dh)) = next.next_if(|r| r.0 == j * nx + i) {
                *h += dh;
            }
        });
    }
    rain.added_volume += ground.volume() - before;
}

/// Per sample of `window` (grid border excluded) lower than its four
/// neighbours' mean and not held by a foot: `(index, raise)`, the raise
/// capped by `fill` and by the gap to the mean.
fn fill_raises(
    grid: &HeightGrid,
    window: GridRect,
    fill: f32,
    held: &BTreeSet<usize>,
) -> Vec<(usize, f32)> {
    let (nx, nz) = (grid.nx(), grid.nz());
    let inner = window.intersect(&GridRect::new(1, 1, nx - 1, nz - 1));
    inner
        .iter()
        .filter_map(|(i, j)| {
            let k = grid.index(i, j);
            let h = grid.height(i, j);
            let mean = 0.25
                * (grid.height(i - 1, j)
                    + grid.height(i + 1, j)
                    + grid.height(i, j - 1)
                    + grid.height(i, j + 1));
            (h < mean && !held.contains(&k)).then(|| (k, fill.min(mean - h)))
        })
        .collect()
}

/// The user material, as data: deeper and more compacting than dry sand,
/// holding steeper walls, a little slower to walk on.
fn wet_sand() -> TerrainMaterial {
    TerrainMaterial {
        name: "wet-sand".into(),
        depth: 0.8,
        compression: 0.7,
        smoothness: 1.0,
        repose_deg: 55.0,
        layer: 0.08,
        gait: GaitResponse {
            speed_scale: 0.9,
            step_length_scale: 0.95,
            extra_clearance: 0.03,
        },
    }
}

/// The pipeline as shipped, with rain added, or with rain and without settling.
#[derive(Debug, Clone, Copy)]
enum Variant {
    Pipeline,
    Rain,
    RainWithoutSettle,
}

impl Variant {
    const ALL: [Variant; 3] = [Variant::Pipeline, Variant::Rain, Variant::RainWithoutSettle];

    fn label(self) -> &'static str {
        match self {
            Variant::Pipeline => "pipeline",
            Variant::Rain => "pipeline + rain",
            Variant::RainWithoutSettle => "pipeline + rain - settle",
        }
    }
}

/// A flat 6 x 3 m field of wet sand, an adult walking 4.5 m along +X, and the
/// schedule changes of `variant`.
fn build(variant: Variant) -> Result<App, Box<dyn Error>> {
    let mut table = MaterialTable::with_presets();
    let wet = table.add(wet_sand())?;
    let spec = generate::GridSpec {
        origin: Vec2::ZERO,
        cell: 0.02,
        nx: 301,
        nz: 151,
    };
    let terrain = Heightfield::from_grid(generate::flat(spec, 1.0)?, table, wet)?;
    let mut sim = SimBuilder::new(DT)?;
    sim.terrain(terrain)?;
    let path = WalkPath::straight(Vec3::new(0.5, 0.0, 1.5), Vec3::X, 4.5)?;
    sim.character("walker", CharacterDesc::adult(), path)?;
    let mut app = sim.build()?;

    if matches!(variant, Variant::Rain | Variant::RainWithoutSettle) {
        app.world.insert_resource(Rain::new(RAIN_RATE));
        app.add_system("rain", rain_system)
            .after(labels::SETTLE)
            .before(labels::REFIT);
    }
    if matches!(variant, Variant::RainWithoutSettle) {
        // Constraints naming `settle` are dropped with it: `rain` keeps its
        // place before `refit`.
        app.schedule.remove(labels::SETTLE)?;
    }
    app.schedule.build()?;
    Ok(app)
}

/// Print depths of a run: mean and deepest, over the samples a sole pressed,
/// measured from the height before the walk.
struct PrintDepths {
    mean: f32,
    deepest: f32,
    pressed: usize,
}

fn measure(before: &HeightGrid, after: &Heightfield) -> PrintDepths {
    let depths: Vec<f32> = after
        .disturbed()
        .iter()
        .zip(before.heights().iter().zip(after.grid().heights()))
        .filter(|(mark, _)| **mark == DISTURBED_PRESSED)
        .map(|(_, (h0, h))| h0 - h)
        .collect();
    let pressed = depths.len();
    PrintDepths {
        mean: depths.iter().sum::<f32>() / pressed.max(1) as f32,
        deepest: depths.iter().copied().fold(0.0, f32::max),
        pressed,
    }
}

fn main() -> Result<(), Box<dyn Error>> {
    let out = common::output_dir("custom_terrain_system")?;
    let mut csv = String::from("run,mean_depth_m,deepest_m,pressed_samples,rain_volume_m3\n");
    for variant in Variant::ALL {
        let walk = walk(variant, STEPS)?;
        println!("{}: {}", variant.label(), walk.order.join(" -> "));
        let depths = &walk.depths;
        println!(
            "  mean print depth {:.1} cm, deepest {:.1} cm over {} pressed samples; rain added {:.2} L\n",
            100.0 * depths.mean,
            100.0 * depths.deepest,
            depths.pressed,
            1000.0 * walk.rained
        );
        csv += &format!(
            "{},{:.5},{:.5},{},{:.6}\n",
            variant.label(),
            depths.mean,
            depths.deepest,
            depths.pressed,
            walk.rained
        );
    }
    let path = out.join("prints.csv");
    write_bytes_atomic(&path, csv.as_bytes())?;
    println!("wrote {}", path.display());
    Ok(())
}

/// What one run of a variant shows: its system order, its prints and the
/// volume the rain added (cubic metres).
struct Walk {
    order: Vec<String>,
    depths: PrintDepths,
    rained: f64,
}

/// Builds `variant` and walks it for `steps` steps.
fn walk(variant: Variant, steps: u64) -> Result<Walk, Box<dyn Error>> {
    let mut app = build(variant)?;
    let order = app.schedule.order().iter().map(|s| s.to_string()).collect();
    let before = terrain_of(&app.world, |hf| hf.grid().clone())?;
    run_steps(&mut app, steps)?;
    let depths = terrain_of(&app.world, |hf| measure(&before, hf))?;
    let rained = app
        .world
        .get_resource::<Rain>()
        .map_or(0.0, |r| r.added_volume);
    Ok(Walk {
        order,
        depths,
        rained,
    })
}

/// Runs `f` on the world's terrain.
fn terrain_of<T>(world: &World, f: impl FnOnce(&Heightfield) -> T) -> Result<T, Box<dyn Error>> {
    let ground = world
        .get_resource::<GroundState>()
        .ok_or("the world has no terrain")?;
    Ok(f(ground.terrain()))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Rain sits between `settle` and `refit` (and before `refit` once
    /// `settle` is removed), adds volume, and makes the prints shallower.
    #[test]
    fn rain_fills_the_prints_and_settle_can_be_removed() {
        let [pipeline, rain, no_settle] = Variant::ALL.map(|v| walk(v, 150).unwrap());
        let has = |walk: &Walk, name: &str| walk.order.iter().any(|s| s == name);
        let runs_before = |walk: &Walk, first: &str, then: &str| {
            let position = |name| walk.order.iter().position(|s| s == name).unwrap();
            position(first) < position(then)
        };
        assert!(!has(&pipeline, "rain"));
        assert!(runs_before(&rain, labels::SETTLE, "rain"));
        assert!(runs_before(&rain, "rain", labels::REFIT));
        assert!(!has(&no_settle, labels::SETTLE));
        assert!(runs_before(&no_settle, "rain", labels::REFIT));

        assert!(
            pipeline.depths.pressed > 100,
            "{} pressed",
            pipeline.depths.pressed
        );
        assert!(pipeline.depths.mean > 0.01, "mean {}", pipeline.depths.mean);
        assert_eq!(pipeline.rained, 0.0);
        assert!(rain.rained > 0.0 && no_settle.rained > 0.0);
        assert!(
            rain.depths.mean < 0.8 * pipeline.depths.mean,
            "rain {} vs {}",
            rain.depths.mean,
            pipeline.depths.mean
        );
    }
}
