//! The paper's vegetation claims (§3.2, §4) as measurable checks:
//! claim 2 (platforms), claim 4 (the deformation field), claim 5 (recovery).

use glam::{Vec2, Vec3};
use softwalk_systems::foot::{FootPhase, FootSole, FootState, Side};
use softwalk_systems::ground::{FlatGround, Ground};
use softwalk_systems::vegetation::{
    Bend, GrassPatch, GrassSettings, PlatformGround, PlatformPhase, VirtualPlatform, XzRect,
};

const GROUND_Y: f32 = 0.2;

fn foot_at(centre: Vec3, phase: FootPhase) -> FootState {
    FootState {
        side: Side::Left,
        sole: FootSole {
            heel: centre - Vec3::new(0.0, 0.0, 0.12),
            toe: centre + Vec3::new(0.0, 0.0, 0.12),
            width: 0.09,
        },
        ankle: centre + Vec3::new(0.0, 0.08, -0.06),
        velocity: Vec3::ZERO,
        phase,
        contact: phase == FootPhase::Stance,
        pressing: phase == FootPhase::Stance,
    }
}

/// A synthetic walk of one foot: stance, swing up, swing down (1 s per cycle),
/// with the animated sole height of the swing; returns (phase, animated height above ground).
fn synthetic_foot(t: f32) -> (FootPhase, f32) {
    let c = t.rem_euclid(1.0);
    if c < 0.4 {
        (FootPhase::Stance, 0.0)
    } else if c < 0.7 {
        (FootPhase::SwingUp, (c - 0.4) / 0.3 * 0.35)
    } else {
        (FootPhase::SwingDown, (1.0 - c) / 0.3 * 0.35)
    }
}

#[test]
fn claim2_platform_stays_below_a_third_and_follows_the_paper_order() {
    for settings in [GrassSettings::small(), GrassSettings::medium()] {
        let ground = FlatGround(GROUND_Y);
        let patch = GrassPatch::with_height_fn(
            XzRect::new(Vec2::new(-5.0, -5.0), Vec2::new(5.0, 5.0)),
            GrassSettings {
                density: 1.0,
                ..settings
            },
            |_, _| Some(GROUND_Y),
        )
        .unwrap();
        let platform_settings = settings.platform;
        let mut platform = VirtualPlatform::new(Side::Left);
        let dt = 1.0 / 60.0;
        let mut sole_y = GROUND_Y;
        let mut max_height = 0.0_f32;
        let mut uplifted = false;
        for step in 0..(4 * 60) {
            let t = step as f32 * dt;
            let (phase, anim) = synthetic_foot(t);
            let x = -1.0 + 0.6 * t;
            let foot = foot_at(Vec3::new(x, sole_y, 0.0), phase);
            let ground_y = ground.cast_down(x, 0.0, 10.0).unwrap().point.y;
            let veg = patch.height_at(x, 0.0);
            platform.update(&foot, ground_y, veg, dt, &platform_settings);
            let top = platform.top(&platform_settings);
            let tops: Vec<_> = top.into_iter().collect();
            // The foot ray sees the platform; IK puts the sole on max(animation, hit).
            let seen = PlatformGround {
                ground: &ground,
                platforms: &tops,
            }
            .cast_down(x, 0.0, 10.0)
            .unwrap()
            .point
            .y;
            let anim_y = GROUND_Y + anim;
            uplifted |= seen > anim_y + 1e-3 && phase != FootPhase::Stance;
            sole_y = anim_y.max(seen);
            let h = platform.height();
            max_height = max_height.max(h);
            assert!(
                h <= settings.height / 3.0 + 1e-6,
                "step {step}: platform {h} above a third of {}",
                settings.height
            );
            if let Some(top) = top {
                assert!((top.top_y - (GROUND_Y + h)).abs() < 1e-6);
            }
        }
        assert!(
            (max_height - settings.height / 3.0).abs() < 1e-4,
            "reaches the top: {max_height}"
        );
        assert!(
            uplifted,
            "the platform lifted the foot above its animated path at least once"
        );
        use PlatformPhase::*;
        let log: Vec<_> = platform.phase_log().collect();
        let cycle = [Rising, Holding, Falling, Idle];
        assert_eq!(log[0], Idle);
        assert_eq!(log.len(), 1 + 4 * cycle.len(), "{log:?}");
        for (k, chunk) in log[1..].chunks(4).enumerate() {
            assert_eq!(chunk, cycle, "walk step {k}: {log:?}");
        }
    }
}

fn grass(area_half: f32, settings: GrassSettings) -> GrassPatch {
    let area = XzRect::new(Vec2::splat(-area_half), Vec2::splat(area_half));
    GrassPatch::new(area, settings, &FlatGround(GROUND_Y)).unwrap()
}

/// Distance from `foot` to the blade's vertical segment.
fn segment_distance(patch: &GrassPatch, i: usize, foot: Vec3) -> f32 {
    let b = patch.blades()[i];
    let y = foot.y.clamp(b.root.y, b.root.y + b.height);
    Vec3::new(b.root.x, y, b.root.z).distance(foot)
}

#[test]
fn claim4_planted_foot_pushes_nearby_blades_down_and_away_and_leaves_far_ones() {
    let mut patch = grass(1.5, GrassSettings::small());
    let foot = Vec3::new(0.1, GROUND_Y + 0.05, -0.2);
    let radius = patch.t_max() / patch.gamma();
    patch.deform(&[foot_at(foot, FootPhase::Stance)], 1.0 / 60.0);
    let (mut pushed, mut untouched) = (0, 0);
    for i in 0..patch.blade_count() {
        let blade = patch.blades()[i];
        let [_, mid, tip] = patch.blade_points(i);
        let bend = patch.bend(i);
        if segment_distance(&patch, i, foot) >= radius {
            assert_eq!(bend, Bend::ZERO, "blade {i} beyond t_max/gamma was moved");
            assert_eq!(patch.state(i).treads, 0);
            untouched += 1;
            continue;
        }
        for (rest, now) in [(blade.rest_mid(), mid), (blade.rest_tip(), tip)] {
            let away = (rest - foot).with_y(0.0);
            if now != rest {
                assert!(now.y < rest.y, "blade {i}: not lowered {rest} -> {now}");
                assert!(
                    (now - foot).with_y(0.0).length() >= away.length() - 1e-6,
                    "blade {i}: moved towards the foot {rest} -> {now}"
                );
            }
        }
        if bend.mid.length() > 0.0 {
            pushed += 1;
            let horizontal = bend.mid.with_y(0.0);
            assert!(bend.mid.y < 0.0);
            assert!(horizontal.dot((blade.root - foot).with_y(0.0)) >= 0.0);
        }
    }
    assert!(
        pushed > 100 && untouched > 1000,
        "pushed {pushed}, untouched {untouched}"
    );
}

/// Runs the scripted scene at `rate` Hz and returns every blade's points at
/// each probe time (seconds, multiples of 1/30).
fn run_scene(rate: u32, probes: &[u32]) -> Vec<Vec<[Vec3; 3]>> {
    let mut patch = grass(1.0, GrassSettings::small());
    let dt = 1.0 / rate as f32;
    let a = Vec3::new(0.0, GROUND_Y + 0.03, 0.0);
    let b = Vec3::new(0.35, GROUND_Y + 0.2, 0.25);
    let mut out = Vec::new();
    let last = *probes.last().unwrap();
    // Integer time in 1/120 s ticks, so every rate samples the same instants.
    let ticks_per_step = 120 / rate;
    let mut tick = 0;
    while tick < last * 4 {
        tick += ticks_per_step;
        // Foot A planted during (0, 1] s, foot B during (0.5, 1.5] s.
        let mut feet = Vec::new();
        if tick <= 120 {
            feet.push(a);
        }
        if tick > 60 && tick <= 180 {
            feet.push(b);
        }
        patch.deform_points(&feet, dt);
        if probes.contains(&(tick / 4)) && tick % 4 == 0 {
            out.push(
                (0..patch.blade_count())
                    .map(|i| patch.blade_points(i))
                    .collect(),
            );
        }
    }
    out
}

#[test]
fn claim5_recovery_is_the_same_at_30_60_and_120_hz() {
    // Probe times in 1/30 s: 1.0, 1.5, 2.0, 3.0 s.
    let probes = [30, 45, 60, 90];
    let reference = run_scene(120, &probes);
    assert_eq!(reference.len(), probes.len());
    let moved = reference[1]
        .iter()
        .zip(reference[0].iter())
        .filter(|(a, b)| a != b)
        .count();
    assert!(moved > 50, "blades move between probes: {moved}");
    for rate in [30, 60] {
        let other = run_scene(rate, &probes);
        let mut worst = 0.0_f32;
        for (frame_a, frame_b) in reference.iter().zip(&other) {
            for (pa, pb) in frame_a.iter().zip(frame_b) {
                for k in 0..3 {
                    worst = worst.max((pa[k] - pb[k]).abs().max_element());
                }
            }
        }
        assert!(worst <= 1e-4, "{rate} Hz differs from 120 Hz by {worst} m");
    }
}

#[test]
fn claim5_elastic_blade_recovers_in_its_documented_time_and_broken_one_stays_down() {
    let settings = GrassSettings::small();
    let mut patch = grass(1.0, settings);
    // The foot lands: down through the grass in 0.3 s, then planted for 0.2 s.
    let dt = 1.0 / 60.0;
    for step in 0..30 {
        let y = GROUND_Y + 0.03 + 0.7 * (1.0 - step as f32 / 18.0).max(0.0);
        patch.deform_points(&[Vec3::new(0.0, y, 0.0)], dt);
    }
    let released = patch.time();
    // The most bent blade that is still elastic, and the most bent broken one.
    let by_bend = |broken: bool| {
        (0..patch.blade_count())
            .filter(|&i| patch.state(i).broken == broken && patch.bend(i).size() > 0.0)
            .max_by(|&a, &b| patch.bend(a).size().total_cmp(&patch.bend(b).size()))
            .unwrap()
    };
    let elastic = by_bend(false);
    let broken = by_bend(true);
    let elastic_held = patch.bend(elastic).tip.length();
    let broken_held = patch.bend(broken);
    assert!(
        elastic_held > 0.05,
        "elastic blade visibly bent: {elastic_held}"
    );
    let documented = settings.recovery_time() / patch.blades()[elastic].stiffness;
    let mut before = None;
    while patch.time() - released < documented as f64 + 1e-3 {
        if before.is_none() && patch.time() - released > 0.8 * documented as f64 {
            before = Some(patch.bend(elastic).tip.length());
        }
        patch.deform_points(&[], dt);
    }
    let after = patch.bend(elastic).tip.length();
    assert!(
        after <= 0.05 * elastic_held,
        "{after} left of {elastic_held}"
    );
    assert!(
        before.unwrap() > 0.05 * elastic_held,
        "not yet recovered earlier"
    );
    for _ in 0..(20 * 60) {
        patch.deform_points(&[], dt);
    }
    assert_eq!(patch.bend(elastic), Bend::ZERO, "settled exactly upright");
    let stays = patch.bend(broken);
    // A broken blade keeps `broken_residual` of the largest bend it took.
    assert_eq!(stays, patch.state(broken).rest);
    assert!(
        stays.size() >= settings.broken_residual * broken_held.size() - 1e-6,
        "broken blade keeps its residual bend: {stays:?} of {broken_held:?}"
    );
    let rest_tip = patch.blades()[broken].rest_tip();
    assert!(
        patch.blade_points(broken)[2].y < rest_tip.y - 0.05,
        "trail stays visible"
    );
    assert_eq!(patch.active_count(), 0, "everything settled");
}

#[test]
fn blades_trodden_several_times_break() {
    let settings = GrassSettings::small();
    let mut patch = grass(1.0, settings);
    // A light touch: a foot high above the ground only brushes the tips.
    let foot = Vec3::new(0.0, GROUND_Y + 0.8, 0.0);
    let touched = |p: &GrassPatch| {
        (0..p.blade_count())
            .filter(|&i| p.state(i).treads > 0)
            .collect::<Vec<_>>()
    };
    patch.deform_points(&[foot], 0.1);
    let first = touched(&patch);
    assert!(!first.is_empty());
    assert!(
        first.iter().any(|&i| !patch.state(i).broken),
        "a light touch does not break all"
    );
    for _ in 1..settings.treads_to_break {
        patch.deform_points(&[], 1.0);
        patch.deform_points(&[foot], 0.1);
    }
    for &i in &first {
        let s = patch.state(i);
        if s.treads >= settings.treads_to_break {
            assert!(s.broken, "blade {i} trodden {} times", s.treads);
        }
    }
    assert!(
        first
            .iter()
            .all(|&i| patch.state(i).treads == settings.treads_to_break)
    );
}

#[test]
fn work_per_step_does_not_grow_with_the_patch() {
    let settings = GrassSettings {
        density: 250.0,
        ..GrassSettings::small()
    };
    let feet = [
        Vec3::new(0.3, GROUND_Y, 0.0),
        Vec3::new(-0.3, GROUND_Y + 0.15, 0.4),
    ];
    let visited = |half: f32| {
        let mut patch = grass(half, settings);
        (0..10)
            .map(|_| patch.deform_points(&feet, 0.02).visited)
            .sum::<usize>()
    };
    let small = visited(5.0);
    let large = visited(20.0);
    assert!(small > 0);
    assert!(
        (large as f32) < 1.5 * small as f32,
        "16x the blades, visited {large} vs {small}"
    );
}
