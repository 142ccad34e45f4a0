//! Frame rendering benchmark: a 512² height grid (10 x 10 m) with footprints, a
//! character-sized mesh and 20,000 grass blades at 1280 x 720.
//!
//! `cargo bench -p engine --bench render_frame`

use criterion::{Criterion, criterion_group, criterion_main};
use engine::geom::{HeightGrid, TriMesh};
use engine::glam::{Mat4, Vec2, Vec3};
use engine::render::{
    Camera, FrameScene, GrassBlade, Lighting, MeshInstance, Renderer, TerrainRenderer,
    TerrainStyle, UniformColor,
};

fn terrain_grid() -> HeightGrid {
    HeightGrid::from_fn(Vec2::new(-5.0, -5.0), 10.0 / 511.0, 512, 512, |x, z| {
        let mut h = 0.25 * (x * 0.6).sin() * (z * 0.45).cos() + 0.01 * (x * 9.0 + z * 7.0).sin();
        for k in 0..8 {
            let (cx, cz) = (-2.0 + 0.35 * k as f32, if k % 2 == 0 { 0.1 } else { -0.1 });
            let r = (((x - cx) / 0.13).powi(2) + ((z - cz) / 0.055).powi(2)).sqrt();
            if r < 1.0 {
                h -= 0.03 * (1.0 - r * r);
            }
        }
        h
    })
    .expect("valid grid")
}

/// A closed box of half-size `half` (a stand-in for a character).
fn body() -> TriMesh {
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    // A tessellated sphere: ~2,000 triangles, like a capsule character.
    let (rings, segments) = (24u32, 40u32);
    for r in 0..=rings {
        let t = std::f32::consts::PI * r as f32 / rings as f32;
        for s in 0..segments {
            let p = std::f32::consts::TAU * s as f32 / segments as f32;
            positions.push(Vec3::new(
                t.sin() * p.cos() * 0.25,
                t.cos() * 0.85,
                t.sin() * p.sin() * 0.25,
            ));
        }
    }
    for r in 0..rings {
        for s in 0..segments {
            let a = r * segments + s;
            let b = r * segments + (s + 1) % segments;
            triangles.push([a, b, b + segments]);
            triangles.push([a, b + segments, a + segments]);
        }
    }
    TriMesh::new(positions, triangles).expect("valid mesh")
}

fn blades(grid: &HeightGrid) -> Vec<GrassBlade> {
    let mut seed = 0x9e37_79b9_7f4a_7c15u64;
    let mut rand = move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 40) as f32 / (1u64 << 24) as f32
    };
    (0..20_000)
        .map(|_| {
            let (x, z) = (0.5 + rand() * 2.5, 0.3 + rand() * 2.0);
            let root = Vec3::new(x, grid.height_at(x, z).unwrap_or(0.0), z);
            let h = 0.3 + 0.2 * rand();
            GrassBlade {
                root,
                mid: root + Vec3::new(0.02, 0.55 * h, 0.0),
                tip: root + Vec3::new(0.06 * rand(), h, 0.05 * rand()),
                width: 0.01,
                color: Vec3::new(0.2, 0.45, 0.12),
            }
        })
        .collect()
}

/// The 1280 x 720 camera both frame benchmarks look through.
fn bench_camera() -> Camera {
    Camera::perspective(0.9, 1280, 720, 0.05, 200.0)
        .expect("camera")
        .look_at(
            Vec3::new(-1.5, 1.6, -3.2),
            Vec3::new(0.0, 0.2, 0.5),
            Vec3::Y,
        )
}

fn bench(c: &mut Criterion) {
    let grid = terrain_grid();
    let lighting = Lighting::default();
    let mut terrain = TerrainRenderer::new(&grid, TerrainStyle::default()).expect("style");
    let colors = UniformColor(Vec3::new(0.62, 0.5, 0.34));
    terrain.update(&grid, &colors, &lighting).expect("grid");
    let mesh = body();
    let meshes = [MeshInstance::new(
        &mesh,
        Mat4::from_translation(Vec3::new(-0.5, 0.85, 0.0)),
        Vec3::new(0.7, 0.3, 0.2),
    )];
    let blades = blades(&grid);
    let scene = FrameScene {
        terrain: Some(&terrain),
        meshes: &meshes,
        blades: &blades,
        lighting,
        shadows: true,
    };
    let camera = bench_camera();
    let renderer = Renderer::new(1280, 720).expect("size");
    let (_, stats) = renderer.render_with_stats(&scene, &camera);
    eprintln!("frame: {stats:?}");
    c.bench_function("frame_512sq_1280x720_mesh_20k_blades", |b| {
        b.iter(|| renderer.render(&scene, &camera))
    });

    let mut group = c.benchmark_group("terrain_update");
    let rect = grid.rect_covering(Vec2::new(-0.2, -0.1), Vec2::new(0.2, 0.1));
    group.bench_function("one_footprint_window", |b| {
        b.iter(|| {
            terrain.mark_dirty(rect);
            terrain.update(&grid, &colors, &lighting).expect("grid");
        })
    });
    group.finish();
}

/// The grass half of the frame alone: the same 20,000 blades and camera over
/// no terrain, on one thread (where the frame goal needs about 4-6 ms).
fn bench_grass(c: &mut Criterion) {
    let grid = terrain_grid();
    let blades = blades(&grid);
    let scene = FrameScene {
        blades: &blades,
        ..FrameScene::new()
    };
    let camera = bench_camera();
    let renderer = Renderer::new(1280, 720)
        .expect("size")
        .with_threads(1)
        .expect("pool");
    c.bench_function("grass_20k_blades_1280x720_1_thread", |b| {
        b.iter(|| renderer.render(&scene, &camera))
    });
}

criterion_group!(benches, bench, bench_grass);
criterion_main!(benches);
