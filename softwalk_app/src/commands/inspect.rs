//! `softwalk inspect FILE`: what a character model (`.glb`/`.gltf`) or mocap
//! clip (`.bvh`) holds: its rig as a tree, its mesh, its clips, the bone map
//! detected and the leg chains and spine found through it, or what is missing;
//! for a model, also how it would stand as a character (units, facing, sizes)
//! or why it would be refused; for a clip, its walk cycle or why it is not a walk.

use std::io::Write;
use std::path::Path;

use engine::anim::bvh::load_bvh;
use engine::anim::gltf::load_gltf;
use engine::anim::{BoneMap, Clip, Model, RigChains, Skeleton, SkinnedMesh, Transform, WalkCycle};
use glam::Vec3;
use softwalk_systems::character::CharacterRig;

use crate::cli::{CliError, InspectArgs};

/// Prints the rig, the mesh (models only), the clips and the detected chains.
/// A file whose chains are not found still prints, ending with what is missing.
pub fn inspect(args: &InspectArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let text = describe(&args.file)?;
    out.write_all(text.as_bytes()).map_err(CliError::Stdout)
}

/// The report for one file, chosen by its extension.
fn describe(path: &Path) -> Result<String, CliError> {
    let extension = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    let mut text = String::new();
    match extension.as_deref() {
        Some("glb" | "gltf") => {
            let model = load_gltf(path).map_err(|e| CliError::Inspect(Box::new(e)))?;
            text.push_str(&format!("{}: glTF model\n", path.display()));
            text.push_str(&rig(&model.skeleton));
            text.push_str(&mesh(&model.mesh));
            text.push_str(&clips(&model.clips));
            text.push_str(&chains(&model.skeleton));
            text.push_str(&as_character(path, model));
        }
        Some("bvh") => {
            let bvh = load_bvh(path).map_err(|e| CliError::Inspect(Box::new(e)))?;
            text.push_str(&format!(
                "{}: BVH mocap, {} frames at {:.1} fps\n",
                path.display(),
                bvh.frames,
                1.0 / bvh.frame_time
            ));
            text.push_str(&rig(&bvh.skeleton));
            text.push_str(&clips(std::slice::from_ref(&bvh.clip)));
            text.push_str(&chains(&bvh.skeleton));
            text.push_str(&walk_cycle(&bvh.skeleton, &bvh.clip));
        }
        _ => {
            return Err(CliError::UnknownFileKind {
                path: path.to_path_buf(),
            });
        }
    }
    Ok(text)
}

/// The joints as an indented tree, parents first.
fn rig(skeleton: &Skeleton) -> String {
    let mut text = format!("rig: {} joints\n", skeleton.len());
    for (k, joint) in skeleton.joints().iter().enumerate() {
        let depth = std::iter::successors(joint.parent, |&p| skeleton.joints()[p].parent).count();
        let t = joint.rest.translation;
        text.push_str(&format!(
            "  {:indent$}{} [{k}]  offset ({:.3}, {:.3}, {:.3})\n",
            "",
            joint.name,
            t.x,
            t.y,
            t.z,
            indent = 2 * depth
        ));
    }
    text
}

fn mesh(mesh: &SkinnedMesh) -> String {
    let influences = mesh
        .weights()
        .iter()
        .map(|w| w.iter().filter(|&&x| x > 0.0).count())
        .max()
        .unwrap_or(0);
    format!(
        "mesh: {} vertices, {} triangles, up to {influences} joints per vertex\n",
        mesh.vertex_count(),
        mesh.triangle_count()
    )
}

fn clips(clips: &[Clip]) -> String {
    if clips.is_empty() {
        return "clips: none\n".to_string();
    }
    let mut text = format!("clips: {}\n", clips.len());
    for clip in clips {
        text.push_str(&format!(
            "  {:?}: {:.3} s, {} channels\n",
            clip.name(),
            clip.duration(),
            clip.channels().len()
        ));
    }
    text
}

/// The clip read as a walk (its cycle), or why it is not one.
fn walk_cycle(skeleton: &Skeleton, clip: &Clip) -> String {
    match WalkCycle::analyse(clip, skeleton, &BoneMap::detect(skeleton)) {
        Ok(c) => format!(
            "walk cycle: {:.3} s ({:.0} steps/min), duty {:.2}, stride {:.3} ({:.2} leg lengths), \
             speed {:.3} per s, left heel strike at {:.3} s, right at phase {:.2}\n",
            c.period,
            c.cadence(),
            c.duty,
            c.stride,
            c.stride / c.leg_length,
            c.speed,
            c.left_strike,
            c.right_phase
        ),
        Err(e) => format!("not a walk clip: {e}\n"),
    }
}

/// The detected bone map, then the chains or what is missing.
fn chains(skeleton: &Skeleton) -> String {
    let map = BoneMap::detect(skeleton);
    let preset = map
        .preset
        .map_or_else(|| "none".to_string(), |p| format!("{p:?}"));
    let mut text = format!("bone names: {preset} ({} roles mapped)\n", map.len());
    let name = |j: usize| skeleton.joints()[j].name.as_str();
    match RigChains::find(skeleton, &map) {
        Ok(c) => {
            for (side, leg) in [("left", c.left), ("right", c.right)] {
                text.push_str(&format!(
                    "{side} leg: hip {}, knee {}, ankle {}, toe {} ({:.3} long)\n",
                    name(leg.hip),
                    name(leg.knee),
                    name(leg.ankle),
                    leg.toe.map_or("none (optional)", name),
                    c.leg_length(skeleton, &leg)
                ));
            }
            let spine: Vec<&str> = c.spine.iter().map(|&j| name(j)).collect();
            text.push_str(&format!(
                "spine: {} -> {}\n",
                name(c.pelvis),
                spine.join(" -> ")
            ));
        }
        Err(e) => text.push_str(&format!("leg chains not found: {e}\n")),
    }
    text
}

/// How the model stands as a character: the armature root's turn and scale,
/// the units told from its height, where it faces, its sizes in metres; or
/// why a scene would refuse it.
fn as_character(path: &Path, model: Model) -> String {
    let mut text = root_transform(&model.skeleton);
    let map = BoneMap::detect(&model.skeleton);
    match CharacterRig::new(&path.display().to_string(), model, map) {
        Ok(rig) => {
            let forward = rig.rest_frame().z_axis;
            text.push_str(&format!(
                "as a character: units {} (stands {:.2} m, hips {:.2} m), faces {}, Y up, \
                 {} + {} sole vertices; scaled to the scene's height when it walks\n",
                rig.units(),
                rig.height(),
                rig.hip_height(),
                facing(forward),
                rig.sole_vertices()[0].len(),
                rig.sole_vertices()[1].len(),
            ));
        }
        Err(e) => text.push_str(&format!("refused as a character: {e}\n")),
    }
    text
}

/// The root joint's rest rotation and scale when they are not the identity
/// (an armature turned from Z up, or scaled from centimetres).
fn root_transform(skeleton: &Skeleton) -> String {
    let Some(root) = skeleton.joints().first() else {
        return String::new();
    };
    let Transform {
        rotation, scale, ..
    } = root.rest;
    let mut parts = Vec::new();
    let (axis, angle) = rotation.to_axis_angle();
    if angle.abs() > 1e-3 {
        parts.push(format!(
            "turned {:.0} degrees about ({:.2}, {:.2}, {:.2})",
            angle.to_degrees(),
            axis.x,
            axis.y,
            axis.z
        ));
    }
    if !scale.abs_diff_eq(Vec3::ONE, 1e-4) {
        parts.push(format!("scaled ({}, {}, {})", scale.x, scale.y, scale.z));
    }
    if parts.is_empty() {
        return String::new();
    }
    format!("root {}: {}\n", root.name, parts.join(", "))
}

/// The axis a rest-pose forward direction is nearest, with its angle off it.
fn facing(forward: Vec3) -> String {
    let axes = [
        ("+Z", Vec3::Z),
        ("-Z", Vec3::NEG_Z),
        ("+X", Vec3::X),
        ("-X", Vec3::NEG_X),
    ];
    let (name, axis) = axes
        .iter()
        .max_by(|a, b| forward.dot(a.1).total_cmp(&forward.dot(b.1)))
        .copied()
        .unwrap_or(axes[0]);
    let off = forward.angle_between(axis).to_degrees();
    format!("{name} ({off:.0} degrees off)")
}
