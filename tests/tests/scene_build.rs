//! Every built-in scene becomes a simulation through `Scene::build_sim` and runs.

use softwalk_app::paper::gait_quality::{GaitQuality, LEVEL_WALK_FIGURE};
use softwalk_app::scene::{Scene, builtin_scenes};
use softwalk_systems::sim::{CharacterName, WalkerMetrics, run_steps};

/// Steps each built-in scene is run for (2 s at 60 Hz).
const STEPS: u64 = 120;

#[test]
fn every_builtin_scene_builds_and_runs_120_steps() {
    for b in builtin_scenes() {
        let scene = Scene::builtin(&b.name).unwrap();
        let (mut app, walkers) = scene
            .build_sim()
            .unwrap_or_else(|e| panic!("{}: {e}", b.name));
        let names: Vec<String> = walkers
            .iter()
            .map(|e| app.world.get::<CharacterName>(*e).unwrap().0.clone())
            .collect();
        let expected: Vec<String> = scene.characters.iter().map(|c| c.name.clone()).collect();
        assert_eq!(names, expected, "{}: entities in scene order", b.name);
        let com = |app: &engine::schedule::App, k: usize| {
            app.world
                .get::<WalkerMetrics>(walkers[k])
                .unwrap()
                .character
                .com
        };
        let before: Vec<_> = (0..walkers.len()).map(|k| com(&app, k)).collect();
        run_steps(&mut app, STEPS).unwrap_or_else(|e| panic!("{}: {e}", b.name));
        assert_eq!(app.steps_done(), STEPS, "{}", b.name);
        for (k, start) in before.iter().enumerate() {
            let walked = (com(&app, k) - *start).length();
            assert!(walked > 1.0, "{} walker {k} moved only {walked} m", b.name);
        }
    }
}

/// The `props` scene: a walker in snow steps up onto a low rock (a prop
/// mesh, through the same ray-cast scene as the ground) and down again. Its
/// feet stand on the rock's top, and the pelvis never jumps: at most 3 cm
/// from one 60 Hz step to the next. The walk meets every gait goal but the
/// level-walk stance knee mean (stepping up bends the knee as on a stair).
#[test]
fn a_walker_steps_onto_a_rock_and_down_without_a_pelvis_pop() {
    let scene = Scene::builtin("props").unwrap();
    let rock = &scene.props[0];
    let (mut app, _) = scene.build_sim().unwrap();
    let steps = scene.steps() as usize;
    let metrics = softwalk_tests::walk(&mut app, steps);
    // Half the rock's length along the walk (0.45 m scaled), inset by a sole's half-length.
    let half = 0.45 * rock.scale - 0.13;
    let top = 0.12 * rock.scale - rock.sink;
    let on_rock = |p: glam::Vec3| (p.x - rock.at[0]).abs() < half && (p.z - rock.at[1]).abs() < 0.2;
    let planted_on_rock = (metrics.iter())
        .flat_map(|m| {
            (0..2)
                .filter(move |&f| m.character.planted[f])
                .map(move |f| m.character.feet[f])
        })
        .filter(|&p| on_rock(p))
        .count();
    assert!(
        planted_on_rock > 10,
        "{planted_on_rock} planted steps on the rock"
    );
    for m in &metrics {
        for f in 0..2 {
            let p = m.character.feet[f];
            if m.character.planted[f] && on_rock(p) {
                assert!(
                    p.y > top - 0.03,
                    "a planted foot at {p} is under the rock's top {top}"
                );
            }
        }
    }
    let past = metrics.last().unwrap().character.com.x;
    assert!(past > rock.at[0] + 0.8, "the walker stopped at x = {past}");
    let pop = (metrics.windows(2))
        .map(|w| (w[1].character.pelvis_y - w[0].character.pelvis_y).abs())
        .fold(0.0f32, f32::max);
    assert!(pop <= 0.03, "the pelvis moved {pop} m in one step");
    let q = GaitQuality::measure(&metrics, scene.sim.dt);
    println!("props: {q}");
    for g in q.goals().iter().filter(|g| g.figure != LEVEL_WALK_FIGURE) {
        assert!(g.met(), "props: {g}");
    }
}
