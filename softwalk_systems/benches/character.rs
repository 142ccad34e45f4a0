//! All character stages (gait, foot rays, balance, foot IK, metrics) for one
//! character and one 60 Hz step, on a bumpy 512² height grid; the driver's
//! pose retargeted onto the built-in human as a view does each frame, without
//! and with the shipped walk clip's upper body; and preparing the human.

use criterion::{Criterion, criterion_group, criterion_main};
use engine::anim::bvh::load_bvh;
use engine::anim::{BoneMap, WalkCycle};
use engine::geom::HeightGrid;
use glam::{Vec2, Vec3};
use softwalk_systems::character::{
    Character, CharacterDesc, CharacterRig, ClipScratch, ClipWalk, RigPose, WalkPath,
    step_character,
};

/// A walker on a bumpy grid, a second into its walk.
fn walker() -> (Character, WalkPath, HeightGrid) {
    let ground = HeightGrid::from_fn(Vec2::new(-5.0, -5.0), 10.0 / 511.0, 512, 512, |x, z| {
        0.04 * (1.7 * x).sin() * (1.3 * z).cos()
    })
    .expect("a valid grid");
    let path = WalkPath::circle(Vec3::new(3.0, 0.0, 0.0), Vec3::Z, 3.0).expect("a valid path");
    let mut walker =
        Character::new(CharacterDesc::adult(), &path, &ground).expect("a valid character");
    for _ in 0..60 {
        step_character(&mut walker, &path, &ground, 1.0 / 60.0);
    }
    (walker, path, ground)
}

fn character_step(c: &mut Criterion) {
    let (mut walker, path, ground) = walker();
    c.bench_function("character_step_all_stages", |b| {
        b.iter(|| step_character(&mut walker, &path, &ground, 1.0 / 60.0))
    });
}

/// The shipped walk clip retargeted onto `rig`.
fn walk_clip(rig: &CharacterRig) -> ClipWalk {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../assets/clips/walk.bvh");
    let bvh = load_bvh(std::path::Path::new(path)).expect("the shipped clip");
    let map = BoneMap::detect(&bvh.skeleton);
    let cycle = WalkCycle::analyse(&bvh.clip, &bvh.skeleton, &map).expect("a walk");
    ClipWalk::new(&bvh.skeleton, &map, &bvh.clip, cycle, rig).expect("a clip for the human")
}

fn rig_pose(c: &mut Criterion) {
    let (walker, _, _) = walker();
    let (body, pose, feet, gait) = (&walker.body, &walker.pose, &walker.feet, &walker.gait);
    let rig = CharacterRig::human().expect("the built-in human");
    let clip = walk_clip(&rig);
    c.bench_function("rig_pose_drive_human", |b| {
        b.iter(|| RigPose::drive(&rig, body, pose, feet))
    });
    let mut out = RigPose::default();
    c.bench_function("rig_pose_frame_human", |b| {
        b.iter(|| out.drive_in_place(&rig, body, pose, feet))
    });
    let mut scratch = ClipScratch::default();
    c.bench_function("rig_pose_frame_human_clip", |b| {
        b.iter(|| {
            out.drive_in_place(&rig, body, pose, feet);
            clip.play_upper_body(&rig, &mut out, gait.phase, gait.roll, &mut scratch);
        })
    });
    c.bench_function("rig_new_human", |b| {
        b.iter(|| {
            let model = CharacterRig::parse_human().expect("the human's bytes");
            let map = BoneMap::detect(&model.skeleton);
            CharacterRig::new("human", model, map).expect("the human")
        })
    });
}

criterion_group!(benches, character_step, rig_pose);
criterion_main!(benches);
