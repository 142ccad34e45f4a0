//! `[[grass]]`: vegetation patches.

use serde::{Deserialize, Serialize};

use super::SceneError;
use super::check::{in_range, interval, positive};

/// Highest accepted blade density, blades per square metre.
pub const MAX_GRASS_DENSITY: f32 = 10_000.0;

/// A rectangle of grass blades and the parameters of the paper's deformation field
/// `t(p) = clamp(t_max - gamma |p - p_f|) (p - p_f)_down / |p - p_f|`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GrassPatchSpec {
    /// `[min, max]` along X, metres, on the terrain.
    pub x: [f32; 2],
    /// `[min, max]` along Z, metres, on the terrain.
    pub z: [f32; 2],
    /// Blade height, metres, in `(0, 3]` (paper: 0.5 small, 0.9 medium).
    pub height: f32,
    /// Blades per square metre, in `(0, 10000]`.
    pub density: f32,
    /// Largest displacement t_max, metres, in `[0, 3]`.
    pub t_max: f32,
    /// Fall-off gamma of the displacement with distance to the foot, per metre, in `[0, 100]`.
    pub gamma: f32,
    /// Displacement in metres beyond which a blade breaks and stays down; none = blades always recover.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub break_threshold: Option<f32>,
}

impl GrassPatchSpec {
    /// Checks the patch; `field` is its path (`grass[0]`), `size` the terrain extent.
    pub(crate) fn validate(&self, field: &str, size: [f32; 2]) -> Result<(), SceneError> {
        interval(&format!("{field}.x"), self.x, 0.0, size[0])?;
        interval(&format!("{field}.z"), self.z, 0.0, size[1])?;
        positive(&format!("{field}.height"), self.height, 3.0)?;
        positive(&format!("{field}.density"), self.density, MAX_GRASS_DENSITY)?;
        in_range(&format!("{field}.t_max"), self.t_max, 0.0, 3.0)?;
        in_range(&format!("{field}.gamma"), self.gamma, 0.0, 100.0)?;
        if let Some(b) = self.break_threshold {
            positive(&format!("{field}.break_threshold"), b, 3.0)?;
        }
        Ok(())
    }

    /// Area of the patch, square metres.
    pub fn area(&self) -> f32 {
        (self.x[1] - self.x[0]) * (self.z[1] - self.z[0])
    }

    /// Height of the virtual platform under a foot in this grass: a third of the blade height.
    pub fn platform_height(&self) -> f32 {
        self.height / 3.0
    }
}
