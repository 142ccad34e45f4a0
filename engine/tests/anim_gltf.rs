//! glTF import: a hand-built two-bone skinned triangle with a clip loads from
//! `.gltf` (data URI) and `.glb`, poses to hand-computed vertex positions, and
//! each kind of bad file is refused with its typed error.

mod anim_support;

use std::path::Path;

use anim_support::TwoBones;
use engine::anim::gltf::{GltfError, load_gltf, load_gltf_from_slice};
use engine::anim::{Model, Playback, SkinnedVertices, skin, skin_matrices, skin_serial};
use engine::glam::Vec3;

fn load(model: &TwoBones) -> Result<Model, GltfError> {
    load_gltf_from_slice(model.gltf_text().as_bytes(), Path::new("two_bones.gltf"))
}

/// The mesh skinned at `time` seconds into the first clip.
fn posed(model: &Model, time: f32) -> SkinnedVertices {
    let pose = model.clips[0].pose_at(time, Playback::Once, &model.skeleton);
    let mut globals = Vec::new();
    pose.globals(&model.skeleton, &mut globals);
    let mut matrices = Vec::new();
    skin_matrices(&model.skeleton, &globals, &mut matrices);
    let mut out = SkinnedVertices::default();
    skin(&model.mesh, &matrices, &mut out).unwrap();
    let mut serial = SkinnedVertices::default();
    skin_serial(&model.mesh, &matrices, &mut serial).unwrap();
    assert_eq!(out, serial, "parallel and serial skinning agree");
    out
}

fn assert_near(found: Vec3, expected: Vec3) {
    assert!(
        found.distance(expected) < 1e-5,
        "found {found}, expected {expected}"
    );
}

#[test]
fn two_bones_load_with_rig_mesh_and_clip() {
    let model = load(&TwoBones::default()).unwrap();
    let names: Vec<&str> = model
        .skeleton
        .joints()
        .iter()
        .map(|j| j.name.as_str())
        .collect();
    assert_eq!(names, ["root", "tip"]);
    assert_eq!(model.skeleton.joints()[1].parent, Some(0));
    assert_eq!(model.mesh.vertex_count(), 3);
    assert_eq!(model.mesh.triangle_count(), 1);
    assert_eq!(model.mesh.joints()[1], [0, 1, 0, 0]);
    assert_eq!(model.clips.len(), 1);
    assert_eq!(model.clips[0].name(), "bend");
    assert_eq!(model.clips[0].duration(), 1.0);
}

#[test]
fn rest_pose_leaves_the_mesh_in_place() {
    let model = load(&TwoBones::default()).unwrap();
    let out = posed(&model, 0.0);
    for (p, q) in out.positions.iter().zip(model.mesh.positions()) {
        assert_near(*p, *q);
    }
    assert_near(out.normals[0], Vec3::Z);
}

#[test]
fn bent_tip_moves_vertices_to_hand_computed_places() {
    let model = load(&TwoBones::default()).unwrap();
    // t = 1: tip turned 90 degrees about +z at (0, 1, 0).
    // Vertex 2 (0.1, 2, 0) is (0.1, 1, 0) from the tip -> (-1, 0.1, 0) -> (-1, 1.1, 0).
    // Vertex 1 (0.1, 1, 0), half each: root keeps it, tip moves it to (0, 1.1, 0).
    let out = posed(&model, 1.0);
    assert_near(out.positions[0], Vec3::new(0.1, 0.0, 0.0));
    assert_near(out.positions[1], Vec3::new(0.05, 1.05, 0.0));
    assert_near(out.positions[2], Vec3::new(-1.0, 1.1, 0.0));
    // t = 0.5: 45 degrees (slerp): (0.1, 1) -> (0.1c - s, 0.1s + c) + (0, 1).
    let h = std::f32::consts::FRAC_1_SQRT_2;
    let out = posed(&model, 0.5);
    assert_near(out.positions[2], Vec3::new(-0.9 * h, 1.0 + 1.1 * h, 0.0));
    // Normals along +z stay along +z under a turn about +z.
    assert_near(out.normals[2], Vec3::Z);
}

#[test]
fn glb_file_loads_like_the_gltf_text() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("two_bones.glb");
    std::fs::write(&path, TwoBones::default().glb()).unwrap();
    let from_glb = load_gltf(&path).unwrap();
    let from_text = load(&TwoBones::default()).unwrap();
    assert_eq!(from_glb, from_text);
}

#[test]
fn gltf_with_a_buffer_file_next_to_it_loads() {
    let dir = tempfile::tempdir().unwrap();
    let (json, bin) = TwoBones::default().build(Some("two_bones.bin"));
    std::fs::write(dir.path().join("two_bones.bin"), bin).unwrap();
    let path = dir.path().join("two_bones.gltf");
    std::fs::write(&path, json).unwrap();
    assert_eq!(load_gltf(&path).unwrap().mesh.vertex_count(), 3);
}

#[test]
fn missing_skin_is_refused() {
    let model = TwoBones {
        skinned: false,
        ..TwoBones::default()
    };
    let error = load(&model).unwrap_err();
    assert!(matches!(error, GltfError::MissingSkin { .. }), "{error}");
    assert!(error.to_string().contains("two_bones.gltf"), "{error}");
}

#[test]
fn weights_not_summing_to_one_are_refused() {
    let mut model = TwoBones::default();
    model.weights[1] = [0.5, 0.3, 0.0, 0.0];
    let error = load(&model).unwrap_err();
    assert!(
        matches!(error, GltfError::WeightSum { vertex: 1, .. }),
        "{error}"
    );
    assert!(error.to_string().contains("WEIGHTS") || error.to_string().contains("mesh 0"));
}

#[test]
fn joints_out_of_range_are_refused() {
    let mut model = TwoBones::default();
    model.joints[2] = [7, 0, 0, 0];
    let error = load(&model).unwrap_err();
    assert!(
        matches!(
            error,
            GltfError::JointOutOfRange {
                vertex: 2,
                joint: 7,
                joints: 2,
                ..
            }
        ),
        "{error}"
    );
}

#[test]
fn clip_targeting_no_joint_is_refused() {
    let model = TwoBones {
        channel_target: 2,
        ..TwoBones::default()
    };
    let error = load(&model).unwrap_err();
    assert!(
        matches!(error, GltfError::ClipTargetsNoJoint { .. }),
        "{error}"
    );
    assert!(error.to_string().contains("bend"), "{error}");
}

#[test]
fn nan_values_are_refused() {
    let mut model = TwoBones::default();
    model.positions[1][1] = f32::NAN;
    let error = load(&model).unwrap_err();
    assert!(
        matches!(&error, GltfError::NonFinite { part, index: 1, .. } if part.contains("POSITION")),
        "{error}"
    );
    let mut clip = TwoBones::default();
    clip.rotations[1][0] = f32::INFINITY;
    let error = load(&clip).unwrap_err();
    assert!(
        matches!(&error, GltfError::NonFinite { part, .. } if part.contains("output")),
        "{error}"
    );
}

#[test]
fn buffer_shorter_than_its_accessor_is_refused() {
    let model = TwoBones {
        position_count: 4,
        ..TwoBones::default()
    };
    let error = load(&model).unwrap_err();
    assert!(
        matches!(
            &error,
            GltfError::BufferTooShort { part, needed: 48, available: 36, .. } if part.contains("POSITION")
        ),
        "{error}"
    );
}

#[test]
fn glb_cut_short_is_refused_without_panicking() {
    let glb = TwoBones::default().glb();
    for cut in [0, 11, 20, glb.len() / 2, glb.len() - 4] {
        let error = load_gltf_from_slice(&glb[..cut], Path::new("cut.glb")).unwrap_err();
        assert!(
            matches!(
                error,
                GltfError::Malformed { .. } | GltfError::BufferTooShort { .. }
            ),
            "cut at {cut}: {error}"
        );
    }
}

#[test]
fn remote_buffer_uris_are_refused() {
    let (json, _) = TwoBones::default().build(Some("https://example.com/x.bin"));
    let error = load_gltf_from_slice(json.as_bytes(), Path::new("remote.gltf")).unwrap_err();
    assert!(matches!(error, GltfError::Unsupported { .. }), "{error}");
}

#[test]
fn missing_file_is_a_read_error() {
    let error = load_gltf(Path::new("no/such/model.glb")).unwrap_err();
    assert!(matches!(error, GltfError::Read { .. }), "{error}");
    assert!(error.to_string().contains("no/such/model.glb"));
}

#[test]
fn every_single_byte_corruption_is_an_error_or_a_model_never_a_panic() {
    let glb = TwoBones::default().glb();
    for k in 0..glb.len() {
        for flip in [0xFFu8, 0x01, 0x80] {
            let mut bytes = glb.clone();
            bytes[k] ^= flip;
            // Any result is fine; a panic fails the test.
            let _ = load_gltf_from_slice(&bytes, Path::new("flipped.glb"));
        }
    }
}
