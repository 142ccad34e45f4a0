//! Vegetation friction on the balance controller (paper §4): the damping
//! gain `beta` goes linearly from 6 with no vegetation to 4 in medium (0.9 m)
//! vegetation, so the body swings less in taller grass.

use serde::{Deserialize, Serialize};

/// The linear laws from sensed vegetation height to controller gains.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct VegetationFriction {
    /// `beta` with no vegetation (the paper: 6).
    pub beta_bare: f32,
    /// `beta` at `reference_height` and above (the paper: 4).
    pub beta_reference: f32,
    /// The vegetation height where the law reaches its end value (the paper's medium grass: 0.9 m).
    pub reference_height: f32,
    /// Multiplier on the body's swing amplitude at `reference_height`
    /// (1 with no vegetation, linear in between): a hook for the balance controller.
    pub swing_scale_reference: f32,
}

impl Default for VegetationFriction {
    fn default() -> Self {
        Self {
            beta_bare: 6.0,
            beta_reference: 4.0,
            reference_height: 0.9,
            swing_scale_reference: 0.7,
        }
    }
}

impl VegetationFriction {
    /// 0 with no vegetation, 1 at the reference height and above.
    fn amount(&self, height: f32) -> f32 {
        if height.is_nan() {
            return 0.0;
        }
        (height / self.reference_height).clamp(0.0, 1.0)
    }

    /// The balance controller's `beta` for vegetation of `height` metres.
    pub fn beta(&self, height: f32) -> f32 {
        self.beta_bare + (self.beta_reference - self.beta_bare) * self.amount(height)
    }

    /// Multiplier on the swing amplitude for vegetation of `height` metres.
    pub fn swing_scale(&self, height: f32) -> f32 {
        1.0 + (self.swing_scale_reference - 1.0) * self.amount(height)
    }
}

/// The paper's law: `beta` from 6 (no vegetation) to 4 (0.9 m), linear, clamped.
///
/// ```
/// use softwalk_systems::vegetation::beta_for_vegetation;
/// assert_eq!(beta_for_vegetation(0.0), 6.0);
/// assert_eq!(beta_for_vegetation(0.45), 5.0);
/// assert_eq!(beta_for_vegetation(2.0), 4.0);
/// ```
pub fn beta_for_vegetation(height: f32) -> f32 {
    VegetationFriction::default().beta(height)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn beta_law_endpoints_and_clamping() {
        assert_eq!(beta_for_vegetation(0.0), 6.0);
        assert_eq!(beta_for_vegetation(-1.0), 6.0);
        assert_eq!(beta_for_vegetation(f32::NAN), 6.0);
        assert_eq!(beta_for_vegetation(0.9), 4.0);
        assert_eq!(beta_for_vegetation(5.0), 4.0);
        assert!((beta_for_vegetation(0.5) - (6.0 - 2.0 * 0.5 / 0.9)).abs() < 1e-6);
        let f = VegetationFriction::default();
        assert_eq!(f.swing_scale(0.0), 1.0);
        assert!((f.swing_scale(0.9) - 0.7).abs() < 1e-6);
        assert!(f.swing_scale(0.5) < 1.0 && f.swing_scale(0.5) > 0.7);
    }
}
