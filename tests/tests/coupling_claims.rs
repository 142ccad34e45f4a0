//! The two-way coupling, measured on the full pipeline: deformed ground and
//! grass change the gait (loose-ground claim 4, vegetation claims 1 and 3).

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
fn stance_feet_follow_the_carved_surface() {
    let mut app = build(&TestScene::flat("snow"));
    let mut worst = 0.0f32;
    let mut planted_steps = 0;
    for _ in 0..STEPS {
        // Heights before this step's carving: what the foot rays see.
        let grid = {
            let mut q = app.world.query::<&softwalk_systems::terrain::Heightfield>();
            q.iter().next().unwrap().grid().clone()
        };
        let metrics = walk(&mut app, 1)[0];
        for k in 0..2 {
            if metrics.character.contact[k] {
                let p = metrics.character.feet[k];
                let ground = grid.height_at(p.x, p.z).unwrap();
                worst = worst.max((p.y - ground).abs());
                planted_steps += 1;
            }
        }
    }
    println!("worst stance gap {worst:.4} m over {planted_steps} planted foot-steps");
    assert!(planted_steps > 100);
    assert!(
        worst <= 0.01,
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
