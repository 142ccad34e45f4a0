//! The default human (`assets/characters/human.glb`): loads quickly, is small
//! enough, its weights sum to 1, its legs and spine are found, and its rest
//! pose skins to its bind pose.

mod anim_support;

use std::time::Instant;

use engine::anim::gltf::load_gltf;
use engine::anim::{BoneMap, RigChains, RigPreset, SkinnedVertices, skin, skin_matrices};

#[test]
fn default_human_loads_with_a_game_engine_rig() {
    let start = Instant::now();
    let model = load_gltf(&anim_support::human_path()).unwrap();
    let elapsed = start.elapsed();
    println!("loaded the default human in {elapsed:?}");
    // The goal is 50 ms in release; a debug test on a loaded machine gets slack.
    assert!(elapsed.as_millis() < 2000, "{elapsed:?}");
    assert!(
        model.mesh.triangle_count() <= 12_500,
        "{}",
        model.mesh.triangle_count()
    );
    assert!(model.mesh.vertex_count() > 3000);
    assert!(model.skeleton.len() >= 20);
    for (k, w) in model.mesh.weights().iter().enumerate() {
        let sum: f32 = w.iter().sum();
        assert!((sum - 1.0).abs() < 1e-5, "vertex {k}: {sum}");
    }
    let map = BoneMap::detect(&model.skeleton);
    assert_eq!(map.preset, Some(RigPreset::GameEngine));
    let chains = RigChains::find(&model.skeleton, &map).unwrap();
    let name = |j: usize| model.skeleton.joints()[j].name.as_str();
    assert_eq!(
        [
            chains.left.hip,
            chains.left.knee,
            chains.left.ankle,
            chains.left.toe.unwrap()
        ]
        .map(name),
        ["thigh_l", "calf_l", "foot_l", "ball_l"]
    );
    assert_eq!(name(chains.right.toe.unwrap()), "ball_r");
    assert_eq!(name(chains.pelvis), "pelvis");
    let spine: Vec<&str> = chains.spine.iter().map(|&j| name(j)).collect();
    assert_eq!(
        spine,
        ["spine_01", "spine_02", "spine_03", "neck_01", "head"]
    );
    let leg = chains.leg_length(&model.skeleton, &chains.left);
    assert!((0.6..1.0).contains(&leg), "leg length {leg} m");
}

#[test]
fn default_human_stands_on_the_ground_facing_z() {
    let model = load_gltf(&anim_support::human_path()).unwrap();
    let (mut lo, mut hi) = (engine::glam::Vec3::MAX, engine::glam::Vec3::MIN);
    for p in model.mesh.positions() {
        lo = lo.min(*p);
        hi = hi.max(*p);
    }
    assert!(lo.y.abs() < 1e-3, "soles at {}", lo.y);
    assert!((1.5..1.9).contains(&hi.y), "height {}", hi.y);
    // The left leg is on +x (the character's left when it faces +z).
    let map = BoneMap::detect(&model.skeleton);
    let globals = model.skeleton.rest_globals();
    let left = map.joint(engine::anim::BoneRole::FootL).unwrap();
    assert!(globals[left].w_axis.x > 0.0);
}

#[test]
fn rest_pose_skins_to_the_bind_pose() {
    let model = load_gltf(&anim_support::human_path()).unwrap();
    let globals = model.skeleton.rest_globals();
    let mut matrices = Vec::new();
    skin_matrices(&model.skeleton, &globals, &mut matrices);
    let mut out = SkinnedVertices::default();
    skin(&model.mesh, &matrices, &mut out).unwrap();
    for (p, q) in out.positions.iter().zip(model.mesh.positions()) {
        assert!(p.distance(*q) < 1e-4);
    }
}
