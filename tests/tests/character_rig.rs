//! The loaded character: the built-in human driven by the walking biped.
//! Its skinned soles stay on the ground during stance, the rig's feet land
//! where the driver's IK put them, and scenes refuse bad models and bone
//! tables with errors naming the field.

use softwalk_app::scene::Scene;
use softwalk_systems::character::{CharacterBody, CharacterRig, Pose};
use softwalk_tests::sole_contact::{Skinner, walk_soles};

/// Length of the measured walks, seconds.
const WALK_S: f64 = 5.0;

#[test]
fn the_skinned_soles_stay_on_the_ground_during_stance() {
    let mut failures = Vec::new();
    for name in ["sand-flat", "snow-up", "default"] {
        let f = walk_soles(&Scene::builtin(name).unwrap(), WALK_S).soles;
        println!(
            "{name}: skinned sole gap {:.2} cm, slide {:.2} cm (the driver's sole: {:.2} cm) over {} stance steps",
            100.0 * f.gap,
            100.0 * f.slide,
            100.0 * f.driver_slide,
            f.stance_steps
        );
        assert!(f.stance_steps > 100, "{name}: too few stance steps");
        if !f.met() {
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
