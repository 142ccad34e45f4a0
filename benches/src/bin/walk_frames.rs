//! Frame time of a scene's walk: the scene is simulated and every `every`-th
//! step drawn by its `WorldView` (terrain re-lit where it changed, shadows,
//! drawing, overlays); prints the median, quartiles and mean per frame (wall
//! time), the median CPU time per frame (all threads of the process, which a
//! loaded machine does not inflate on one thread), then
//! (unless `once`) walks again on the other thread count (1 or 2) and says
//! whether every frame came out byte for byte the same. The digest of all
//! frames tells whether a change to the renderer changed any pixel.
//!
//! ```text
//! cargo run --release -p benches --bin walk_frames -- [SCENE] [THREADS] [once]
//! ```

use std::collections::hash_map::DefaultHasher;
use std::hash::{Hash, Hasher};
use std::time::Instant;

use softwalk_app::scene::Scene;
use softwalk_app::view::scene_view;
use softwalk_systems::sim::step;

/// CPU time the process's threads have run so far, in nanoseconds (Linux
/// `/proc/self/task/*/schedstat`); 0 where that is not available.
fn process_cpu_ns() -> u64 {
    let Ok(tasks) = std::fs::read_dir("/proc/self/task") else {
        return 0;
    };
    tasks
        .flatten()
        .filter_map(|task| std::fs::read_to_string(task.path().join("schedstat")).ok())
        .filter_map(|stat| stat.split_whitespace().next()?.parse::<u64>().ok())
        .sum()
}

/// Per frame of a walk: wall time (ms), CPU time (ms) and the image's hash.
#[derive(Default)]
struct Walk {
    wall: Vec<f64>,
    cpu: Vec<f64>,
    hashes: Vec<u64>,
}

/// Frame times and frame hashes of one walk drawn on `threads` threads.
fn walk(scene: &Scene, threads: usize) -> Result<Walk, Box<dyn std::error::Error>> {
    let (mut app, walkers) = scene.build_sim()?;
    let (w, h) = (scene.render.width, scene.render.height);
    let mut view = scene_view(scene, &app.world, &walkers, w, h, threads)?;
    let dt = scene.sim.dt * scene.render.every as f32;
    let mut walk = Walk::default();
    for k in 0..scene.steps() {
        step(&mut app)?;
        if k % u64::from(scene.render.every) != 0 {
            continue;
        }
        let (start, cpu) = (Instant::now(), process_cpu_ns());
        let image = view.render(&app.world, dt)?;
        walk.wall.push(start.elapsed().as_secs_f64() * 1e3);
        walk.cpu.push((process_cpu_ns() - cpu) as f64 * 1e-6);
        let mut hasher = DefaultHasher::new();
        image.as_raw().hash(&mut hasher);
        walk.hashes.push(hasher.finish());
    }
    Ok(walk)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let name = args.next().unwrap_or_else(|| "default".into());
    let threads: usize = args.next().map_or(Ok(1), |t| t.parse())?;
    let scene = Scene::builtin(&name)?;
    let Walk {
        mut wall,
        mut cpu,
        hashes,
    } = walk(&scene, threads)?;
    let other = match args.next().as_deref() {
        Some("once") => hashes.clone(),
        _ => walk(&scene, if threads == 1 { 2 } else { 1 })?.hashes,
    };
    let mean = wall.iter().sum::<f64>() / wall.len() as f64;
    let [median, low, high] = quantiles(&mut wall, [0.5, 0.25, 0.75]);
    let [cpu_median] = quantiles(&mut cpu, [0.5]);
    let mut digest = DefaultHasher::new();
    hashes.hash(&mut digest);
    println!(
        "{name}: {} frames {}x{}, {threads} thread(s): median {median:.2} ms (quartiles {low:.2}-{high:.2}, mean {mean:.2}), CPU median {cpu_median:.2} ms; frames identical on 1 and 2 threads: {}; digest {:016x}",
        wall.len(),
        scene.render.width,
        scene.render.height,
        hashes == other,
        digest.finish(),
    );
    Ok(())
}

/// The `fractions` quantiles of `values` (sorted in place).
fn quantiles<const N: usize>(values: &mut [f64], fractions: [f64; N]) -> [f64; N] {
    values.sort_by(f64::total_cmp);
    fractions.map(|f| values[((values.len() - 1) as f64 * f) as usize])
}
