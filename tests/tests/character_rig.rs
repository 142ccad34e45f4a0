//! The loaded character: the built-in human driven by the walking biped.
//! Its skinned soles stay on the ground during stance, the rig's feet land
//! where the driver's IK put them, and scenes refuse bad models and bone
//! tables with errors naming the field.

use engine::anim::{SkinnedVertices, skin};
use engine::ecs::Entity;
use engine::schedule::App;
use glam::{Affine3A, Mat4, Vec3};
use softwalk_systems::character::{CharacterBody, CharacterRig, Pose, RigPose};
use softwalk_systems::foot::FootPhase;
use softwalk_systems::sim::{Feet, run_steps};

use softwalk_app::scene::Scene;

/// Most accepted gap between the skinned sole and the ground during stance, metres.
const SOLE_GAP_GOAL_M: f32 = 0.01;
/// Most accepted slide of a touching skinned sole vertex over one stance,
/// metres (the driver's own sole is held to the same figure).
const SOLE_SLIDE_GOAL_M: f32 = 0.01;
/// A sole vertex this close above the sole's lowest vertex touches the ground, metres.
const TOUCH_M: f32 = 0.01;
/// Length of the measured walks, seconds.
const WALK_S: f64 = 5.0;

/// The skinned mesh of `entity`'s rig as the world poses it now.
struct Skinner {
    rig: CharacterRig,
    globals: Vec<Mat4>,
    matrices: Vec<Affine3A>,
    out: SkinnedVertices,
}

impl Skinner {
    fn new(rig: CharacterRig) -> Skinner {
        Skinner {
            rig,
            globals: Vec::new(),
            matrices: Vec::new(),
            out: SkinnedVertices::default(),
        }
    }

    fn pose(&mut self, app: &App, entity: Entity) -> RigPose {
        let body = app.world.get::<CharacterBody>(entity).unwrap();
        let pose = app.world.get::<Pose>(entity).unwrap();
        let feet = app.world.get::<Feet>(entity).unwrap();
        let rig_pose = RigPose::drive(&self.rig, &body, &pose, &feet.0);
        rig_pose.skin_matrices(&self.rig, &mut self.globals, &mut self.matrices);
        skin(&self.rig.model().mesh, &self.matrices, &mut self.out).unwrap();
        rig_pose
    }
}

/// Worst sole gap and slide over a stance in one walk.
#[derive(Debug, Default)]
struct SoleFigures {
    /// Largest distance of the skinned sole's lowest vertex from the driver's sole plane.
    gap: f32,
    /// Largest slide of a touching skinned sole vertex over one stance (see [`StanceSlide`]).
    slide: f32,
    /// The same slide of the driver's own sole (heel, centre, toe).
    driver_slide: f32,
    /// Steps measured in stance.
    stance_steps: usize,
}

/// Slide of one stance so far: how far any point of the sole has moved
/// horizontally, while it touches the ground (within [`TOUCH_M`] of the
/// lowest point), from where it first touched it in this stance. A foot that
/// rolls from heel to toe touches with other points in turn and does not
/// slide; a point that touches and moves does.
#[derive(Default)]
struct StanceSlide {
    first_touch: Vec<Option<Vec3>>,
    worst: f32,
}

impl StanceSlide {
    fn add(&mut self, points: Vec<Vec3>) -> f32 {
        self.first_touch.resize(points.len(), None);
        let floor = points.iter().map(|p| p.y).fold(f32::INFINITY, f32::min);
        for (first, p) in self.first_touch.iter_mut().zip(&points) {
            if p.y < floor + TOUCH_M {
                let at = *first.get_or_insert(*p);
                self.worst = self
                    .worst
                    .max(((*p - at) * Vec3::new(1.0, 0.0, 1.0)).length());
            }
        }
        self.worst
    }
}

fn measure_soles(scene_name: &str) -> SoleFigures {
    let mut scene = Scene::builtin(scene_name).unwrap();
    scene.characters.truncate(1);
    let (mut app, walkers) = scene.build_sim().unwrap();
    let entity = walkers[0];
    let rig = app.world.get::<CharacterRig>(entity).unwrap().clone();
    let mut skinner = Skinner::new(rig.clone());
    let mut figures = SoleFigures::default();
    let mut slides: [[StanceSlide; 2]; 2] = Default::default();
    for _ in 0..scene.sim.steps_for(WALK_S) {
        run_steps(&mut app, 1).unwrap();
        skinner.pose(&app, entity);
        let feet = app.world.get::<Feet>(entity).unwrap().0;
        let right = app.world.get::<Pose>(entity).unwrap().right;
        for (k, foot) in feet.iter().enumerate() {
            if !(foot.contact && foot.phase == FootPhase::Stance) {
                slides[k] = Default::default();
                continue;
            }
            figures.stance_steps += 1;
            let sole: Vec<Vec3> = (rig.sole_vertices()[k].iter())
                .map(|&v| skinner.out.positions[v as usize])
                .collect();
            let along = (foot.sole.toe - foot.sole.heel).normalize();
            let normal = right.cross(along).normalize();
            let above = |p: &Vec3| (*p - foot.sole.heel).dot(normal);
            let lowest = sole.iter().map(above).fold(f32::INFINITY, f32::min);
            figures.gap = figures.gap.max(lowest.abs());
            figures.slide = figures.slide.max(slides[k][0].add(sole));
            let driver = vec![foot.sole.heel, foot.sole.center(), foot.sole.toe];
            figures.driver_slide = figures.driver_slide.max(slides[k][1].add(driver));
        }
    }
    figures
}

#[test]
fn the_skinned_soles_stay_on_the_ground_during_stance() {
    let mut failures = Vec::new();
    for name in ["sand-flat", "snow-up", "default"] {
        let f = measure_soles(name);
        println!(
            "{name}: skinned sole gap {:.2} cm, slide {:.2} cm (the driver's sole: {:.2} cm) over {} stance steps",
            100.0 * f.gap,
            100.0 * f.slide,
            100.0 * f.driver_slide,
            f.stance_steps
        );
        assert!(f.stance_steps > 100, "{name}: too few stance steps");
        if f.gap > SOLE_GAP_GOAL_M
            || f.slide > SOLE_SLIDE_GOAL_M
            || f.driver_slide > SOLE_SLIDE_GOAL_M
        {
            failures.push(format!("{name}: {f:?}"));
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

#[test]
fn a_standing_driver_puts_the_rig_on_its_soles_and_its_hips_on_the_driver_s() {
    let scene = Scene::builtin("sand-flat").unwrap();
    let (app, walkers) = scene.build_sim().unwrap();
    let rig = app.world.get::<CharacterRig>(walkers[0]).unwrap().clone();
    let pose = Skinner::new(rig.clone()).pose(&app, walkers[0]);
    let chains = rig.chains();
    let driver = app.world.get::<Pose>(walkers[0]).unwrap();
    let hips = 0.5 * (pose.positions[chains.left.hip] + pose.positions[chains.right.hip]);
    let pelvis = driver.joint(softwalk_systems::character::Joint::Pelvis);
    assert!(hips.distance(pelvis) < 1e-4, "{hips} vs {pelvis}");
    let body = app.world.get::<CharacterBody>(walkers[0]).unwrap();
    assert!((pose.scale * rig.hip_height() - body.hip_height).abs() < 1e-4);
    // Scaled to the driver's hips, the human stands within 10 % of its height.
    let height = pose.scale * rig.height();
    assert!((height / body.desc.height - 1.0).abs() < 0.1, "{height}");
}

#[test]
fn scenes_refuse_bad_models_and_bone_tables_naming_the_field() {
    let base = Scene::builtin("sand-flat").unwrap();
    let check = |edit: &dyn Fn(&mut Scene), field: &str, words: &str| {
        let mut scene = base.clone();
        edit(&mut scene);
        let e = scene.validate().unwrap_err();
        assert_eq!(e.field(), Some(field), "{e}");
        assert!(e.to_string().contains(words), "{e}");
    };
    check(
        &|s| s.characters[0].model = "no/such/hero.glb".into(),
        "characters[0].model",
        "does not exist",
    );
    check(
        &|s| {
            s.characters[0]
                .bones
                .insert("thigh_x".into(), "thigh_l".into());
        },
        "characters[0].bones.thigh_x",
        "unknown role",
    );
    check(
        &|s| {
            s.characters[0]
                .bones
                .insert("thigh_l".into(), "UpperLeg.L".into());
        },
        "characters[0].bones.thigh_l",
        "no bone named \"UpperLeg.L\"",
    );
    check(
        &|s| {
            s.characters[0].model = "mannequin".into();
            s.characters[0].bones.insert("head".into(), "head".into());
        },
        "characters[0].bones.head",
        "mannequin",
    );
    // Naming a role with a bone of the wrong chain breaks the legs.
    check(
        &|s| {
            s.characters[0].bones.insert("calf_l".into(), "head".into());
        },
        "characters[0].model",
        "does not descend",
    );
}

#[test]
fn the_mannequin_has_no_rig_and_the_default_is_the_human() {
    let mut scene = Scene::builtin("sand-flat").unwrap();
    assert_eq!(scene.characters[0].model, "human");
    scene.characters[0].model = "mannequin".into();
    let (app, walkers) = scene.build_sim().unwrap();
    assert!(app.world.get::<CharacterRig>(walkers[0]).is_err());
}
