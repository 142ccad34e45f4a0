use glam::{Mat4, Quat, Vec3, Vec4};
use thiserror::Error;

use super::{
    AnimError, BoneMap, BoneRole, Channel, Clip, Interpolation, Playback, Property, RigChains,
    RigError, Skeleton,
};

/// Most sample times a retargeted clip may have.
pub const MAX_RETARGET_KEYS: usize = 1 << 20;

/// Why a clip could not be retargeted.
#[derive(Debug, Error, PartialEq)]
pub enum RetargetError {
    /// The source rig's legs or spine were not found.
    #[error("source rig: {0}")]
    Source(#[source] RigError),
    /// The target rig's legs or spine were not found.
    #[error("target rig: {0}")]
    Target(#[source] RigError),
    /// A rig's legs have no length, so nothing can be scaled by them.
    #[error("the {which} rig's legs have zero length")]
    DegenerateLegs {
        /// `source` or `target`.
        which: &'static str,
    },
    /// The clip has more distinct key times than `MAX_RETARGET_KEYS`.
    #[error("the clip has {keys} key times, over the limit of {limit}")]
    TooManyKeys {
        /// Key times found.
        keys: usize,
        /// The limit.
        limit: usize,
    },
    /// The retargeted channels were refused.
    #[error("the retargeted clip is invalid: {0}")]
    Clip(#[source] AnimError),
}

/// One role mapped on both rigs.
struct Pair {
    source: usize,
    target: usize,
    /// Turns the target bone's rest direction onto the source bone's.
    correction: Quat,
}

/// `clip` (animating `source`) moved onto `target` by bone role: at each key
/// time of the clip, each mapped target bone takes the world-space rotation its
/// source bone made from the source rest pose (after turning the target's rest
/// bone direction onto the source's, so a T-pose clip drives an A-pose rig), and
/// the target pelvis moves as the source pelvis did, scaled by the ratio of leg
/// lengths. Unmapped target joints keep their rest transforms. Rest scales are
/// taken as 1.
pub fn retarget(
    source: &Skeleton,
    source_map: &BoneMap,
    clip: &Clip,
    target: &Skeleton,
    target_map: &BoneMap,
) -> Result<Clip, RetargetError> {
    let source_chains = RigChains::find(source, source_map).map_err(RetargetError::Source)?;
    let target_chains = RigChains::find(target, target_map).map_err(RetargetError::Target)?;
    let scale = leg_ratio(source, &source_chains, target, &target_chains)?;
    let times = key_times(clip)?;
    let source_rest = source.rest_globals();
    let target_rest = target.rest_globals();
    let pairs = pairs(source_map, target_map, &source_rest, &target_rest);
    let mut rotations = vec![Vec::with_capacity(times.len()); pairs.len()];
    let mut pelvis_track = Vec::with_capacity(times.len());
    let mut source_globals = Vec::new();
    for &t in &times {
        clip.pose_at(t, Playback::Once, source)
            .globals(source, &mut source_globals);
        let frame = TargetFrame::solve(
            target,
            &pairs,
            &source_rest,
            &source_globals,
            &target_rest,
            (source_chains.pelvis, target_chains.pelvis, scale),
        );
        for (track, rotation) in rotations.iter_mut().zip(frame.local_rotations) {
            track.push(rotation);
        }
        pelvis_track.push(frame.pelvis_translation);
    }
    let mut channels = Vec::with_capacity(pairs.len() + 1);
    for (pair, track) in pairs.iter().zip(rotations) {
        channels.push(rotation_channel(pair.target, &times, track)?);
    }
    let pelvis_values = pelvis_track.iter().map(|p| p.extend(0.0)).collect();
    channels.push(
        Channel::new(
            target_chains.pelvis,
            Property::Translation,
            Interpolation::Linear,
            times.clone(),
            pelvis_values,
        )
        .map_err(RetargetError::Clip)?,
    );
    Clip::new(clip.name().to_string(), channels, target.len()).map_err(RetargetError::Clip)
}

/// Target leg length over source leg length (both legs averaged).
fn leg_ratio(
    source: &Skeleton,
    source_chains: &RigChains,
    target: &Skeleton,
    target_chains: &RigChains,
) -> Result<f32, RetargetError> {
    let legs =
        |s: &Skeleton, c: &RigChains| 0.5 * (c.leg_length(s, &c.left) + c.leg_length(s, &c.right));
    let (from, to) = (legs(source, source_chains), legs(target, target_chains));
    if from <= 1e-6 {
        return Err(RetargetError::DegenerateLegs { which: "source" });
    }
    if to <= 1e-6 {
        return Err(RetargetError::DegenerateLegs { which: "target" });
    }
    Ok(to / from)
}

/// Every distinct key time of the clip, sorted.
fn key_times(clip: &Clip) -> Result<Vec<f32>, RetargetError> {
    let keys: usize = clip.channels().iter().map(|c| c.times().len()).sum();
    let mut times = Vec::with_capacity(keys.min(MAX_RETARGET_KEYS));
    for channel in clip.channels() {
        times.extend_from_slice(channel.times());
        times.sort_by(f32::total_cmp);
        times.dedup();
        if times.len() > MAX_RETARGET_KEYS {
            return Err(RetargetError::TooManyKeys {
                keys: times.len(),
                limit: MAX_RETARGET_KEYS,
            });
        }
    }
    if times.is_empty() {
        times.push(0.0);
    }
    Ok(times)
}

/// The roles mapped on both rigs, with their rest-direction corrections.
fn pairs(
    source_map: &BoneMap,
    target_map: &BoneMap,
    source_rest: &[Mat4],
    target_rest: &[Mat4],
) -> Vec<Pair> {
    let position = |globals: &[Mat4], j: usize| globals[j].w_axis.truncate();
    let direction = |map: &BoneMap, globals: &[Mat4], role: BoneRole| {
        let child = map.joint(role.child()?)?;
        let d = position(globals, child) - position(globals, map.joint(role)?);
        d.try_normalize()
    };
    target_map
        .pairs()
        .iter()
        .filter_map(|&(role, target)| {
            let source = source_map.joint(role)?;
            let correction = match (
                direction(target_map, target_rest, role),
                direction(source_map, source_rest, role),
            ) {
                (Some(from), Some(to)) => Quat::from_rotation_arc(from, to),
                _ => Quat::IDENTITY,
            };
            Some(Pair {
                source,
                target,
                correction,
            })
        })
        .collect()
}

/// The target's pose at one key time.
struct TargetFrame {
    /// Local rotation of each pair's target joint.
    local_rotations: Vec<Quat>,
    /// The target pelvis's local translation.
    pelvis_translation: Vec3,
}

impl TargetFrame {
    /// Solves the target joints parents first. `pelvis` is (source pelvis,
    /// target pelvis, leg-length ratio).
    fn solve(
        target: &Skeleton,
        pairs: &[Pair],
        source_rest: &[Mat4],
        source_globals: &[Mat4],
        target_rest: &[Mat4],
        pelvis: (usize, usize, f32),
    ) -> TargetFrame {
        let (source_pelvis, target_pelvis, scale) = pelvis;
        let rotation = |m: &Mat4| m.to_scale_rotation_translation().1;
        let mut wanted: Vec<Option<Quat>> = vec![None; target.len()];
        for pair in pairs {
            let delta = rotation(&source_globals[pair.source])
                * rotation(&source_rest[pair.source]).inverse();
            wanted[pair.target] =
                Some((delta * pair.correction * rotation(&target_rest[pair.target])).normalize());
        }
        let moved = source_globals[source_pelvis].w_axis.truncate()
            - source_rest[source_pelvis].w_axis.truncate();
        let pelvis_world = target_rest[target_pelvis].w_axis.truncate() + moved * scale;
        let mut globals: Vec<Mat4> = Vec::with_capacity(target.len());
        let mut locals: Vec<Quat> = Vec::with_capacity(target.len());
        let mut pelvis_translation = Vec3::ZERO;
        for (k, joint) in target.joints().iter().enumerate() {
            // Parents come first, so globals[p] exists.
            let parent = joint.parent.map_or(Mat4::IDENTITY, |p| globals[p]);
            let mut local = joint.rest;
            if let Some(global_rotation) = wanted[k] {
                local.rotation = (rotation(&parent).inverse() * global_rotation).normalize();
            }
            if k == target_pelvis {
                local.translation = parent.inverse().transform_point3(pelvis_world);
                pelvis_translation = local.translation;
            }
            locals.push(local.rotation);
            globals.push(parent * local.to_mat4());
        }
        let local_rotations = pairs.iter().map(|p| locals[p.target]).collect();
        TargetFrame {
            local_rotations,
            pelvis_translation,
        }
    }
}

/// A linear rotation channel, each quaternion on the same side as the one before.
fn rotation_channel(
    joint: usize,
    times: &[f32],
    track: Vec<Quat>,
) -> Result<Channel, RetargetError> {
    let mut values: Vec<Vec4> = Vec::with_capacity(track.len());
    for q in track {
        let v = Vec4::from(q);
        let flip = values.last().is_some_and(|prev| prev.dot(v) < 0.0);
        values.push(if flip { -v } else { v });
    }
    Channel::new(
        joint,
        Property::Rotation,
        Interpolation::Linear,
        times.to_vec(),
        values,
    )
    .map_err(RetargetError::Clip)
}
