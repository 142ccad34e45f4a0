//! An axis-aligned rectangle on the ground plane (XZ).

use glam::Vec2;
use serde::{Deserialize, Serialize};

/// An axis-aligned rectangle in XZ (`x` of the vectors is world X, `y` is world Z).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct XzRect {
    /// Corner with the smallest X and Z.
    pub min: Vec2,
    /// Corner with the largest X and Z.
    pub max: Vec2,
}

impl XzRect {
    /// The rectangle between two corners (in any order).
    pub fn new(a: Vec2, b: Vec2) -> Self {
        Self {
            min: a.min(b),
            max: a.max(b),
        }
    }

    /// Extent along X and Z.
    pub fn size(&self) -> Vec2 {
        self.max - self.min
    }

    /// Area in square metres.
    pub fn area(&self) -> f32 {
        let s = self.size();
        s.x * s.y
    }

    /// True when `(x, z)` lies inside (edges included).
    pub fn contains(&self, x: f32, z: f32) -> bool {
        x >= self.min.x && x <= self.max.x && z >= self.min.y && z <= self.max.y
    }

    /// True when both corners are finite and the area is positive.
    pub fn is_valid(&self) -> bool {
        self.min.is_finite()
            && self.max.is_finite()
            && self.max.x > self.min.x
            && self.max.y > self.min.y
    }
}
