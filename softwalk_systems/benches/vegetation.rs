//! Grass deformation and recovery per step with two feet walking through a
//! patch of 100k blades, and the same walk through 400k blades (same density,
//! 4x the area) to show the cost follows what the feet touch, not the patch.

use criterion::{Criterion, criterion_group, criterion_main};
use glam::{Vec2, Vec3};
use softwalk_systems::vegetation::{GrassPatch, GrassSettings, XzRect};
use std::hint::black_box;
use std::time::{Duration, Instant};

const DT: f32 = 1.0 / 60.0;
const CYCLE: f32 = 1.1;
const SPEED: f32 = 1.3;

/// Sole centres of a two-foot walk at time `t`, looping along X over `[-4, 4]`.
fn feet_at(t: f32) -> [Vec3; 2] {
    let stride = SPEED * CYCLE;
    [(0.0_f32, -0.1_f32), (0.5, 0.1)].map(|(offset, z)| {
        let u = t / CYCLE + offset;
        let (n, c) = (u.floor(), u.fract());
        let (along, lift) = if c < 0.6 {
            (0.0, 0.0)
        } else {
            let s = (c - 0.6) / 0.4;
            (s, 0.15 * (std::f32::consts::PI * s).sin())
        };
        let x = ((n + along) * stride).rem_euclid(8.0) - 4.0;
        Vec3::new(x, lift, z)
    })
}

/// CPU time this thread has run (Linux `/proc/thread-self/schedstat`, ns
/// resolution). The benchmark VM is shared by many jobs, so wall time
/// includes waiting for a core; CPU time is the cost of the step itself.
fn thread_cpu_time() -> Option<Duration> {
    let text = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    let ns: u64 = text.split_whitespace().next()?.parse().ok()?;
    Some(Duration::from_nanos(ns))
}

/// Runs `f` `iters` times; returns the thread's CPU time, or wall time where
/// CPU time is not available or the interval is too short to resolve it.
fn cpu_timed(iters: u64, mut f: impl FnMut()) -> Duration {
    let (cpu0, wall0) = (thread_cpu_time(), Instant::now());
    for _ in 0..iters {
        f();
    }
    let wall = wall0.elapsed();
    match (cpu0, thread_cpu_time()) {
        // The scheduler updates the counter at ticks: trust it only over
        // intervals much longer than a tick (criterion's samples are).
        (Some(a), Some(b)) if wall > Duration::from_millis(40) => b - a,
        _ => wall,
    }
}

fn patch(blades: f32, settings: GrassSettings) -> GrassPatch {
    let half = (blades / settings.density).sqrt() * 0.5;
    let area = XzRect::new(Vec2::splat(-half), Vec2::splat(half));
    GrassPatch::with_height_fn(area, settings, |_, _| Some(0.0)).expect("valid patch")
}

fn walk(c: &mut Criterion) {
    let mut group = c.benchmark_group("grass_deform_step");
    for (name, settings) in [
        ("small", GrassSettings::small()),
        ("medium", GrassSettings::medium()),
    ] {
        for blades in [100_000.0, 400_000.0] {
            let mut grass = patch(blades, settings);
            let mut step = 0u32;
            let label = format!("{name}/{}k_blades", blades as u32 / 1000);
            let (mut visited, mut pushed, mut reused, mut steps) = (0usize, 0usize, 0usize, 0usize);
            group.bench_function(label, |b| {
                b.iter_custom(|iters| {
                    cpu_timed(iters, || {
                        step += 1;
                        let feet = feet_at(step as f32 * DT);
                        let stats = black_box(grass.deform_points(black_box(&feet), DT));
                        visited += stats.visited;
                        pushed += stats.pushed;
                        reused += stats.reused;
                        steps += 1;
                    })
                })
            });
            let per_step = |n: usize| n as f64 / steps.max(1) as f64;
            println!(
                "  {name} {}k blades: {:.0} blades visited and {:.0} pushed per step ({:.0} of them with the field of feet \
                 standing still reused), {} recovering at the end",
                blades as u32 / 1000,
                per_step(visited),
                per_step(pushed),
                per_step(reused),
                grass.active_count()
            );
        }
    }
    group.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .sample_size(30)
        .warm_up_time(std::time::Duration::from_secs(2))
        .measurement_time(std::time::Duration::from_secs(4));
    targets = walk
}
criterion_main!(benches);
