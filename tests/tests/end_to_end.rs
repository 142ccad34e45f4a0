//! Every built-in scene runs a few seconds headless and passes sanity checks:
//! no NaN, planted feet on the ground, prints where the feet were.

use demos::scene::{Scene, builtin_scenes};
use demos::sim::{ObserverError, RunObserver, RunOptions, StepRecord, TerrainMoment, run};
use engine::geom::HeightGrid;

/// Keeps every record and the terrain before and after.
#[derive(Default)]
struct Recorder {
    records: Vec<StepRecord>,
    initial: Option<HeightGrid>,
    last: Option<HeightGrid>,
}

impl RunObserver for Recorder {
    fn on_step(&mut self, record: &StepRecord) -> Result<(), ObserverError> {
        self.records.push(*record);
        Ok(())
    }

    fn on_terrain(
        &mut self,
        moment: TerrainMoment,
        grid: &HeightGrid,
    ) -> Result<(), ObserverError> {
        match moment {
            TerrainMoment::Initial => self.initial = Some(grid.clone()),
            TerrainMoment::Final => self.last = Some(grid.clone()),
        }
        Ok(())
    }
}

fn finite(r: &StepRecord) -> bool {
    let scalars = [
        r.tilt,
        r.tilt_rate,
        r.torque,
        r.pelvis_y,
        r.target_y[0],
        r.target_y[1],
        r.knee[0],
        r.knee[1],
    ];
    r.com.is_finite()
        && r.feet.iter().all(|f| f.is_finite())
        && scalars.iter().all(|x| x.is_finite())
}

#[test]
fn every_builtin_scene_walks_sanely() {
    for builtin in builtin_scenes() {
        let scene = Scene::builtin(&builtin.name).unwrap();
        let mut options = RunOptions::from_scene(&scene);
        options.steps = options.steps.min(150);
        options.render = false;
        let mut rec = Recorder::default();
        run(&scene, &options, &mut rec).unwrap_or_else(|e| panic!("{}: {e}", builtin.name));
        let (before, after) = (rec.initial.unwrap(), rec.last.unwrap());
        assert_eq!(
            rec.records.len() as u64,
            options.steps * scene.characters.len() as u64
        );
        let mut lowered = 0;
        let mut planted = 0;
        for r in &rec.records {
            assert!(
                finite(r),
                "{}: non-finite metrics at step {}",
                builtin.name,
                r.step
            );
            for k in 0..2 {
                let f = r.feet[k];
                // A foot standing on a falling virtual platform is still above the grass.
                if !r.contacts[k] || r.platform_y[k].is_some() || !after.contains_xz(f.x, f.z) {
                    continue;
                }
                planted += 1;
                // A planted sole stands on the ground it carved: never below the
                // final surface by more than a print depth, never floating above
                // the original one.
                let top = before.height_at(f.x, f.z).unwrap();
                assert!(
                    f.y <= top + 0.02,
                    "{}: planted foot floats {} m",
                    builtin.name,
                    f.y - top
                );
                if after.height_at(f.x, f.z).unwrap() < top - 0.002 {
                    lowered += 1;
                }
            }
        }
        assert!(planted > 0, "{}: no foot was ever planted", builtin.name);
        assert!(
            lowered * 2 > planted,
            "{}: prints were left under only {lowered} of {planted} planted foot-steps",
            builtin.name
        );
    }
}
