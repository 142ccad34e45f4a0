//! Linear blend skinning of 12k vertices (the default human, 6002 vertices,
//! taken twice), positions and normals, on one thread and on the rayon pool;
//! and loading the default `.glb`. Besides criterion's mean (wall time, which
//! other processes on a loaded machine inflate), each prints the fastest of
//! many single runs.
//!
//! `cargo bench -p engine --bench skinning`

use std::hint::black_box;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use engine::anim::gltf::load_gltf;
use engine::anim::{Model, Pose, SkinnedMesh, SkinnedVertices, skin, skin_matrices, skin_serial};
use engine::glam::{Affine3A, Quat};

/// The fastest of `runs` single runs of `f`: on a shared, loaded machine the
/// minimum is the run nothing else interrupted.
fn fastest<T>(runs: usize, mut f: impl FnMut() -> T) -> Duration {
    (0..runs)
        .map(|_| {
            let start = Instant::now();
            black_box(f());
            start.elapsed()
        })
        .min()
        .unwrap_or_default()
}

fn human_path() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/characters/human.glb")
}

/// The human's mesh repeated until it has at least 12 000 vertices.
fn twelve_thousand(model: &Model) -> SkinnedMesh {
    let mesh = &model.mesh;
    let copies = 12_000_usize.div_ceil(mesh.vertex_count());
    let n = mesh.vertex_count() as u32;
    SkinnedMesh::new(
        (0..copies)
            .flat_map(|_| mesh.positions().to_vec())
            .collect(),
        (0..copies).flat_map(|_| mesh.normals().to_vec()).collect(),
        (0..copies)
            .flat_map(|k| mesh.indices().iter().map(move |&i| i + k as u32 * n))
            .collect(),
        (0..copies).flat_map(|_| mesh.joints().to_vec()).collect(),
        (0..copies).flat_map(|_| mesh.weights().to_vec()).collect(),
        mesh.joint_count(),
    )
    .expect("a repeated valid mesh is valid")
}

/// Every joint turned a little, so no skinning matrix is the identity.
fn bent_matrices(model: &Model) -> Vec<Affine3A> {
    let mut pose: Pose = model.skeleton.rest_pose();
    for (k, local) in pose.locals.iter_mut().enumerate() {
        local.rotation = Quat::from_rotation_x(0.02 * k as f32) * local.rotation;
    }
    let mut globals = Vec::new();
    pose.globals(&model.skeleton, &mut globals);
    let mut matrices = Vec::new();
    skin_matrices(&model.skeleton, &globals, &mut matrices);
    matrices
}

fn skinning(c: &mut Criterion) {
    let model = load_gltf(&human_path()).expect("the default human loads");
    let mesh = twelve_thousand(&model);
    let matrices = bent_matrices(&model);
    let mut out = SkinnedVertices::default();
    let mut group = c.benchmark_group("skinning");
    group.throughput(Throughput::Elements(mesh.vertex_count() as u64));
    let best = fastest(2000, || skin_serial(&mesh, &matrices, &mut out));
    println!(
        "skinning {} vertices, one thread: fastest run {best:?}",
        mesh.vertex_count()
    );
    let best = fastest(2000, || skin(&mesh, &matrices, &mut out));
    println!(
        "skinning {} vertices, rayon: fastest run {best:?}",
        mesh.vertex_count()
    );
    group.bench_function("12k_vertices_one_thread", |b| {
        b.iter(|| skin_serial(black_box(&mesh), black_box(&matrices), &mut out))
    });
    group.bench_function("12k_vertices_rayon", |b| {
        b.iter(|| skin(black_box(&mesh), black_box(&matrices), &mut out))
    });
    group.finish();
}

fn loading(c: &mut Criterion) {
    let path = human_path();
    let best = fastest(200, || load_gltf(&path).expect("loads"));
    println!("loading the default human: fastest run {best:?}");
    c.bench_function("load_default_human_glb", |b| {
        b.iter(|| load_gltf(black_box(&path)).expect("loads"))
    });
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(30);
    targets = skinning, loading
}
criterion_main!(benches);
