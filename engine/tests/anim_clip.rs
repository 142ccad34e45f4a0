//! Clip sampling: step, linear and cubic-spline channels on translations and
//! rotations, holding before and after the keys, looping, and refused channels.

use engine::anim::{
    AnimError, Channel, Clip, Interpolation, Joint, Playback, Property, Skeleton, Transform,
};
use engine::glam::{Mat4, Quat, Vec3, Vec4};

fn v(x: f32) -> Vec4 {
    Vec4::new(x, 0.0, 0.0, 0.0)
}

fn translation(interpolation: Interpolation, values: Vec<Vec4>) -> Channel {
    Channel::new(
        0,
        Property::Translation,
        interpolation,
        vec![0.0, 1.0, 3.0],
        values,
    )
    .unwrap()
}

fn near(a: f32, b: f32) -> bool {
    (a - b).abs() < 1e-5
}

#[test]
fn step_holds_each_key_until_the_next() {
    let c = translation(Interpolation::Step, vec![v(0.0), v(10.0), v(20.0)]);
    for (t, x) in [
        (-1.0, 0.0),
        (0.0, 0.0),
        (0.99, 0.0),
        (1.0, 10.0),
        (2.9, 10.0),
        (3.0, 20.0),
        (9.0, 20.0),
    ] {
        assert!(near(c.sample(t).x, x), "t {t}: {}", c.sample(t).x);
    }
}

#[test]
fn linear_draws_straight_lines_between_keys() {
    let c = translation(Interpolation::Linear, vec![v(0.0), v(10.0), v(20.0)]);
    for (t, x) in [
        (-1.0, 0.0),
        (0.25, 2.5),
        (1.0, 10.0),
        (2.0, 15.0),
        (3.0, 20.0),
        (4.0, 20.0),
    ] {
        assert!(near(c.sample(t).x, x), "t {t}: {}", c.sample(t).x);
    }
}

#[test]
fn linear_rotation_is_a_slerp() {
    let q1 = Quat::from_rotation_y(std::f32::consts::FRAC_PI_2);
    let c = Channel::new(
        0,
        Property::Rotation,
        Interpolation::Linear,
        vec![0.0, 1.0],
        vec![Vec4::from(Quat::IDENTITY), Vec4::from(q1)],
    )
    .unwrap();
    let half = Quat::from_vec4(c.sample(0.5));
    assert!(half.angle_between(Quat::from_rotation_y(std::f32::consts::FRAC_PI_4)) < 1e-5);
}

#[test]
fn cubic_spline_follows_the_hermite_curve() {
    // Keys (in-tangent, value, out-tangent) at t = 0 and t = 2.
    let times = vec![0.0, 2.0];
    let flat = Channel::new(
        0,
        Property::Translation,
        Interpolation::CubicSpline,
        times.clone(),
        vec![v(0.0), v(0.0), v(0.0), v(0.0), v(1.0), v(0.0)],
    )
    .unwrap();
    // Zero tangents: smoothstep, 3s^2 - 2s^3.
    assert!(near(flat.sample(1.0).x, 0.5));
    assert!(near(flat.sample(0.5).x, 3.0 * 0.0625 - 2.0 * 0.015625));
    assert!(near(flat.sample(2.0).x, 1.0));
    assert!(near(flat.sample(5.0).x, 1.0));
    // Tangents of 0.5 per second over a 2 s interval: the straight line x = t / 2.
    let straight = Channel::new(
        0,
        Property::Translation,
        Interpolation::CubicSpline,
        times,
        vec![v(0.5), v(0.0), v(0.5), v(0.5), v(1.0), v(0.5)],
    )
    .unwrap();
    for t in [0.3, 0.8, 1.5] {
        assert!(near(straight.sample(t).x, t / 2.0), "t {t}");
    }
}

#[test]
fn cubic_spline_rotation_stays_a_unit_quaternion() {
    let q1 = Vec4::from(Quat::from_rotation_x(1.0));
    let zero = Vec4::ZERO;
    let c = Channel::new(
        0,
        Property::Rotation,
        Interpolation::CubicSpline,
        vec![0.0, 1.0],
        vec![zero, Vec4::from(Quat::IDENTITY), zero, zero, q1, zero],
    )
    .unwrap();
    for t in [0.1, 0.5, 0.9] {
        assert!(near(c.sample(t).length(), 1.0));
    }
}

fn one_joint() -> Skeleton {
    Skeleton::new(vec![Joint {
        name: "root".into(),
        parent: None,
        rest: Transform::from_translation(Vec3::new(0.0, 1.0, 0.0)),
        inverse_bind: Mat4::IDENTITY,
    }])
    .unwrap()
}

#[test]
fn clips_loop_or_hold_and_only_touch_animated_properties() {
    let skeleton = one_joint();
    let clip = Clip::new(
        "slide".into(),
        vec![
            Channel::new(
                0,
                Property::Scale,
                Interpolation::Linear,
                vec![0.0, 2.0],
                vec![Vec4::new(1.0, 1.0, 1.0, 0.0), Vec4::new(3.0, 1.0, 1.0, 0.0)],
            )
            .unwrap(),
        ],
        1,
    )
    .unwrap();
    assert_eq!(clip.duration(), 2.0);
    assert!(near(clip.local_time(5.0, Playback::Loop), 1.0));
    assert!(near(clip.local_time(-0.5, Playback::Loop), 1.5));
    assert!(near(clip.local_time(5.0, Playback::Once), 2.0));
    let looped = clip.pose_at(5.0, Playback::Loop, &skeleton);
    assert!(near(looped.locals[0].scale.x, 2.0));
    assert_eq!(looped.locals[0].translation, Vec3::new(0.0, 1.0, 0.0));
    let held = clip.pose_at(5.0, Playback::Once, &skeleton);
    assert!(near(held.locals[0].scale.x, 3.0));
}

#[test]
fn bad_channels_and_clips_are_refused() {
    let keys = |times: Vec<f32>, values: Vec<Vec4>, i| {
        Channel::new(0, Property::Translation, i, times, values)
    };
    assert!(matches!(
        keys(vec![0.0, 1.0], vec![v(0.0)], Interpolation::Linear),
        Err(AnimError::Length { .. })
    ));
    assert!(matches!(
        keys(
            vec![0.0, 1.0],
            vec![v(0.0), v(1.0)],
            Interpolation::CubicSpline
        ),
        Err(AnimError::Length { .. })
    ));
    assert!(matches!(
        keys(vec![], vec![], Interpolation::Step),
        Err(AnimError::Length { .. })
    ));
    assert!(matches!(
        keys(vec![1.0, 0.0], vec![v(0.0), v(1.0)], Interpolation::Linear),
        Err(AnimError::KeyOrder { key: 1, .. })
    ));
    assert!(matches!(
        keys(
            vec![0.0, 1.0],
            vec![v(0.0), v(f32::NAN)],
            Interpolation::Linear
        ),
        Err(AnimError::NonFinite { .. })
    ));
    let far = Channel::new(
        4,
        Property::Scale,
        Interpolation::Step,
        vec![0.0],
        vec![v(1.0)],
    )
    .unwrap();
    assert!(matches!(
        Clip::new("far".into(), vec![far], 1),
        Err(AnimError::ChannelJoint {
            joint: 4,
            joints: 1
        })
    ));
}

#[test]
fn skeletons_need_parents_before_children() {
    let joint = |name: &str, parent| Joint {
        name: name.into(),
        parent,
        rest: Transform::IDENTITY,
        inverse_bind: Mat4::IDENTITY,
    };
    assert!(matches!(
        Skeleton::new(vec![joint("a", Some(1)), joint("b", None)]),
        Err(AnimError::ParentOrder { joint: 0, .. })
    ));
    assert!(matches!(
        Skeleton::new(vec![joint("a", Some(0))]),
        Err(AnimError::ParentOrder { joint: 0, .. })
    ));
    let s = Skeleton::new(vec![joint("a", None), joint("b", Some(0))]).unwrap();
    assert!(s.is_ancestor(0, 1));
    assert!(!s.is_ancestor(1, 0));
    assert_eq!(s.children(0).collect::<Vec<_>>(), [1]);
}
