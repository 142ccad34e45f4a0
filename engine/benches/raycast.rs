//! Ray-cast benchmarks (single thread):
//! vertical foot rays on 512² and 4096² grids, rays against a 100k-triangle
//! mesh (ours one by one and batched, and obvhs's own CwBvh path, in CPU time), arbitrary rays on the
//! grid per tile size, and the refit after a 40x40-cell edit.
//!
//! `cargo bench -p engine --bench raycast`

use std::hint::black_box;
use std::time::{Duration, Instant};

use criterion::{Bencher, Criterion, Throughput, criterion_group, criterion_main};
use engine::geom::{GridBvh, GridRect, HeightGrid, MeshBvh, Ray, TriMesh};
use engine::glam::{Vec2, Vec3, Vec3A};
use engine::rng::SplitMix64;
use obvhs::BvhBuildParams;
use obvhs::cwbvh::builder::build_cwbvh_from_tris;
use obvhs::ray::{Ray as ObRay, RayHit};
use obvhs::triangle::Triangle;

/// The paper's terrain resolution: 512 samples over 10 m.
const CELL: f32 = 10.0 / 511.0;
const RAYS: usize = 4096;

fn terrain(n: usize) -> HeightGrid {
    HeightGrid::from_fn(Vec2::ZERO, CELL, n, n, |x, z| {
        0.3 * (0.9 * x).sin() * (0.7 * z).cos() + 0.05 * (4.0 * x + 3.0 * z).sin()
    })
    .unwrap()
}

/// Foot rays: a walking character's feet stay in a 2 m x 2 m window per step.
fn foot_points(rng: &mut SplitMix64) -> Vec<(f32, f32)> {
    (0..RAYS)
        .map(|_| (rng.range(4.0, 6.0), rng.range(4.0, 6.0)))
        .collect()
}

fn vertical(c: &mut Criterion) {
    let mut group = c.benchmark_group("vertical_rays");
    group.throughput(Throughput::Elements(RAYS as u64));
    let points = foot_points(&mut SplitMix64::new(1));
    for n in [512usize, 4096] {
        let grid = terrain(n);
        let bvh = GridBvh::build(&grid);
        group.bench_function(format!("cast_down_{n}"), |b| {
            b.iter(|| {
                let mut sum = 0.0;
                for &(x, z) in &points {
                    if let Some(h) = bvh.cast_down(&grid, x, z, 5.0) {
                        sum += h.point.y;
                    }
                }
                black_box(sum)
            })
        });
        let rays: Vec<Ray> = points
            .iter()
            .map(|&(x, z)| Ray::down(x, 5.0, z).unwrap())
            .collect();
        group.bench_function(format!("bvh_cast_{n}"), |b| {
            b.iter(|| {
                let mut sum = 0.0;
                for ray in &rays {
                    if let Some(h) = bvh.cast(&grid, ray, f32::INFINITY) {
                        sum += h.distance;
                    }
                }
                black_box(sum)
            })
        });
    }
    group.finish();
}

/// A closed bumpy sphere of `2 * n * n` triangles.
fn blob(n: usize) -> TriMesh {
    let mut positions = Vec::new();
    for a in 0..=n {
        for b in 0..n {
            let theta = std::f32::consts::PI * a as f32 / n as f32;
            let phi = std::f32::consts::TAU * b as f32 / n as f32;
            let r = 1.0 + 0.1 * (7.0 * phi).sin() * (5.0 * theta).sin();
            positions.push(
                r * Vec3::new(
                    theta.sin() * phi.cos(),
                    theta.cos(),
                    theta.sin() * phi.sin(),
                ),
            );
        }
    }
    let n32 = n as u32;
    let mut triangles = Vec::new();
    for a in 0..n32 {
        for b in 0..n32 {
            let (p, q) = (a * n32 + b, a * n32 + (b + 1) % n32);
            triangles.push([p, q, q + n32]);
            triangles.push([p, q + n32, p + n32]);
        }
    }
    TriMesh::new(positions, triangles).unwrap()
}

/// Incoherent rays: from random points in a cube of 3 radii around the object
/// towards random points of its central half-radius cube (every ray meets the
/// mesh from outside, each in an unrelated place).
fn arbitrary_rays(rng: &mut SplitMix64, centre: Vec3, radius: f32) -> Vec<Ray> {
    let mut point = |scale: f32| {
        centre
            + Vec3::new(
                rng.range(-1.0, 1.0),
                rng.range(-1.0, 1.0),
                rng.range(-1.0, 1.0),
            ) * radius
                * scale
    };
    (0..RAYS)
        .map(|_| {
            let o = point(3.0);
            Ray::new(o, point(0.5) - o).unwrap()
        })
        .collect()
}

/// Primary rays of a `w` x `h` pinhole camera framing the unit blob, in
/// scanline order (a renderer's rays).
fn camera_rays(w: usize, h: usize) -> Vec<Ray> {
    let eye = Vec3::new(0.3, 0.8, 3.0);
    (0..w * h)
        .map(|k| {
            let px = (k % w) as f32 / (w - 1) as f32 - 0.5;
            let py = (k / w) as f32 / (h - 1) as f32 - 0.5;
            Ray::new(eye, Vec3::new(px * 0.9, py * 0.9 - 0.25, -1.0)).unwrap()
        })
        .collect()
}

/// CPU time of this thread (Linux), so that other processes on a loaded
/// machine do not count; wall time elsewhere.
fn thread_cpu_time() -> Option<Duration> {
    let stat = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    let ns = stat.split_whitespace().next()?.parse().ok()?;
    Some(Duration::from_nanos(ns))
}

/// Times `iters` runs of `f` in thread CPU time (wall time if unavailable).
fn cpu_timed(b: &mut Bencher, mut f: impl FnMut() -> f32) {
    b.iter_custom(|iters| {
        let (cpu, wall) = (thread_cpu_time(), Instant::now());
        for _ in 0..iters {
            black_box(f());
        }
        match (cpu, thread_cpu_time()) {
            (Some(start), Some(end)) => end - start,
            _ => wall.elapsed(),
        }
    });
}

fn mesh(c: &mut Criterion) {
    let mesh = blob(224);
    assert!(mesh.triangles.len() >= 100_000);
    let ours = MeshBvh::build(&mesh).unwrap();
    // obvhs's own fast path, for comparison: CwBvh (medium preset) over its
    // triangles, stored in primitive order, with its triangle test.
    let triangles: Vec<Triangle> = mesh
        .triangles
        .iter()
        .map(|t| {
            let [v0, v1, v2] = t.map(|v| Vec3A::from(mesh.positions[v as usize]));
            Triangle { v0, v1, v2 }
        })
        .collect();
    let cwbvh = build_cwbvh_from_tris(
        &triangles,
        BvhBuildParams::medium_build(),
        &mut Duration::default(),
    );
    let ordered: Vec<Triangle> = cwbvh
        .primitive_indices
        .iter()
        .map(|&k| triangles[k as usize])
        .collect();
    let workloads = [
        (
            "arbitrary",
            arbitrary_rays(&mut SplitMix64::new(2), Vec3::ZERO, 1.0),
        ),
        ("camera_64x64", camera_rays(64, 64)),
        ("camera_640x480", camera_rays(640, 480)),
    ];
    let mut group = c.benchmark_group("mesh_100k");
    for (name, rays) in &workloads {
        group.throughput(Throughput::Elements(rays.len() as u64));
        group.bench_function(format!("{name}/ours"), |b| {
            cpu_timed(b, || {
                rays.iter()
                    .filter_map(|ray| ours.cast(ray, f32::INFINITY))
                    .map(|h| h.distance)
                    .sum()
            })
        });
        // The batch API: the same rays through `cast_many` (interleaved walks
        // with prefetching), same answers.
        let mut hits = Vec::with_capacity(rays.len());
        group.bench_function(format!("{name}/ours_batch"), |b| {
            cpu_timed(b, || {
                ours.cast_many(rays, f32::INFINITY, &mut hits);
                hits.iter().flatten().map(|h| h.distance).sum()
            })
        });
        group.bench_function(format!("{name}/obvhs_cwbvh"), |b| {
            cpu_timed(b, || {
                let mut sum = 0.0;
                for ray in rays {
                    let ray = ObRay::new_inf(ray.origin().into(), ray.dir().into());
                    let mut hit = RayHit::none();
                    if cwbvh.ray_traverse(ray, &mut hit, |r, k| ordered[k].intersect(r)) {
                        sum += hit.t;
                    }
                }
                sum
            })
        });
    }
    group.finish();
}

/// Arbitrary rays on the 512² grid for several tile sizes (how the default was chosen).
fn grid_tiles(c: &mut Criterion) {
    let grid = terrain(512);
    let mut rng = SplitMix64::new(3);
    let rays: Vec<Ray> = (0..RAYS)
        .map(|_| {
            let o = Vec3::new(
                rng.range(0.0, 10.0),
                rng.range(1.0, 3.0),
                rng.range(0.0, 10.0),
            );
            let d = Vec3::new(
                rng.range(-1.0, 1.0),
                rng.range(-1.0, -0.1),
                rng.range(-1.0, 1.0),
            );
            Ray::new(o, d).unwrap()
        })
        .collect();
    let mut group = c.benchmark_group("grid_arbitrary_rays_512");
    group.throughput(Throughput::Elements(RAYS as u64));
    for tile in [8usize, 16, 32] {
        let bvh = GridBvh::build_with_tiles(&grid, tile).unwrap();
        group.bench_function(format!("tile_{tile}"), |b| {
            b.iter(|| {
                let mut sum = 0.0;
                for ray in &rays {
                    if let Some(h) = bvh.cast(&grid, ray, f32::INFINITY) {
                        sum += h.distance;
                    }
                }
                black_box(sum)
            })
        });
    }
    group.finish();
}

/// A foot-sized edit (40x40 cells) and the refit that follows it.
fn refit(c: &mut Criterion) {
    let mut grid = terrain(512);
    let mut group = c.benchmark_group("refit_40x40");
    for tile in [8usize, 16, 32] {
        let mut bvh = GridBvh::build_with_tiles(&grid, tile).unwrap();
        let rect = GridRect::new(200, 230, 241, 271);
        let mut depth = 0.001;
        group.bench_function(format!("tile_{tile}"), |b| {
            b.iter(|| {
                depth = -depth;
                for (i, j) in rect.iter() {
                    let h = grid.height(i, j) + depth;
                    grid.set_height(i, j, h);
                }
                bvh.refit(&grid, rect);
            })
        });
    }
    group.finish();
}

/// The edit alone, to subtract from `refit_40x40`.
fn edit_only(c: &mut Criterion) {
    let mut grid = terrain(512);
    let rect = GridRect::new(200, 230, 241, 271);
    let mut depth = 0.001;
    c.bench_function("edit_40x40_only", |b| {
        b.iter(|| {
            depth = -depth;
            for (i, j) in rect.iter() {
                let h = grid.height(i, j) + depth;
                grid.set_height(i, j, h);
            }
            black_box(grid.height(200, 230))
        })
    });
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .sample_size(20)
        .warm_up_time(std::time::Duration::from_millis(500))
        .measurement_time(std::time::Duration::from_secs(2));
    targets = vertical, mesh, grid_tiles, refit, edit_only
}
criterion_main!(benches);
