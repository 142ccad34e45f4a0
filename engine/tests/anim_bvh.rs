//! BVH import and retargeting: a small hand-written CMU-named BVH loads, drives
//! the default human's legs through the bone maps (scaled by leg length), and
//! bad BVH files are refused with their typed errors.

mod anim_support;

use std::path::Path;

use engine::anim::bvh::{BvhError, load_bvh, load_bvh_from_str};
use engine::anim::gltf::load_gltf;
use engine::anim::{
    BoneMap, BoneRole, Playback, RetargetError, RigChains, RigError, RigPreset, retarget,
};
use engine::glam::Vec3;

fn walk_path() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/walk_small.bvh")
}

fn walk_text() -> String {
    std::fs::read_to_string(walk_path()).unwrap()
}

#[test]
fn small_bvh_loads_with_its_hierarchy_and_frames() {
    let bvh = load_bvh(&walk_path()).unwrap();
    assert_eq!(bvh.skeleton.len(), 12);
    assert_eq!(bvh.frames, 2);
    assert_eq!(bvh.frame_time, 0.5);
    assert_eq!(bvh.clip.name(), "walk_small");
    assert_eq!(bvh.clip.duration(), 0.5);
    let map = BoneMap::detect(&bvh.skeleton);
    assert_eq!(map.preset, Some(RigPreset::Bvh));
    let chains = RigChains::find(&bvh.skeleton, &map).unwrap();
    assert_eq!(
        bvh.skeleton.joints()[chains.left.toe.unwrap()].name,
        "LeftToeBase"
    );
    assert_eq!(chains.spine.len(), 3);
    // Frame 1 turns LeftUpLeg -90 degrees about x: the knee swings forward (+z).
    let pose = bvh.clip.pose_at(0.5, Playback::Once, &bvh.skeleton);
    let mut globals = Vec::new();
    pose.globals(&bvh.skeleton, &mut globals);
    let knee = globals[chains.left.knee].w_axis.truncate();
    let hip = globals[chains.left.hip].w_axis.truncate();
    assert!(
        (knee - hip).normalize().distance(Vec3::Z) < 1e-4,
        "{}",
        knee - hip
    );
    // The root's position channels move it 20 units along z.
    assert!((hip.z - 20.0).abs() < 1e-4);
}

#[test]
fn bvh_retargets_onto_the_default_human_by_bone_name() {
    let human = load_gltf(&anim_support::human_path()).unwrap();
    let bvh = load_bvh(&walk_path()).unwrap();
    let source_map = BoneMap::detect(&bvh.skeleton);
    let target_map = BoneMap::detect(&human.skeleton);
    let chains = RigChains::find(&human.skeleton, &target_map).unwrap();
    let clip = retarget(
        &bvh.skeleton,
        &source_map,
        &bvh.clip,
        &human.skeleton,
        &target_map,
    )
    .unwrap();
    let skeleton = &human.skeleton;
    let at = |time: f32| {
        let mut globals = Vec::new();
        clip.pose_at(time, Playback::Once, skeleton)
            .globals(skeleton, &mut globals);
        globals
    };
    let (rest, bent) = (at(0.0), at(0.5));
    let position = |g: &[engine::glam::Mat4], j: usize| g[j].w_axis.truncate();
    // Frame 0 is the source's rest (T-pose, legs straight down): the thigh points down.
    let down = (position(&rest, chains.left.knee) - position(&rest, chains.left.hip)).normalize();
    assert!(down.distance(-Vec3::Y) < 0.02, "{down}");
    // Frame 1: the left thigh points forward, the right one still down.
    let forward =
        (position(&bent, chains.left.knee) - position(&bent, chains.left.hip)).normalize();
    assert!(forward.distance(Vec3::Z) < 0.02, "{forward}");
    let right =
        (position(&bent, chains.right.knee) - position(&bent, chains.right.hip)).normalize();
    assert!(right.distance(-Vec3::Y) < 0.02, "{right}");
    // The pelvis moved 20 source units forward, scaled by leg length (80 units
    // in the BVH, the human's in metres).
    let leg = chains.leg_length(skeleton, &chains.left);
    let moved = position(&bent, chains.pelvis) - position(&rest, chains.pelvis);
    assert!(
        (moved.z - 20.0 * leg / 80.0).abs() < 0.02 * leg,
        "{moved} for leg {leg}"
    );
}

#[test]
fn missing_leg_bones_are_listed() {
    let text = walk_text()
        .replace("LeftFoot", "LeftPaw")
        .replace("RightLeg", "RightShin");
    let bvh = load_bvh_from_str(&text, Path::new("renamed.bvh")).unwrap();
    let map = BoneMap::from_preset(&bvh.skeleton, RigPreset::Bvh);
    let error = RigChains::find(&bvh.skeleton, &map).unwrap_err();
    let RigError::Missing { missing, .. } = &error else {
        panic!("{error}");
    };
    let roles: Vec<BoneRole> = missing.iter().map(|(r, _)| *r).collect();
    assert_eq!(roles, [BoneRole::FootL, BoneRole::CalfR]);
    let text = error.to_string();
    assert!(
        text.contains("FootL") && text.contains("LeftFoot"),
        "{text}"
    );
    let human = load_gltf(&anim_support::human_path()).unwrap();
    let target = BoneMap::detect(&human.skeleton);
    let refused = retarget(&bvh.skeleton, &map, &bvh.clip, &human.skeleton, &target).unwrap_err();
    assert!(matches!(
        refused,
        RetargetError::Source(RigError::Missing { .. })
    ));
}

#[test]
fn syntax_errors_name_the_line() {
    let text = walk_text().replacen("OFFSET 0.0 -40.0 0.0", "OFFSET 0.0 -40.0", 1);
    let error = load_bvh_from_str(&text, Path::new("bad.bvh")).unwrap_err();
    assert!(
        matches!(error, BvhError::Syntax { line: 13, .. }),
        "{error}"
    );
    assert!(error.to_string().starts_with("bad.bvh:13"), "{error}");
    let error = load_bvh_from_str("HIERARCHY\nROOT Hips\n{", Path::new("short.bvh")).unwrap_err();
    assert!(
        matches!(&error, BvhError::Syntax { found, .. } if found == "end of file"),
        "{error}"
    );
    let error = load_bvh_from_str("", Path::new("empty.bvh")).unwrap_err();
    assert!(matches!(error, BvhError::Syntax { .. }), "{error}");
}

#[test]
fn unknown_channels_are_refused() {
    let text = walk_text().replacen(
        "Zrotation Xrotation Yrotation",
        "Zrotation Wrotation Yrotation",
        1,
    );
    let error = load_bvh_from_str(&text, Path::new("bad.bvh")).unwrap_err();
    assert!(
        matches!(&error, BvhError::BadChannel { name, .. } if name == "Wrotation"),
        "{error}"
    );
}

#[test]
fn missing_or_extra_frame_values_are_refused() {
    let short = walk_text().replace("Frames: 2", "Frames: 3");
    let error = load_bvh_from_str(&short, Path::new("short.bvh")).unwrap_err();
    assert!(
        matches!(
            error,
            BvhError::FrameData {
                frames: 3,
                channels: 39,
                needed: 117,
                found: 78,
                ..
            }
        ),
        "{error}"
    );
    let long = walk_text().replace("Frames: 2", "Frames: 1");
    let error = load_bvh_from_str(&long, Path::new("long.bvh")).unwrap_err();
    assert!(
        matches!(error, BvhError::FrameData { frames: 1, .. }),
        "{error}"
    );
    let huge = walk_text().replace("Frames: 2", "Frames: 99999999999");
    let error = load_bvh_from_str(&huge, Path::new("huge.bvh")).unwrap_err();
    assert!(matches!(error, BvhError::Limit { .. }), "{error}");
}

#[test]
fn nan_values_and_bad_frame_times_are_refused() {
    let nan = walk_text().replacen("0 90 20", "0 NaN 20", 1);
    let error = load_bvh_from_str(&nan, Path::new("nan.bvh")).unwrap_err();
    assert!(matches!(error, BvhError::NonFinite { .. }), "{error}");
    let zero = walk_text().replace("Frame Time: 0.5", "Frame Time: 0");
    let error = load_bvh_from_str(&zero, Path::new("zero.bvh")).unwrap_err();
    assert!(matches!(error, BvhError::NonFinite { .. }), "{error}");
}

#[test]
fn missing_file_is_a_read_error() {
    let error = load_bvh(Path::new("no/such/clip.bvh")).unwrap_err();
    assert!(matches!(error, BvhError::Read { .. }), "{error}");
}

#[test]
fn every_truncation_is_an_error_never_a_panic() {
    let text = walk_text();
    for cut in (0..text.len()).filter(|&k| text.is_char_boundary(k)) {
        // Cutting inside the last value still parses (a shorter number).
        let result = load_bvh_from_str(&text[..cut], Path::new("cut.bvh"));
        assert!(
            result.is_err() || cut + 2 >= text.len(),
            "cut at {cut} loaded"
        );
    }
}

#[test]
fn mixamo_names_are_detected_whatever_the_namespace() {
    let mut text = walk_text();
    for name in [
        "Hips",
        "LeftUpLeg",
        "LeftLeg",
        "LeftFoot",
        "LeftToeBase",
        "RightUpLeg",
        "RightLeg",
        "RightFoot",
        "RightToeBase",
        "Spine",
        "Neck",
        "Head",
    ] {
        text = text.replace(&format!(" {name}\n"), &format!(" mixamorig1:{name}\n"));
    }
    let bvh = load_bvh_from_str(&text, Path::new("mixamo.bvh")).unwrap();
    assert_eq!(bvh.skeleton.joints()[1].name, "mixamorig1:LeftUpLeg");
    let map = BoneMap::detect(&bvh.skeleton);
    assert_eq!(map.preset, Some(RigPreset::Mixamo));
    let chains = RigChains::find(&bvh.skeleton, &map).unwrap();
    assert_eq!(
        bvh.skeleton.joints()[chains.right.knee].name,
        "mixamorig1:RightLeg"
    );
}

#[test]
fn custom_bone_names_map_any_rig() {
    let text = walk_text()
        .replace("LeftUpLeg", "hip.L")
        .replace("LeftLeg", "knee.L");
    let bvh = load_bvh_from_str(&text, Path::new("custom.bvh")).unwrap();
    assert!(RigChains::find(&bvh.skeleton, &BoneMap::detect(&bvh.skeleton)).is_err());
    let mut names: Vec<(BoneRole, String)> = BoneMap::from_preset(&bvh.skeleton, RigPreset::Bvh)
        .pairs()
        .iter()
        .map(|&(role, joint)| (role, bvh.skeleton.joints()[joint].name.clone()))
        .collect();
    names.push((BoneRole::ThighL, "hip.L".into()));
    names.push((BoneRole::CalfL, "knee.L".into()));
    let map = BoneMap::from_names(&bvh.skeleton, &names);
    assert_eq!(map.preset, None);
    let chains = RigChains::find(&bvh.skeleton, &map).unwrap();
    assert_eq!(bvh.skeleton.joints()[chains.left.knee].name, "knee.L");
}
