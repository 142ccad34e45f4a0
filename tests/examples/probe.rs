use glam::Vec3;
use softwalk_systems::character::*;
use softwalk_systems::ground::FlatGround;
fn main() {
    let g = FlatGround(1.0);
    let path = WalkPath::straight(Vec3::new(1.0, 0.0, 1.5), Vec3::X, 6.0).unwrap();
    let mut c = Character::new(CharacterDesc::adult(), &path, &g).unwrap();
    println!("hip height {} leg reach {}", c.body.hip_height, c.body.leg_reach());
    for i in 0..300 {
        step_character(&mut c, &path, &g, 1.0 / 60.0);
        if i % 10 == 0 {
            let m = c.metrics;
            println!("{i} pelvis {:.3} knees {:.2} {:.2} feet {:.3} {:.3} contact {:?} drop {:.3}", m.pelvis_y, m.knee_flexion[0], m.knee_flexion[1], m.feet[0].y, m.feet[1].y, m.contact, c.ik.pelvis_drop);
        }
    }
}
