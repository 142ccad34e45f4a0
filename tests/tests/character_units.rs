//! Character construction, paths and outputs: errors name their field, curved
//! paths turn the motion plane, the end of a path stops the walk, walking off
//! the terrain stays finite, and the mesh and metrics are consistent.

use engine::geom::HeightGrid;
use glam::{Vec2, Vec3};
use softwalk_systems::character::{
    Bone, Character, CharacterDesc, CharacterError, PathSegment, WalkPath, character_mesh,
    step_character,
};
use softwalk_systems::foot::FootPhase;
use softwalk_systems::ground::FlatGround;

const DT: f32 = 1.0 / 60.0;

fn field_of(desc: CharacterDesc) -> &'static str {
    let path = WalkPath::straight(Vec3::ZERO, Vec3::Z, 1.0).unwrap();
    match Character::new(desc, &path, &FlatGround(0.0)) {
        Err(CharacterError::InvalidField { field, .. }) => field,
        other => panic!("expected an invalid field, got {other:?}"),
    }
}

#[test]
fn bad_descriptions_name_the_field() {
    let adult = CharacterDesc::adult();
    assert_eq!(
        field_of(CharacterDesc {
            height: 0.0,
            ..adult
        }),
        "height"
    );
    assert_eq!(
        field_of(CharacterDesc {
            height: -1.7,
            ..adult
        }),
        "height"
    );
    assert_eq!(field_of(CharacterDesc { mass: 0.0, ..adult }), "mass");
    assert_eq!(
        field_of(CharacterDesc {
            alpha: f32::NAN,
            ..adult
        }),
        "alpha"
    );
    assert_eq!(
        field_of(CharacterDesc {
            beta: f32::INFINITY,
            ..adult
        }),
        "beta"
    );
    assert_eq!(
        field_of(CharacterDesc {
            leg_length_factor: 0.2,
            ..adult
        }),
        "leg_length_factor"
    );
    assert_eq!(
        field_of(CharacterDesc {
            proxy_mass: -1.0,
            ..adult
        }),
        "proxy_mass"
    );
}

#[test]
fn descriptions_round_trip_through_serde_with_defaults() {
    let desc: CharacterDesc = serde_json::from_str(r#"{ "height": 1.2, "mass": 25.0 }"#).unwrap();
    assert_eq!(desc, CharacterDesc::new(1.2, 25.0));
    let text = serde_json::to_string(&CharacterDesc::long_legged()).unwrap();
    let back: CharacterDesc = serde_json::from_str(&text).unwrap();
    assert_eq!(back, CharacterDesc::long_legged());
    assert!(serde_json::from_str::<CharacterDesc>(r#"{ "height": 1.2 }"#).is_err());
}

#[test]
fn a_curved_path_turns_the_motion_plane() {
    let quarter = PathSegment::Arc {
        radius: 2.0,
        angle: std::f32::consts::FRAC_PI_2,
    };
    let segments = vec![
        PathSegment::Straight { length: 1.0 },
        quarter,
        PathSegment::Straight { length: 3.0 },
    ];
    let path = WalkPath::new(Vec3::ZERO, Vec3::Z, segments, false).unwrap();
    let ground = FlatGround(0.0);
    let mut c = Character::new(CharacterDesc::adult(), &path, &ground).unwrap();
    step_character(&mut c, &path, &ground, DT);
    // Facing +Z the motion plane's normal (the right) is -X.
    assert!(c.proxy.axis.distance(Vec3::NEG_X) < 1e-3);
    while c.gait.distance < 1.0 + std::f32::consts::PI + 1.0 {
        step_character(&mut c, &path, &ground, DT);
    }
    // After a left quarter turn the character faces +X and its right is +Z.
    assert!(
        c.proxy.axis.distance(Vec3::Z) < 1e-3,
        "axis {}",
        c.proxy.axis
    );
    assert!(c.pose.forward.distance(Vec3::X) < 1e-3);
}

#[test]
fn the_walk_ends_with_both_feet_planted_side_by_side() {
    let path = WalkPath::straight(Vec3::ZERO, Vec3::Z, 4.0).unwrap();
    let ground = FlatGround(0.3);
    let mut c = Character::new(CharacterDesc::adult(), &path, &ground).unwrap();
    for _ in 0..(8.0 / DT) as usize {
        step_character(&mut c, &path, &ground, DT);
    }
    assert!(c.gait.stopped);
    assert!(
        c.feet
            .iter()
            .all(|f| f.contact && f.phase == FootPhase::Stance)
    );
    for f in &c.feet {
        assert!((f.sole.center().y - 0.3).abs() < 1e-4);
        assert!(f.velocity.length() < 1e-4);
    }
}

#[test]
fn walking_off_the_terrain_keeps_the_last_height_without_nan() {
    let grid = HeightGrid::new(Vec2::new(-2.0, -2.0), 0.1, 41, 41, 0.5).unwrap();
    let path = WalkPath::straight(Vec3::ZERO, Vec3::Z, 6.0).unwrap();
    let mut c = Character::new(CharacterDesc::adult(), &path, &grid).unwrap();
    for _ in 0..(7.0 / DT) as usize {
        step_character(&mut c, &path, &grid, DT);
        assert!(c.pose.joints.iter().all(|j| j.is_finite()));
        assert!(c.proxy.tilt.is_finite());
    }
    assert!(!c.rays.feet[0].hit && c.gait.distance > 5.9);
    assert!((c.feet[0].sole.center().y - 0.5).abs() < 1e-4);
}

#[test]
fn mesh_parts_and_pose_transforms_match() {
    let path = WalkPath::straight(Vec3::ZERO, Vec3::Z, 3.0).unwrap();
    let ground = FlatGround(0.0);
    let mut c = Character::new(CharacterDesc::child(), &path, &ground).unwrap();
    for _ in 0..30 {
        step_character(&mut c, &path, &ground, DT);
    }
    let mesh = character_mesh(&c.body);
    let transforms = c.pose.part_transforms();
    assert_eq!(mesh.parts.len(), transforms.len());
    for (part, (bone, m)) in mesh.parts.iter().zip(Bone::ALL.iter().zip(&transforms)) {
        assert_eq!(part.name, bone.name());
        // Local +Y times the bone length lands on the bone's second joint.
        let (_, b) = bone.joints();
        let tip = m.transform_point3(Vec3::Y * c.body.bone_length(*bone));
        assert!(
            tip.distance(c.pose.joint(b)) < 1e-3,
            "{} off by {}",
            part.name,
            tip.distance(c.pose.joint(b))
        );
    }
}

#[test]
fn lowering_beta_makes_the_body_swing_less() {
    let path = WalkPath::straight(Vec3::ZERO, Vec3::Z, 12.0).unwrap();
    let ground = FlatGround(0.0);
    let swing = |beta: f32| {
        let mut c = Character::new(CharacterDesc::adult(), &path, &ground).unwrap();
        c.balance.set_gains(30.0, beta).unwrap();
        let tilts: Vec<f32> = (0..420)
            .map(|_| {
                step_character(&mut c, &path, &ground, DT);
                c.metrics.tilt
            })
            .skip(120)
            .collect();
        tilts.iter().cloned().fold(f32::MIN, f32::max)
            - tilts.iter().cloned().fold(f32::MAX, f32::min)
    };
    assert!(swing(4.0) < swing(6.0));
}

#[test]
fn same_inputs_give_bit_identical_walks() {
    let path = WalkPath::circle(Vec3::ZERO, Vec3::Z, 2.5).unwrap();
    let ground = FlatGround(0.0);
    let run = || {
        let mut c = Character::new(CharacterDesc::tall(), &path, &ground).unwrap();
        for _ in 0..300 {
            step_character(&mut c, &path, &ground, DT);
        }
        c
    };
    assert_eq!(run(), run());
}

#[test]
fn a_raised_key_under_a_swing_foot_lifts_it_and_bends_the_knee_more() {
    use softwalk_systems::character::{
        balance_stage, foot_ik_stage, foot_raycast_stage, gait_stage,
    };
    let path = WalkPath::straight(Vec3::ZERO, Vec3::Z, 6.0).unwrap();
    let ground = FlatGround(0.0);
    let mut c = Character::new(CharacterDesc::adult(), &path, &ground).unwrap();
    // Walk until the left foot is in its upward swing.
    while c.gait.feet[0].phase != FootPhase::SwingUp || c.gait.distance < 1.0 {
        step_character(&mut c, &path, &ground, DT);
    }
    let pose_with = |platform: f32| {
        let mut c = c.clone();
        gait_stage(&mut c.gait, &c.body, &path, &c.modifiers, DT);
        foot_raycast_stage(&mut c.rays, &c.gait, &c.body, &ground);
        // Stage 3 stand-in: a virtual platform raises the left key.
        c.rays.feet[0].point.y += platform;
        balance_stage(&mut c.proxy, &c.balance, &c.body, &c.gait, &c.rays, DT);
        let feet = foot_ik_stage(
            &mut c.ik,
            &mut c.pose,
            &c.body,
            &c.gait,
            &mut c.rays,
            &c.proxy,
            DT,
        );
        // The target rises with the key; the foot follows it as fast as the
        // knee may bend (see `MAX_KNEE_SPEED`).
        assert!(feet[0].sole.center().y <= c.ik.sole_targets[0].y + 1e-4);
        (c.ik.sole_targets[0].y, c.pose.knee_flexion()[0])
    };
    let (low_y, low_knee) = pose_with(0.0);
    let (high_y, high_knee) = pose_with(0.15);
    assert!((high_y - low_y - 0.15).abs() < 1e-3, "{low_y} -> {high_y}");
    assert!(
        high_knee > low_knee + 0.05,
        "knee {low_knee} -> {high_knee}"
    );
}
