//! One carving step (carve, smooth, settle) of one foot, at 512² and 4096²
//! samples of the same spacing (the paper's 10 m / 512): the work must follow
//! the foot, not the terrain size.
//!
//! Run: `cargo bench -p softwalk_systems --bench terrain`. Besides criterion's
//! figures it prints a direct timing of both sizes and their ratio.

use std::hint::black_box;
use std::time::Instant;

use criterion::{Criterion, criterion_group, criterion_main};
use glam::Vec2;
use softwalk_systems::terrain::generate::{self, GridSpec};
use softwalk_systems::terrain::{
    FootPrint, FootSize, Heightfield, MaterialTable, TerrainMaterial, sole_on_ground, step_foot,
};

const DT: f32 = 1.0 / 60.0;
const STANCE_STEPS: usize = 18;
const CELL: f32 = 10.0 / 511.0;

/// A flat dry-sand terrain of `n`² samples at the paper's spacing.
fn terrain(n: usize) -> Heightfield {
    let spec = GridSpec {
        origin: Vec2::ZERO,
        cell: CELL,
        nx: n,
        nz: n,
    };
    let mut table = MaterialTable::new();
    let sand = table.add(TerrainMaterial::dry_sand()).unwrap();
    Heightfield::from_grid(generate::flat(spec, 1.0).unwrap(), table, sand).unwrap()
}

/// A foot walking rows across the first 10 x 10 m (the same path on every
/// terrain size): 18 stance steps and one release step per foothold.
struct Walker {
    print: FootPrint,
    foothold: usize,
    step: usize,
}

impl Walker {
    fn new() -> Self {
        Walker {
            print: FootPrint::new(),
            foothold: 0,
            step: 0,
        }
    }

    fn center(&self) -> Vec2 {
        let per_row = 14;
        let (row, col) = (self.foothold / per_row % 60, self.foothold % per_row);
        Vec2::new(0.6 + 0.65 * col as f32, 0.4 + 0.15 * row as f32)
    }

    /// One fixed step of the terrain stages for this foot.
    fn step(&mut self, hf: &mut Heightfield) {
        hf.begin_step();
        let sole = sole_on_ground(hf, self.center(), Vec2::X, FootSize::default()).unwrap();
        let contact = self.step < STANCE_STEPS;
        black_box(step_foot(hf, &mut self.print, &sole, contact, DT).unwrap());
        black_box(hf.take_dirty());
        self.step += 1;
        if self.step > STANCE_STEPS {
            self.step = 0;
            self.foothold += 1;
        }
    }
}

/// Mean nanoseconds per step over `steps` steps after a warm-up walk.
fn direct_ns_per_step(n: usize, steps: usize) -> f64 {
    let mut hf = terrain(n);
    let mut walker = Walker::new();
    for _ in 0..steps {
        walker.step(&mut hf);
    }
    let start = Instant::now();
    for _ in 0..steps {
        walker.step(&mut hf);
    }
    start.elapsed().as_nanos() as f64 / steps as f64
}

fn bench_step(c: &mut Criterion) {
    let mut group = c.benchmark_group("terrain_step");
    for n in [512, 4096] {
        let mut hf = terrain(n);
        let mut walker = Walker::new();
        group.bench_function(format!("carve_smooth_settle_{n}"), |b| {
            b.iter(|| walker.step(&mut hf))
        });
    }
    group.finish();
    let steps = 19 * 400;
    let small = direct_ns_per_step(512, steps);
    let large = direct_ns_per_step(4096, steps);
    println!(
        "direct: 512^2 {:.2} us/step, 4096^2 {:.2} us/step, ratio {:.3} (goal <= 20 us, ratio <= 1.1)",
        small / 1e3,
        large / 1e3,
        large / small
    );
}

criterion_group!(benches, bench_step);
criterion_main!(benches);
