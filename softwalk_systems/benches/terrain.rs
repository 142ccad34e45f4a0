//! One carving step (carve, smooth, settle) of one foot, at 512² and 4096²
//! samples of the same spacing (the paper's 10 m / 512): the work must follow
//! the foot, not the terrain size.
//!
//! Run: `cargo bench -p softwalk_systems --bench terrain`. Besides criterion's
//! figures it prints a direct timing of both sizes and their ratio.

use std::hint::black_box;
use std::time::{Duration, Instant};

use criterion::{Criterion, criterion_group, criterion_main};
use engine::geom::GridRect;
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
/// terrain size): 18 stance steps and one release step per foothold. After
/// each foothold the heights under it are restored (untimed), so the long
/// runs of the benchmark keep measuring fresh prints instead of digging the
/// same holes deeper and deeper.
struct Walker {
    print: FootPrint,
    foothold: usize,
    step: usize,
    saved_rect: GridRect,
    saved: Vec<f32>,
}

impl Walker {
    fn new() -> Self {
        Walker {
            print: FootPrint::new(),
            foothold: 0,
            step: 0,
            saved_rect: GridRect::EMPTY,
            saved: Vec::new(),
        }
    }

    /// Before a foothold's first step, saves the heights around it; after its
    /// release step, puts them back and moves on to the next foothold.
    fn save_or_restore(&mut self, hf: &mut Heightfield) {
        let nx = hf.grid().nx();
        if self.step > STANCE_STEPS {
            let rect = self.saved_rect;
            let heights = hf.grid_mut().heights_mut();
            for (r, j) in (rect.j0..rect.j1).enumerate() {
                heights[j * nx + rect.i0..j * nx + rect.i1]
                    .copy_from_slice(&self.saved[r * rect.width()..(r + 1) * rect.width()]);
            }
            hf.mark_dirty(rect);
            self.step = 0;
            self.foothold += 1;
        }
        if self.step == 0 {
            let c = self.center();
            let reach = Vec2::splat(0.5);
            let rect = hf.grid().rect_covering(c - reach, c + reach);
            let heights = hf.grid().heights();
            self.saved.clear();
            for j in rect.j0..rect.j1 {
                self.saved
                    .extend_from_slice(&heights[j * nx + rect.i0..j * nx + rect.i1]);
            }
            self.saved_rect = rect;
        }
    }

    fn center(&self) -> Vec2 {
        let per_row = 14;
        let (row, col) = (self.foothold / per_row % 60, self.foothold % per_row);
        Vec2::new(0.6 + 0.65 * col as f32, 0.4 + 0.15 * row as f32)
    }

    /// One fixed step of the terrain stages for this foot (timed); true for a release step.
    fn step(&mut self, hf: &mut Heightfield) -> bool {
        hf.begin_step();
        let sole = sole_on_ground(hf, self.center(), Vec2::X, FootSize::default()).unwrap();
        let contact = self.step < STANCE_STEPS;
        black_box(step_foot(hf, &mut self.print, &sole, contact, DT).unwrap());
        black_box(hf.take_dirty());
        self.step += 1;
        !contact
    }
}

/// Mean nanoseconds per step, and per release step (the heaviest: the whole
/// print is smoothed and slumps), over `footholds` footholds after a warm-up.
fn direct_ns_per_step(n: usize, footholds: usize) -> (f64, f64) {
    let mut hf = terrain(n);
    let mut walker = Walker::new();
    let steps = footholds * (STANCE_STEPS + 1);
    for _ in 0..steps {
        walker.save_or_restore(&mut hf);
        walker.step(&mut hf);
    }
    let (mut all, mut release) = (0u128, 0u128);
    for _ in 0..steps {
        walker.save_or_restore(&mut hf);
        let start = Instant::now();
        let released = walker.step(&mut hf);
        let ns = start.elapsed().as_nanos();
        all += ns;
        if released {
            release += ns;
        }
    }
    (all as f64 / steps as f64, release as f64 / footholds as f64)
}

fn bench_step(c: &mut Criterion) {
    let mut group = c.benchmark_group("terrain_step");
    for n in [512, 4096] {
        let mut hf = terrain(n);
        let mut walker = Walker::new();
        group.bench_function(format!("carve_smooth_settle_{n}"), |b| {
            b.iter_custom(|iters| {
                let mut total = Duration::ZERO;
                for _ in 0..iters {
                    walker.save_or_restore(&mut hf);
                    let start = Instant::now();
                    walker.step(&mut hf);
                    total += start.elapsed();
                }
                total
            })
        });
    }
    group.finish();
    let small = direct_ns_per_step(512, 400);
    let large = direct_ns_per_step(4096, 400);
    println!(
        "direct: mean step 512^2 {:.2} us, 4096^2 {:.2} us, ratio {:.3} (goal <= 20 us, ratio <= 1.1)",
        small.0 / 1e3,
        large.0 / 1e3,
        large.0 / small.0
    );
    println!(
        "direct: release step 512^2 {:.2} us, 4096^2 {:.2} us, ratio {:.3}",
        small.1 / 1e3,
        large.1 / 1e3,
        large.1 / small.1
    );
}

criterion_group!(benches, bench_step);
criterion_main!(benches);
