use glam::{Quat, Vec4};

/// How a channel's value moves between two keys (the glTF sampler modes).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Interpolation {
    /// Holds each key's value until the next key.
    Step,
    /// Straight lines between keys; spherical (slerp) for rotations.
    Linear,
    /// Cubic Hermite spline: each key stores an in-tangent, a value and an out-tangent.
    CubicSpline,
}

impl Interpolation {
    /// How many stored values each key has: 3 for a cubic spline, 1 otherwise.
    pub fn values_per_key(self) -> usize {
        match self {
            Interpolation::CubicSpline => 3,
            Interpolation::Step | Interpolation::Linear => 1,
        }
    }
}

/// Linear interpolation, or spherical for a rotation (shortest arc).
pub(super) fn lerp(a: Vec4, b: Vec4, s: f32, rotation: bool) -> Vec4 {
    if rotation {
        Vec4::from(Quat::from_vec4(a).slerp(Quat::from_vec4(b), s))
    } else {
        a.lerp(b, s)
    }
}

/// The cubic Hermite spline from `v0` (out-tangent `b0`) to `v1` (in-tangent
/// `a1`) at `s` in [0, 1], over a key interval `dt` seconds long (glTF appendix C).
pub(super) fn hermite(v0: Vec4, b0: Vec4, v1: Vec4, a1: Vec4, s: f32, dt: f32) -> Vec4 {
    let s2 = s * s;
    let s3 = s2 * s;
    v0 * (2.0 * s3 - 3.0 * s2 + 1.0)
        + b0 * (dt * (s3 - 2.0 * s2 + s))
        + v1 * (-2.0 * s3 + 3.0 * s2)
        + a1 * (dt * (s3 - s2))
}
