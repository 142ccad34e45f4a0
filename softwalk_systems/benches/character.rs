//! All character stages (gait, foot rays, balance, foot IK, metrics) for one
//! character and one 60 Hz step, on a bumpy 512² height grid.

use criterion::{Criterion, criterion_group, criterion_main};
use engine::geom::HeightGrid;
use glam::{Vec2, Vec3};
use softwalk_systems::character::{Character, CharacterDesc, WalkPath, step_character};

fn character_step(c: &mut Criterion) {
    let ground = HeightGrid::from_fn(Vec2::new(-5.0, -5.0), 10.0 / 511.0, 512, 512, |x, z| {
        0.04 * (1.7 * x).sin() * (1.3 * z).cos()
    })
    .expect("a valid grid");
    let path = WalkPath::circle(Vec3::new(3.0, 0.0, 0.0), Vec3::Z, 3.0).expect("a valid path");
    let mut walker =
        Character::new(CharacterDesc::adult(), &path, &ground).expect("a valid character");
    c.bench_function("character_step_all_stages", |b| {
        b.iter(|| step_character(&mut walker, &path, &ground, 1.0 / 60.0))
    });
}

criterion_group!(benches, character_step);
criterion_main!(benches);
