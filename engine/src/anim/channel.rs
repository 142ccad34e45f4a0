use glam::{Quat, Vec3, Vec4};

use super::interpolation::{hermite, lerp};
use super::{AnimError, Interpolation, Transform};

/// Which part of a joint's local transform a channel animates.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Property {
    /// Translation (xyz of each value).
    Translation,
    /// Rotation (each value is a quaternion `x, y, z, w`).
    Rotation,
    /// Scale (xyz of each value).
    Scale,
}

/// The keys of one property of one joint.
#[derive(Debug, Clone, PartialEq)]
pub struct Channel {
    joint: usize,
    property: Property,
    interpolation: Interpolation,
    times: Vec<f32>,
    values: Vec<Vec4>,
}

impl Channel {
    /// A channel of `times` (seconds, increasing) and `values` (one per key, or
    /// in-tangent, value, out-tangent per key for [`Interpolation::CubicSpline`];
    /// xyz for translation and scale, a quaternion `x, y, z, w` for rotation).
    /// Refused if it has no key, the lengths disagree, a number is not finite or
    /// the times do not increase.
    pub fn new(
        joint: usize,
        property: Property,
        interpolation: Interpolation,
        times: Vec<f32>,
        values: Vec<Vec4>,
    ) -> Result<Channel, AnimError> {
        let expected = times.len() * interpolation.values_per_key();
        if times.is_empty() || values.len() != expected {
            return Err(AnimError::Length {
                what: format!("values of the channel of joint {joint}"),
                expected: expected.max(interpolation.values_per_key()),
                found: values.len(),
            });
        }
        if let Some(k) = times.iter().position(|t| !t.is_finite()) {
            return Err(AnimError::NonFinite {
                what: format!("key time {k} of the channel of joint {joint}"),
            });
        }
        if let Some(k) = values.iter().position(|v| !v.is_finite()) {
            return Err(AnimError::NonFinite {
                what: format!("value {k} of the channel of joint {joint}"),
            });
        }
        if let Some(k) = (1..times.len()).find(|&k| times[k] <= times[k - 1]) {
            return Err(AnimError::KeyOrder { joint, key: k });
        }
        Ok(Channel {
            joint,
            property,
            interpolation,
            times,
            values,
        })
    }

    /// The joint it animates.
    pub fn joint(&self) -> usize {
        self.joint
    }

    /// The property it animates.
    pub fn property(&self) -> Property {
        self.property
    }

    /// How it interpolates.
    pub fn interpolation(&self) -> Interpolation {
        self.interpolation
    }

    /// The key times in seconds.
    pub fn times(&self) -> &[f32] {
        &self.times
    }

    /// The channel with its values multiplied by `factor` if it animates a
    /// translation (a change of length unit); unchanged otherwise.
    pub fn with_lengths_scaled(&self, factor: f32) -> Channel {
        let mut out = self.clone();
        if self.property == Property::Translation {
            for v in &mut out.values {
                *v *= factor;
            }
        }
        out
    }

    /// The time of the last key.
    pub fn end(&self) -> f32 {
        self.times.last().copied().unwrap_or(0.0)
    }

    /// The value at `time`, held constant before the first and after the last key.
    pub fn sample(&self, time: f32) -> Vec4 {
        let n = self.times.len();
        let after = self.times.partition_point(|&t| t <= time);
        if after == 0 {
            return self.key_value(0);
        }
        if after >= n {
            return self.key_value(n - 1);
        }
        let (k0, k1) = (after - 1, after);
        let dt = self.times[k1] - self.times[k0];
        let s = ((time - self.times[k0]) / dt).clamp(0.0, 1.0);
        let rotation = self.property == Property::Rotation;
        match self.interpolation {
            Interpolation::Step => self.key_value(k0),
            Interpolation::Linear => lerp(self.values[k0], self.values[k1], s, rotation),
            Interpolation::CubicSpline => {
                let v0 = self.values[3 * k0 + 1];
                let b0 = self.values[3 * k0 + 2];
                let a1 = self.values[3 * k1];
                let v1 = self.values[3 * k1 + 1];
                let mut v = hermite(v0, b0, v1, a1, s, dt);
                if rotation {
                    v = v.normalize_or(Vec4::W);
                }
                v
            }
        }
    }

    /// Writes the value at `time` into the animated property of `local`.
    pub fn apply(&self, time: f32, local: &mut Transform) {
        let v = self.sample(time);
        match self.property {
            Property::Translation => local.translation = Vec3::new(v.x, v.y, v.z),
            Property::Scale => local.scale = Vec3::new(v.x, v.y, v.z),
            Property::Rotation => {
                local.rotation = Quat::from_vec4(v).normalize();
            }
        }
    }

    fn key_value(&self, key: usize) -> Vec4 {
        let stride = self.interpolation.values_per_key();
        // The value of a cubic-spline key sits between its two tangents.
        self.values[key * stride + stride / 2]
    }
}
