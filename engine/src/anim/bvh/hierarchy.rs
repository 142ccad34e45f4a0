use glam::Vec3;

use super::BvhError;
use super::tokens::Tokens;

/// Most joints a BVH hierarchy may have.
pub const MAX_JOINTS: usize = 1024;
/// Deepest nesting of joints accepted.
const MAX_DEPTH: usize = 256;

/// One channel of a BVH joint: an axis and whether it moves or turns.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum ChannelKind {
    /// Position along axis 0, 1 or 2 (x, y, z).
    Position(usize),
    /// Rotation in degrees about axis 0, 1 or 2.
    Rotation(usize),
}

/// A joint as the hierarchy declares it.
#[derive(Debug, Clone)]
pub(super) struct BvhJoint {
    pub name: String,
    pub parent: Option<usize>,
    pub offset: Vec3,
    pub channels: Vec<ChannelKind>,
}

/// Parses `HIERARCHY ROOT name { ... }` into joints in file order (parents
/// first); `End Site` blocks are read and dropped.
pub(super) fn parse_hierarchy(tokens: &mut Tokens) -> Result<Vec<BvhJoint>, BvhError> {
    tokens.expect("HIERARCHY")?;
    tokens.expect("ROOT")?;
    let mut joints = Vec::new();
    parse_joint(tokens, None, 0, &mut joints)?;
    Ok(joints)
}

fn parse_joint(
    tokens: &mut Tokens,
    parent: Option<usize>,
    depth: usize,
    joints: &mut Vec<BvhJoint>,
) -> Result<(), BvhError> {
    for (what, count, limit) in [
        ("nesting depth", depth, MAX_DEPTH),
        ("joint count", joints.len() + 1, MAX_JOINTS),
    ] {
        if count > limit {
            return Err(BvhError::Limit {
                path: tokens.path().to_path_buf(),
                line: tokens.line(),
                what: format!("{what} {count}"),
                limit,
            });
        }
    }
    let name = tokens.next("a joint name")?.to_string();
    tokens.expect("{")?;
    let offset = parse_offset(tokens)?;
    let channels = if tokens.peek_is("CHANNELS") {
        parse_channels(tokens)?
    } else {
        Vec::new()
    };
    let index = joints.len();
    joints.push(BvhJoint {
        name,
        parent,
        offset,
        channels,
    });
    loop {
        let word = tokens.next("JOINT, End Site or }")?;
        if word.eq_ignore_ascii_case("JOINT") {
            parse_joint(tokens, Some(index), depth + 1, joints)?;
        } else if word.eq_ignore_ascii_case("End") {
            tokens.expect("Site")?;
            tokens.expect("{")?;
            parse_offset(tokens)?;
            tokens.expect("}")?;
        } else if word == "}" {
            return Ok(());
        } else {
            return Err(tokens.syntax("JOINT, End Site or }", word));
        }
    }
}

fn parse_offset(tokens: &mut Tokens) -> Result<Vec3, BvhError> {
    tokens.expect("OFFSET")?;
    Ok(Vec3::new(
        tokens.number("OFFSET x")?,
        tokens.number("OFFSET y")?,
        tokens.number("OFFSET z")?,
    ))
}

fn parse_channels(tokens: &mut Tokens) -> Result<Vec<ChannelKind>, BvhError> {
    tokens.expect("CHANNELS")?;
    let count = tokens.count("channel count", 6)?;
    (0..count)
        .map(|_| {
            let name = tokens.next("a channel name")?;
            channel_kind(name).ok_or_else(|| BvhError::BadChannel {
                path: tokens.path().to_path_buf(),
                line: tokens.line(),
                name: name.to_string(),
            })
        })
        .collect()
}

fn channel_kind(name: &str) -> Option<ChannelKind> {
    let lower = name.to_ascii_lowercase();
    let axis = match lower.as_bytes().first()? {
        b'x' => 0,
        b'y' => 1,
        b'z' => 2,
        _ => return None,
    };
    match &lower[1..] {
        "position" => Some(ChannelKind::Position(axis)),
        "rotation" => Some(ChannelKind::Rotation(axis)),
        _ => None,
    }
}
