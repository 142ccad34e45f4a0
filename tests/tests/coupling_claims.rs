//! The two-way coupling, measured on the full pipeline: deformed ground and
//! grass change the gait (loose-ground claim 4, vegetation claims 1 and 3).

use softwalk_systems::sim::sole_ends;
use softwalk_systems::vegetation::GrassSettings;
use softwalk_tests::{TestScene, build, mean, std_dev, walk};

const STEPS: usize = 300; // 5 s at 60 Hz
const SETTLE: usize = 60; // skip the first second (start-up transient)

#[test]
fn snow_lowers_the_pelvis_and_bends_the_knees_more_than_rigid_ground() {
    let run = |material| {
        let mut app = build(&TestScene::flat(material));
        walk(&mut app, STEPS)
    };
    let (snow, rigid) = (run("snow"), run("rigid"));
    let pelvis = |m: &[softwalk_systems::sim::WalkerMetrics]| {
        mean(m[SETTLE..].iter().map(|s| s.character.pelvis_y))
    };
    // The more bent knee each step: the swing leg lifting out of the print.
    let knees = |m: &[softwalk_systems::sim::WalkerMetrics]| {
        mean(
            m[SETTLE..]
                .iter()
                .map(|s| s.character.knee_flexion[0].max(s.character.knee_flexion[1])),
        )
    };
    println!(
        "pelvis: snow {:.4} rigid {:.4}; knees: snow {:.4} rigid {:.4}",
        pelvis(&snow),
        pelvis(&rigid),
        knees(&snow),
        knees(&rigid)
    );
    assert!(
        pelvis(&snow) < pelvis(&rigid) - 0.02,
        "the pelvis is lower on snow"
    );
    assert!(knees(&snow) > knees(&rigid), "the knees bend more on snow");
}

#[test]
fn planted_feet_stand_on_the_carved_surface() {
    let mut app = build(&TestScene::flat("snow"));
    let mut worst = 0.0f32;
    let mut planted_steps = 0;
    for step in 0..STEPS {
        let metrics = walk(&mut app, 1)[0];
        if step < SETTLE {
            continue; // the start-up transient: the first prints being pressed
        }
        // Heights after this step's carving: the print the foot pressed.
        let grid = {
            let ground = app.world.resource::<softwalk_systems::sim::GroundState>();
            ground.terrain().grid().clone()
        };
        for k in 0..2 {
            if metrics.character.planted[k] {
                // The sole's lowest point stands on the print's floor. Its
                // tip lies on the print's wall, which the grid draws as a
                // one-cell slope, so the floor is read under the tip and under
                // the centre of the sole's rounded end there, the lower.
                let p = metrics.character.feet[k];
                let [heel, toe] = sole_ends(&metrics.character.soles[k]);
                let end = if heel.y < toe.y { heel } else { toe };
                let height = |q: glam::Vec3| grid.height_at(q.x, q.z).unwrap();
                let ground = height(p).min(height(end));
                worst = worst.max((p.y - ground).abs());
                planted_steps += 1;
            }
        }
    }
    println!("worst stance gap {worst:.4} m over {planted_steps} planted foot-steps");
    assert!(planted_steps > 100);
    // Within one cell of the 10 m / 512 grid: a heel striking with its toe
    // up has its tip on the print's wall.
    assert!(
        worst <= 0.02,
        "a planted sole is {worst} m off the carved ground"
    );
}

/// Peak swing clearance (sole above the real ground) and peak knee flexion.
fn swing_peaks(grass: Option<GrassSettings>) -> (f32, f32, f32) {
    let scene = TestScene {
        grass,
        ..TestScene::flat("rigid")
    };
    let mut app = build(&scene);
    let metrics = walk(&mut app, STEPS);
    let ground_y = 1.0;
    let mut clearance = 0.0f32;
    let mut knee = 0.0f32;
    for m in &metrics[SETTLE..] {
        for k in 0..2 {
            if !m.character.contact[k] {
                clearance = clearance.max(m.character.feet[k].y - ground_y);
            }
            knee = knee.max(m.character.knee_flexion[k]);
        }
    }
    let tilts: Vec<f32> = metrics[SETTLE..].iter().map(|m| m.character.tilt).collect();
    (clearance, knee, std_dev(&tilts))
}

#[test]
fn knees_rise_higher_in_taller_grass_and_the_body_swings_less() {
    let (bare_clear, bare_knee, bare_swing) = swing_peaks(None);
    let (small_clear, small_knee, _) = swing_peaks(Some(GrassSettings::small()));
    let (medium_clear, medium_knee, medium_swing) = swing_peaks(Some(GrassSettings::medium()));
    println!("clearance: bare {bare_clear:.3} small {small_clear:.3} medium {medium_clear:.3}");
    println!("knee: bare {bare_knee:.3} small {small_knee:.3} medium {medium_knee:.3}");
    println!("tilt std: bare {bare_swing:.5} medium {medium_swing:.5}");
    assert!(
        small_clear > bare_clear && medium_clear > small_clear,
        "swing clearance grows with grass height"
    );
    assert!(
        small_knee > bare_knee && medium_knee > small_knee,
        "knee flexion grows with grass height"
    );
    assert!(
        medium_swing < bare_swing,
        "the body swings less in medium grass"
    );
}
