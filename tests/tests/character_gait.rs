//! A natural gait on flat ground: nearly straight stance knees, a clear swing
//! knee bend and a pelvis near its standing height, for a child, an adult and
//! a tall adult (default Froude number).

use glam::Vec3;
use softwalk_systems::character::{Character, CharacterDesc, WalkPath, step_character};
use softwalk_systems::ground::FlatGround;

const DT: f32 = 1.0 / 60.0;

/// What the gait figures of one walk are.
#[derive(Debug)]
struct GaitFigures {
    /// Mean knee flexion over every planted foot-step, radians.
    stance_knee: f32,
    /// Mean over the swings of each swing's peak knee flexion, radians.
    swing_knee_peak: f32,
    /// Mean pelvis height over the standing hip height.
    pelvis_ratio: f32,
}

/// Walks `desc` 8 s on flat ground and measures after the first 2 s.
fn figures(desc: CharacterDesc) -> GaitFigures {
    let ground = FlatGround(0.0);
    let path = WalkPath::straight(Vec3::ZERO, Vec3::Z, 30.0).unwrap();
    let mut c = Character::new(desc, &path, &ground).unwrap();
    let (mut stance_sum, mut stance_n) = (0.0f32, 0usize);
    let (mut pelvis_sum, mut pelvis_n) = (0.0f32, 0usize);
    let mut peaks: Vec<f32> = Vec::new();
    let mut current_peak = [None::<f32>; 2];
    for step in 0..(8.0 / DT) as usize {
        step_character(&mut c, &path, &ground, DT);
        if step < (2.0 / DT) as usize {
            continue;
        }
        let m = c.metrics;
        pelvis_sum += m.pelvis_y;
        pelvis_n += 1;
        for (k, peak) in current_peak.iter_mut().enumerate() {
            if m.contact[k] {
                stance_sum += m.knee_flexion[k];
                stance_n += 1;
                if let Some(p) = peak.take() {
                    peaks.push(p);
                }
            } else {
                let p = peak.get_or_insert(0.0);
                *p = p.max(m.knee_flexion[k]);
            }
        }
    }
    assert!(stance_n > 0 && peaks.len() >= 4, "too few steps measured");
    GaitFigures {
        stance_knee: stance_sum / stance_n as f32,
        swing_knee_peak: peaks.iter().sum::<f32>() / peaks.len() as f32,
        pelvis_ratio: pelvis_sum / pelvis_n as f32 / c.body.hip_height,
    }
}

#[test]
fn stance_knees_are_nearly_straight_swing_knees_bend_and_the_pelvis_rides_high() {
    let all: Vec<(&str, GaitFigures)> = [
        ("child", CharacterDesc::child()),
        ("adult", CharacterDesc::adult()),
        ("tall", CharacterDesc::tall()),
    ]
    .into_iter()
    .map(|(name, desc)| (name, figures(desc)))
    .collect();
    for (name, f) in &all {
        println!(
            "{name}: stance knee {:.3} rad, swing knee peak {:.3} rad, pelvis {:.3} x hip height",
            f.stance_knee, f.swing_knee_peak, f.pelvis_ratio
        );
    }
    for (name, f) in &all {
        assert!(f.stance_knee <= 0.35, "{name}: crouched stance {f:?}");
        assert!(
            (0.9..=1.3).contains(&f.swing_knee_peak),
            "{name}: swing knee {f:?}"
        );
        assert!(
            (0.9..=0.98).contains(&f.pelvis_ratio),
            "{name}: pelvis height {f:?}"
        );
    }
}
