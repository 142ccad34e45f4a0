//! One carving step of one foot (carve, smooth, settle, and the ground BVH
//! refit of what they changed), at 512² and 4096² samples of the same spacing
//! (the paper's 10 m / 512): the work must follow the foot, not the terrain size.
//!
//! Run: `cargo bench -p softwalk_systems --bench terrain`. Besides criterion's
//! figures it prints a direct timing of every step of both sizes, interleaved
//! foothold by foothold in one run (so machine load hits both alike): the mean
//! step, the release step (the heaviest: the foot lifts, the whole print is
//! smoothed and its walls slump) and the 4096²/512² ratio.

use std::hint::black_box;
use std::time::{Duration, Instant};

use criterion::{Criterion, criterion_group, criterion_main};
use engine::geom::{GridBvh, GridRect};
use glam::Vec2;
use softwalk_systems::terrain::generate::{self, GridSpec};
use softwalk_systems::terrain::{
    FootPrint, FootSize, Heightfield, MaterialTable, StageScratch, TerrainMaterial, press_into,
    sole_on_ground, step_foot_with,
};

const DT: f32 = 1.0 / 60.0;
const STANCE_STEPS: usize = 18;
const CELL: f32 = 10.0 / 511.0;
const SIZES: [usize; 2] = [512, 4096];

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
/// terrain size) on its own terrain and ground BVH: 18 stance steps, one
/// release step and the lifted steps until the print has settled (settling
/// is spread over steps) per foothold. After each foothold the heights under it are
/// restored (untimed, BVH refit included), so the long runs of the benchmark
/// keep measuring fresh prints instead of digging the same holes deeper and deeper.
struct Walker {
    hf: Heightfield,
    bvh: GridBvh,
    print: FootPrint,
    scratch: StageScratch,
    foothold: usize,
    step: usize,
    saved_rect: GridRect,
    saved: Vec<f32>,
}

impl Walker {
    fn new(n: usize) -> Self {
        let hf = terrain(n);
        let bvh = GridBvh::build(hf.grid());
        Walker {
            hf,
            bvh,
            print: FootPrint::new(),
            scratch: StageScratch::default(),
            foothold: 0,
            step: 0,
            saved_rect: GridRect::EMPTY,
            saved: Vec::new(),
        }
    }

    /// Before a foothold's first step, saves the heights around it; after its
    /// release step and settling, puts them back and moves on to the next foothold.
    fn save_or_restore(&mut self) {
        let nx = self.hf.grid().nx();
        if self.step > STANCE_STEPS && !self.hf.settling_pending() {
            let rect = self.saved_rect;
            let heights = self.hf.grid_mut().heights_mut();
            for (r, j) in (rect.j0..rect.j1).enumerate() {
                heights[j * nx + rect.i0..j * nx + rect.i1]
                    .copy_from_slice(&self.saved[r * rect.width()..(r + 1) * rect.width()]);
            }
            self.bvh.refit(self.hf.grid(), rect);
            self.step = 0;
            self.foothold += 1;
        }
        if self.step == 0 {
            let c = self.center();
            let reach = Vec2::splat(0.5);
            let rect = self.hf.grid().rect_covering(c - reach, c + reach);
            let heights = self.hf.grid().heights();
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

    /// One fixed step of the terrain stages for this foot (the part to time),
    /// the BVH refit included when `refit`; returns which kind of step it was.
    fn step(&mut self, refit: bool) -> StepKind {
        let center = self.center();
        let hf = &mut self.hf;
        hf.begin_step();
        let sole = sole_on_ground(hf, center, Vec2::X, FootSize::default()).unwrap();
        let sole = press_into(hf, sole, DT);
        let contact = self.step < STANCE_STEPS;
        black_box(
            step_foot_with(hf, &mut self.scratch, &mut self.print, &sole, contact, DT).unwrap(),
        );
        if refit {
            for rect in hf.dirty().iter() {
                self.bvh.refit(hf.grid(), rect);
            }
        } else {
            black_box(hf.dirty());
        }
        self.step += 1;
        match self.step - 1 {
            k if k < STANCE_STEPS => StepKind::Stance,
            STANCE_STEPS => StepKind::Release,
            k => StepKind::Settling {
                first: k == STANCE_STEPS + 1,
            },
        }
    }

    /// Times one whole foothold step by step (full step with refit), in
    /// nanoseconds, into `t` by kind of step.
    fn foothold(&mut self, t: &mut Timings) {
        loop {
            self.save_or_restore();
            let start = Instant::now();
            let kind = self.step(true);
            let ns = start.elapsed().as_nanos() as f64;
            match kind {
                StepKind::Stance => t.stance.push(ns),
                StepKind::Release => t.release.push(ns),
                StepKind::Settling { first } => {
                    t.settling.push(ns);
                    if first {
                        t.first_settling.push(ns);
                    }
                }
            }
            if self.step > STANCE_STEPS && !self.hf.settling_pending() {
                return;
            }
        }
    }
}

/// The three kinds of step of a foothold.
enum StepKind {
    /// The foot presses in.
    Stance,
    /// The foot lifts: the whole print is smoothed and starts to slump.
    Release,
    /// The foot is lifted and the print still slumps (settling left pending);
    /// `first` for the step right after the release (its settling starts there).
    Settling { first: bool },
}

fn bench_step(c: &mut Criterion) {
    let mut group = c.benchmark_group("terrain_step");
    for n in SIZES {
        for (name, refit) in [
            ("carve_smooth_settle", false),
            ("full_step_with_refit", true),
        ] {
            let mut walker = Walker::new(n);
            group.bench_function(format!("{name}_{n}"), |b| {
                b.iter_custom(|iters| {
                    let mut total = Duration::ZERO;
                    for _ in 0..iters {
                        walker.save_or_restore();
                        let start = Instant::now();
                        walker.step(refit);
                        total += start.elapsed();
                    }
                    total
                })
            });
        }
    }
    group.finish();
    direct_timing(400);
}

/// Per-step timings of one terrain size, ns.
#[derive(Default)]
struct Timings {
    stance: Vec<f64>,
    release: Vec<f64>,
    settling: Vec<f64>,
    /// The first settling step of each foothold (also in `settling`).
    first_settling: Vec<f64>,
}

impl Timings {
    fn all(&self) -> Vec<f64> {
        let kinds = [&self.stance, &self.release, &self.settling];
        kinds.into_iter().flatten().copied().collect()
    }
}

/// Mean of `v` without its slowest 2 % (preemptions on a shared machine), ns (0 if empty).
fn trimmed_mean(v: &[f64]) -> f64 {
    if v.is_empty() {
        return 0.0;
    }
    let mut s = v.to_vec();
    s.sort_by(f64::total_cmp);
    let keep = &s[..(s.len() * 49).div_ceil(50)];
    keep.iter().sum::<f64>() / keep.len() as f64
}

/// The `q` quantile of `v`, ns (0 if empty).
fn quantile(v: &[f64], q: f64) -> f64 {
    if v.is_empty() {
        return 0.0;
    }
    let mut s = v.to_vec();
    s.sort_by(f64::total_cmp);
    s[((s.len() - 1) as f64 * q).round() as usize]
}

/// Walks `footholds` footholds on both sizes, alternating which size goes
/// first, after a warm-up of 40 footholds each; prints the figures.
fn direct_timing(footholds: usize) {
    let mut walkers = SIZES.map(Walker::new);
    let mut timings = [Timings::default(), Timings::default()];
    let mut warm_up = Timings::default();
    for round in 0..40 + footholds {
        for k in [round % 2, 1 - round % 2] {
            let t = if round < 40 {
                &mut warm_up
            } else {
                &mut timings[k]
            };
            walkers[k].foothold(t);
        }
    }
    let us = |ns: f64| ns / 1e3;
    for (n, t) in SIZES.iter().zip(&timings) {
        println!(
            "direct {n}^2 (full step with refit): mean step {:.2} us (median {:.2}); \
             stance {:.2} us; release {:.2} us (median {:.2}, p90 {:.2}); \
             settling after release {:.2} us (p90 {:.2}, {:.2} steps per foothold; \
             first of them {:.2} us, median {:.2}, p90 {:.2}); all steps p90 {:.2} us",
            us(trimmed_mean(&t.all())),
            us(quantile(&t.all(), 0.5)),
            us(trimmed_mean(&t.stance)),
            us(trimmed_mean(&t.release)),
            us(quantile(&t.release, 0.5)),
            us(quantile(&t.release, 0.9)),
            us(trimmed_mean(&t.settling)),
            us(quantile(&t.settling, 0.9)),
            t.settling.len() as f64 / t.release.len() as f64,
            us(trimmed_mean(&t.first_settling)),
            us(quantile(&t.first_settling, 0.5)),
            us(quantile(&t.first_settling, 0.9)),
            us(quantile(&t.all(), 0.9)),
        );
    }
    let [small, large] = &timings;
    println!(
        "direct ratio 4096^2/512^2: mean step {:.3}, median step {:.3}, release {:.3} \
         (goal: every step <= 20 us, ratio <= 1.1; means drop the slowest 2 % as preemptions)",
        trimmed_mean(&large.all()) / trimmed_mean(&small.all()),
        quantile(&large.all(), 0.5) / quantile(&small.all(), 0.5),
        trimmed_mean(&large.release) / trimmed_mean(&small.release),
    );
}

criterion_group!(benches, bench_step);
criterion_main!(benches);
