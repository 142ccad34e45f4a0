//! The shape of a sole on the ground: a rounded rectangle from heel to toe.

use glam::{Vec2, Vec3};

use super::error::TerrainError;
use crate::foot::FootSole;

/// A sole's footprint in XZ: the points within `radius` (half the sole width)
/// of the heel-toe axis shortened by `radius` at each end, so the print spans
/// exactly heel to toe with rounded ends; it turns with the foot.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Footprint {
    /// Axis start (heel end, inset by `radius`).
    a: Vec2,
    /// Axis end (toe end, inset by `radius`).
    b: Vec2,
    /// Heel bottom in XZ and its height.
    heel: Vec2,
    heel_y: f32,
    /// Heel-to-toe vector in XZ and its squared length.
    along: Vec2,
    along_len2: f32,
    toe_y: f32,
    /// Half the sole width, metres.
    pub radius: f32,
}

impl Footprint {
    /// The footprint of `sole`; refuses non-finite points and a width that is not > 0.
    pub fn from_sole(sole: &FootSole) -> Result<Self, TerrainError> {
        let finite = |v: Vec3| v.is_finite();
        if !(finite(sole.heel) && finite(sole.toe)) {
            return Err(TerrainError::InvalidParameter {
                name: "sole",
                reason: format!("heel {} / toe {} not finite", sole.heel, sole.toe),
            });
        }
        if !(sole.width.is_finite() && sole.width > 0.0) {
            return Err(TerrainError::InvalidParameter {
                name: "sole.width",
                reason: format!("{} must be finite and > 0", sole.width),
            });
        }
        let heel = Vec2::new(sole.heel.x, sole.heel.z);
        let toe = Vec2::new(sole.toe.x, sole.toe.z);
        let radius = 0.5 * sole.width;
        let along = toe - heel;
        let len = along.length();
        let (a, b) = if len > 2.0 * radius {
            let dir = along / len;
            (heel + dir * radius, toe - dir * radius)
        } else {
            let c = 0.5 * (heel + toe);
            (c, c)
        };
        Ok(Footprint {
            a,
            b,
            heel,
            heel_y: sole.heel.y,
            along,
            along_len2: along.length_squared(),
            toe_y: sole.toe.y,
            radius,
        })
    }

    /// Distance in XZ from `p` to the footprint's axis (inside when <= `radius`).
    #[inline]
    pub fn axis_distance(&self, p: Vec2) -> f32 {
        let ab = self.b - self.a;
        let l2 = ab.length_squared();
        let t = if l2 > 0.0 {
            ((p - self.a).dot(ab) / l2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        (p - (self.a + ab * t)).length()
    }

    /// Height of the sole bottom over `p`: linear from heel to toe (flat across the width).
    #[inline]
    pub fn sole_height(&self, p: Vec2) -> f32 {
        if self.along_len2 == 0.0 {
            return 0.5 * (self.heel_y + self.toe_y);
        }
        let t = ((p - self.heel).dot(self.along) / self.along_len2).clamp(0.0, 1.0);
        self.heel_y + (self.toe_y - self.heel_y) * t
    }

    /// The XZ box holding the footprint grown by `margin` metres.
    pub fn bounds(&self, margin: f32) -> (Vec2, Vec2) {
        let m = Vec2::splat(self.radius + margin);
        (self.a.min(self.b) - m, self.a.max(self.b) + m)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sole() -> FootSole {
        FootSole {
            heel: Vec3::new(0.0, 1.0, 0.0),
            toe: Vec3::new(0.26, 1.1, 0.0),
            width: 0.1,
        }
    }

    #[test]
    fn rounded_rectangle_from_heel_to_toe() {
        let f = Footprint::from_sole(&sole()).unwrap();
        assert!(f.axis_distance(Vec2::new(0.0, 0.0)) <= 0.05 + 1e-6);
        assert!(f.axis_distance(Vec2::new(0.26, 0.0)) <= 0.05 + 1e-6);
        assert!(f.axis_distance(Vec2::new(0.28, 0.0)) > 0.05);
        assert!(f.axis_distance(Vec2::new(0.13, 0.049)) < 0.05);
        assert!(f.axis_distance(Vec2::new(0.13, 0.051)) > 0.05);
        // Rounded corners: the heel corner of the bounding box is outside.
        assert!(f.axis_distance(Vec2::new(0.0, 0.049)) > 0.05);
        assert!((f.sole_height(Vec2::new(0.13, 0.0)) - 1.05).abs() < 1e-6);
        let (lo, hi) = f.bounds(0.0);
        assert!((lo - Vec2::new(0.0, -0.05)).length() < 1e-6);
        assert!((hi - Vec2::new(0.26, 0.05)).length() < 1e-6);
    }

    #[test]
    fn bad_soles_are_refused() {
        let mut s = sole();
        s.width = 0.0;
        assert!(Footprint::from_sole(&s).is_err());
        let mut s = sole();
        s.toe.x = f32::NAN;
        assert!(Footprint::from_sole(&s).is_err());
    }
}
