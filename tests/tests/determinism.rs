//! Same scene, same inputs: the same world, bit for bit, with or without
//! rendering and on any thread count (checked through the world hash).

use softwalk_app::runner::{RunOptions, run};
use softwalk_app::scene::Scene;

const STEPS: u64 = 90;

fn hash(scene: &Scene, render: bool, threads: usize) -> u64 {
    let mut options = RunOptions::from_scene(scene);
    options.steps = STEPS;
    options.render = render;
    options.width = 96;
    options.height = 54;
    options.render_every = 15;
    options.threads = threads;
    options.hash = true;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    let summary = pool.install(|| run(scene, &options, &mut ())).unwrap();
    summary.world_hash.expect("a hash was asked for")
}

#[test]
fn the_world_hash_ignores_rendering_and_thread_count() {
    let scene = Scene::builtin("grass-small").unwrap();
    let reference = hash(&scene, false, 1);
    assert_eq!(
        hash(&scene, false, 1),
        reference,
        "two identical runs agree"
    );
    assert_eq!(
        hash(&scene, true, 1),
        reference,
        "rendering does not change the world"
    );
    assert_eq!(
        hash(&scene, true, 2),
        reference,
        "two threads give the same world"
    );
    assert_eq!(hash(&scene, false, 2), reference);
}

#[test]
fn a_different_scene_gives_a_different_hash() {
    let sand = Scene::builtin("sand-flat").unwrap();
    let snow = Scene::builtin("snow-flat").unwrap();
    assert_ne!(hash(&sand, false, 1), hash(&snow, false, 1));
}

#[test]
fn a_crowd_gives_the_same_world_on_one_two_and_four_threads() {
    // 48 walkers crossing sand, snow and grass: per-character systems run
    // in parallel, ground edits in a fixed order.
    let spec = softwalk_app::scene::CrowdSpec {
        walkers: 48,
        size_m: 16.0,
        resolution: 801,
        spacing_m: 0.8,
        ..softwalk_app::scene::CrowdSpec::default()
    };
    let scene = Scene::from_toml_str(&spec.toml("crowd-test"), std::path::Path::new("")).unwrap();
    assert!(scene.warnings().is_empty());
    let reference = hash(&scene, false, 1);
    assert_eq!(hash(&scene, false, 2), reference, "two threads");
    assert_eq!(hash(&scene, false, 4), reference, "four threads");
}

#[test]
fn the_model_sets_the_body_mass_and_drawing_it_never_changes_the_world() {
    let human = Scene::builtin("grass-small").unwrap();
    assert_eq!(human.characters[0].model, softwalk_app::scene::HUMAN_MODEL);
    let mut mannequin = human.clone();
    for c in &mut mannequin.characters {
        c.model = softwalk_app::scene::MANNEQUIN_MODEL.to_string();
    }
    let headless = hash(&human, false, 1);
    assert_eq!(hash(&human, true, 2), headless, "drawing the human");
    // The human's skinned volume, not the capsules, gives its body its
    // centre of mass and inertia.
    assert_ne!(hash(&mannequin, false, 1), headless);
}
