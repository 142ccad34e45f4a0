use glam::{Quat, Vec3, Vec4};

use super::BvhError;
use super::hierarchy::{BvhJoint, ChannelKind};
use super::tokens::Tokens;
use crate::anim::{Channel, Interpolation, Property};

/// The frames of a BVH `MOTION` section.
pub(super) struct Motion {
    /// Seconds per frame.
    pub frame_time: f32,
    /// Every frame's values, all channels of all joints in hierarchy order.
    pub values: Vec<f32>,
    /// How many frames there are.
    pub frames: usize,
}

/// Parses `MOTION Frames: n Frame Time: t` and `n` lines of values; the count of
/// values is checked against the text's size before anything is allocated.
pub(super) fn parse_motion(
    tokens: &mut Tokens,
    channels: usize,
    text_len: usize,
) -> Result<Motion, BvhError> {
    tokens.expect("MOTION")?;
    tokens.expect("Frames:")?;
    // Each value takes at least 2 bytes ("0 "), which bounds the frame count.
    let frames = tokens.count("frame count", text_len / 2 / channels.max(1) + 1)?;
    tokens.expect("Frame")?;
    tokens.expect("Time:")?;
    let frame_time = tokens.number("frame time")?;
    if frame_time <= 0.0 {
        return Err(BvhError::NonFinite {
            path: tokens.path().to_path_buf(),
            line: tokens.line(),
            what: format!("frame time {frame_time} is not positive"),
        });
    }
    let needed = frames * channels;
    let mut values = Vec::with_capacity(needed);
    for _ in 0..needed {
        match tokens.number("a channel value") {
            Ok(v) => values.push(v),
            Err(BvhError::Syntax { found, .. }) if found == "end of file" => {
                return Err(frame_data(tokens, frames, channels, values.len()));
            }
            Err(e) => return Err(e),
        }
    }
    if tokens.next("end of file").is_ok() {
        return Err(frame_data(tokens, frames, channels, needed + 1));
    }
    Ok(Motion {
        frame_time,
        values,
        frames,
    })
}

fn frame_data(tokens: &Tokens, frames: usize, channels: usize, found: usize) -> BvhError {
    BvhError::FrameData {
        path: tokens.path().to_path_buf(),
        frames,
        channels,
        needed: frames * channels,
        found,
    }
}

/// The clip's channels: a linear rotation channel for each joint with rotation
/// channels (Euler angles composed in the file's order) and a translation
/// channel for each joint with position channels (the positions replace the
/// offset's components).
pub(super) fn clip_channels(
    joints: &[BvhJoint],
    motion: &Motion,
) -> Result<Vec<Channel>, crate::anim::AnimError> {
    let per_frame: usize = joints.iter().map(|j| j.channels.len()).sum();
    let times: Vec<f32> = (0..motion.frames.max(1))
        .map(|k| k as f32 * motion.frame_time)
        .collect();
    let mut channels = Vec::new();
    let mut first = 0;
    for (index, joint) in joints.iter().enumerate() {
        let frame_values = |frame: usize| {
            let start = frame * per_frame + first;
            motion
                .values
                .get(start..start + joint.channels.len())
                .unwrap_or(&[])
        };
        let has = |rotation: bool| {
            joint
                .channels
                .iter()
                .any(|c| matches!(c, ChannelKind::Rotation(_)) == rotation)
        };
        if has(true) {
            let values = (0..times.len())
                .map(|f| Vec4::from(rotation(&joint.channels, frame_values(f))))
                .collect();
            channels.push(Channel::new(
                index,
                Property::Rotation,
                Interpolation::Linear,
                times.clone(),
                values,
            )?);
        }
        if has(false) {
            let values = (0..times.len())
                .map(|f| position(joint, frame_values(f)).extend(0.0))
                .collect();
            channels.push(Channel::new(
                index,
                Property::Translation,
                Interpolation::Linear,
                times.clone(),
                values,
            )?);
        }
        first += joint.channels.len();
    }
    Ok(channels)
}

/// The rotation of one frame: each rotation channel turns about its axis, in
/// the order listed (`Z X Y` means `Rz * Rx * Ry`).
fn rotation(kinds: &[ChannelKind], values: &[f32]) -> Quat {
    kinds
        .iter()
        .zip(values)
        .fold(Quat::IDENTITY, |q, (kind, &degrees)| match kind {
            ChannelKind::Rotation(axis) => {
                q * Quat::from_axis_angle(unit(*axis), degrees.to_radians())
            }
            ChannelKind::Position(_) => q,
        })
        .normalize()
}

fn position(joint: &BvhJoint, values: &[f32]) -> Vec3 {
    let mut p = joint.offset;
    for (kind, &value) in joint.channels.iter().zip(values) {
        if let ChannelKind::Position(axis) = kind {
            p[*axis] = value;
        }
    }
    p
}

fn unit(axis: usize) -> Vec3 {
    match axis {
        0 => Vec3::X,
        1 => Vec3::Y,
        _ => Vec3::Z,
    }
}
