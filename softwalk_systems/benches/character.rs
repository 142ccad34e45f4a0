//! All character stages (gait, foot rays, balance, foot IK, metrics) for one
//! character and one 60 Hz step, on a bumpy 512² height grid; and the
//! driver's pose retargeted onto the built-in human (`RigPose::drive`).

use criterion::{Criterion, criterion_group, criterion_main};
use engine::geom::HeightGrid;
use glam::{Vec2, Vec3};
use softwalk_systems::character::{
    Character, CharacterDesc, CharacterRig, RigPose, WalkPath, step_character,
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

fn rig_pose(c: &mut Criterion) {
    let (walker, _, _) = walker();
    let rig = CharacterRig::human().expect("the built-in human");
    c.bench_function("rig_pose_drive_human", |b| {
        b.iter(|| RigPose::drive(&rig, &walker.body, &walker.pose, &walker.feet))
    });
}

criterion_group!(benches, character_step, rig_pose);
criterion_main!(benches);
