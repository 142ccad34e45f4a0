//! One grass blade as the renderer draws it.

use glam::Vec3;

/// One grass blade: a curve through three points, tapering from `width` at the
/// root to a point at the tip.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GrassBlade {
    /// Where the blade leaves the ground.
    pub root: Vec3,
    /// A point halfway along the blade (bent blades move it).
    pub mid: Vec3,
    /// The blade's tip.
    pub tip: Vec3,
    /// Width at the root, in metres.
    pub width: f32,
    /// Linear RGB albedo.
    pub color: Vec3,
}
