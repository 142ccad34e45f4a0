//! Every built-in scene becomes a simulation through `Scene::build_sim` and runs.

use demos::scene::{Scene, builtin_scenes};
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
