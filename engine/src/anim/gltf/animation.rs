use glam::Vec4;
use gltf::animation::{Interpolation as GltfInterpolation, Property as GltfProperty};
use gltf::json::validation::Checked;

use super::GltfError;
use super::accessor::AccessorReader;
use crate::anim::{Channel, Clip, Interpolation, Property};

/// The clip of `animation` over the joints `node_to_joint` names. Channels on
/// nodes outside the skeleton and morph-weight channels are skipped; an
/// animation left with no channel is refused with [`GltfError::ClipTargetsNoJoint`].
pub(super) fn clip(
    json: &gltf::json::Root,
    animation: &gltf::Animation,
    node_to_joint: &[Option<usize>],
    joint_count: usize,
    reader: &AccessorReader,
) -> Result<Clip, GltfError> {
    let name = animation
        .name()
        .map_or_else(|| format!("animation{}", animation.index()), str::to_string);
    let clip_part = format!("animation {} ({name:?})", animation.index());
    let mut channels = Vec::new();
    for (k, channel) in animation.channels().enumerate() {
        let part = format!("{clip_part} channel {k}");
        let (node, path) =
            checked_target(json, animation.index(), k).ok_or_else(|| GltfError::Invalid {
                path: reader.path.to_path_buf(),
                part: part.clone(),
                reason: "the target's node or path is not valid".to_string(),
            })?;
        let Some(joint) = node_to_joint.get(node).copied().flatten() else {
            continue;
        };
        let property = match path {
            GltfProperty::Translation => Property::Translation,
            GltfProperty::Rotation => Property::Rotation,
            GltfProperty::Scale => Property::Scale,
            GltfProperty::MorphTargetWeights => continue,
        };
        let sampler = channel.sampler();
        let interpolation = match sampler.interpolation() {
            GltfInterpolation::Step => Interpolation::Step,
            GltfInterpolation::Linear => Interpolation::Linear,
            GltfInterpolation::CubicSpline => Interpolation::CubicSpline,
        };
        let times: Vec<f32> = reader
            .floats::<1>(&sampler.input(), &format!("{part} input"))?
            .into_iter()
            .map(|[t]| t)
            .collect();
        let output = sampler.output();
        let output_part = format!("{part} output");
        let values: Vec<Vec4> = match property {
            Property::Rotation => reader
                .floats::<4>(&output, &output_part)?
                .into_iter()
                .map(Vec4::from)
                .collect(),
            Property::Translation | Property::Scale => reader
                .floats::<3>(&output, &output_part)?
                .into_iter()
                .map(|[x, y, z]| Vec4::new(x, y, z, 0.0))
                .collect(),
        };
        let channel = Channel::new(joint, property, interpolation, times, values)
            .map_err(|e| GltfError::from_anim(reader.path, &part, e))?;
        channels.push(channel);
    }
    if channels.is_empty() {
        return Err(GltfError::ClipTargetsNoJoint {
            path: reader.path.to_path_buf(),
            part: clip_part,
        });
    }
    Clip::new(name, channels, joint_count)
        .map_err(|e| GltfError::from_anim(reader.path, &clip_part, e))
}

/// The node index and path of channel `k` of animation `a`, read from the JSON
/// and checked there: the `gltf` crate's validation skips channel targets, and
/// its accessors panic on an unknown path or a node out of range.
fn checked_target(json: &gltf::json::Root, a: usize, k: usize) -> Option<(usize, GltfProperty)> {
    let target = &json.animations.get(a)?.channels.get(k)?.target;
    let node = target.node.value();
    match target.path {
        Checked::Valid(path) if node < json.nodes.len() => Some((node, path)),
        _ => None,
    }
}
