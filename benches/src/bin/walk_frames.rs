//! Frame time of a scene's walk: the scene is simulated and every `every`-th
//! step drawn by its `WorldView` (terrain re-lit where it changed, shadows,
//! drawing, overlays); prints the median, quartiles and mean per frame, then
//! (unless `once`) walks again on the other thread count (1 or 2) and says
//! whether every frame came out byte for byte the same.
//!
//! ```text
//! cargo run --release -p benches --bin walk_frames -- [SCENE] [THREADS] [once]
//! ```

use std::collections::hash_map::DefaultHasher;
use std::hash::{Hash, Hasher};
use std::time::Instant;

use demos::scene::Scene;
use demos::view::scene_view;
use softwalk_systems::sim::step;

/// Frame times (ms) and frame hashes of one walk drawn on `threads` threads.
fn walk(scene: &Scene, threads: usize) -> Result<(Vec<f64>, Vec<u64>), Box<dyn std::error::Error>> {
    let (mut app, walkers) = scene.build_sim()?;
    let (w, h) = (scene.render.width, scene.render.height);
    let mut view = scene_view(scene, &app.world, &walkers, w, h, threads)?;
    let dt = scene.sim.dt * scene.render.every as f32;
    let (mut times, mut hashes) = (Vec::new(), Vec::new());
    for k in 0..scene.steps() {
        step(&mut app)?;
        if k % u64::from(scene.render.every) != 0 {
            continue;
        }
        let start = Instant::now();
        let image = view.render(&app.world, dt)?;
        times.push(start.elapsed().as_secs_f64() * 1e3);
        let mut hasher = DefaultHasher::new();
        image.as_raw().hash(&mut hasher);
        hashes.push(hasher.finish());
    }
    Ok((times, hashes))
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let name = args.next().unwrap_or_else(|| "default".into());
    let threads: usize = args.next().map_or(Ok(1), |t| t.parse())?;
    let scene = Scene::builtin(&name)?;
    let (mut times, hashes) = walk(&scene, threads)?;
    let other = match args.next().as_deref() {
        Some("once") => hashes.clone(),
        _ => walk(&scene, if threads == 1 { 2 } else { 1 })?.1,
    };
    times.sort_by(f64::total_cmp);
    let q = |f: f64| times[((times.len() - 1) as f64 * f) as usize];
    let mean = times.iter().sum::<f64>() / times.len() as f64;
    println!(
        "{name}: {} frames {}x{}, {threads} thread(s): median {:.2} ms (quartiles {:.2}-{:.2}, mean {mean:.2}); frames identical on 1 and 2 threads: {}",
        times.len(),
        scene.render.width,
        scene.render.height,
        q(0.5),
        q(0.25),
        q(0.75),
        hashes == other,
    );
    Ok(())
}
