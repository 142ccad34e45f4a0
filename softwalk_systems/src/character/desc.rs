//! The small, serialisable description a character is built from.

use serde::{Deserialize, Serialize};

use super::clip_gait::ClipGait;
use super::error::{CharacterError, check_range};

/// Default passive damping, N·m·s/rad (above the paper's largest beta, 6).
pub const DEFAULT_PASSIVE_DAMPING: f32 = 12.0;

/// What a scene file says about a character; [`super::CharacterBody::new`] turns it into a body.
///
/// Every field but `height` and `mass` has a default, so a scene may write only those two.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CharacterDesc {
    /// Standing height, metres (0.5 to 2.5).
    pub height: f32,
    /// Body mass, kilograms (> 0).
    pub mass: f32,
    /// Scales thigh and shank; the trunk shrinks or grows so the height is kept (0.7 to 1.3).
    #[serde(default = "one")]
    pub leg_length_factor: f32,
    /// Balance stiffness alpha of eq. 1 (N·m per m of COM offset).
    #[serde(default = "default_alpha")]
    pub alpha: f32,
    /// Balance swing gain beta of eq. 1 (N·m·s/rad), in `[0, 12)`: below the passive damping.
    #[serde(default = "default_beta")]
    pub beta: f32,
    /// Walking Froude number v²/(g·L) that sets the speed (0.02 to 0.5).
    #[serde(default = "default_froude")]
    pub froude: f32,
    /// Mass of the rigid proxy that carries the tilt, kilograms (> 0).
    #[serde(default = "one")]
    pub proxy_mass: f32,
    /// The cadence, stride and duty of a walk clip, when the character walks
    /// like one (a scene's `clip`), instead of the walk its Froude number sets.
    #[serde(skip)]
    pub clip_gait: Option<ClipGait>,
}

fn one() -> f32 {
    1.0
}
fn default_alpha() -> f32 {
    30.0
}
fn default_beta() -> f32 {
    6.0
}
fn default_froude() -> f32 {
    0.15
}

impl CharacterDesc {
    /// A character of this height and mass with every other field at its default.
    pub fn new(height: f32, mass: f32) -> Self {
        CharacterDesc {
            height,
            mass,
            leg_length_factor: 1.0,
            alpha: default_alpha(),
            beta: default_beta(),
            froude: default_froude(),
            proxy_mass: 1.0,
            clip_gait: None,
        }
    }

    /// An adult: 1.75 m, 70 kg.
    pub fn adult() -> Self {
        Self::new(1.75, 70.0)
    }

    /// A child: 1.0 m, 16 kg.
    pub fn child() -> Self {
        Self::new(1.0, 16.0)
    }

    /// A tall adult: 1.9 m, 85 kg.
    pub fn tall() -> Self {
        Self::new(1.9, 85.0)
    }

    /// An adult with legs 20 % longer (the centre of mass sits higher).
    pub fn long_legged() -> Self {
        CharacterDesc {
            leg_length_factor: 1.2,
            ..Self::adult()
        }
    }

    /// An adult with legs 20 % shorter (the centre of mass sits lower).
    pub fn short_legged() -> Self {
        CharacterDesc {
            leg_length_factor: 0.8,
            ..Self::adult()
        }
    }

    /// Checks every field, naming the first one out of range.
    pub fn validate(&self) -> Result<(), CharacterError> {
        check_range("height", self.height, 0.5, 2.5)?;
        check_range("mass", self.mass, 1.0, 500.0)?;
        check_range("leg_length_factor", self.leg_length_factor, 0.7, 1.3)?;
        check_range("alpha", self.alpha, 0.0, 1.0e4)?;
        // The balance refuses a beta at or above its passive damping (the swing would grow).
        if !(self.beta.is_finite() && (0.0..DEFAULT_PASSIVE_DAMPING).contains(&self.beta)) {
            return Err(CharacterError::InvalidField {
                field: "beta",
                reason: format!(
                    "{} is not a finite number in [0, {DEFAULT_PASSIVE_DAMPING}) \
                     (it must stay below the passive damping); allowed [0, {DEFAULT_PASSIVE_DAMPING})",
                    self.beta
                ),
            });
        }
        check_range("froude", self.froude, 0.02, 0.5)?;
        check_range("proxy_mass", self.proxy_mass, 0.01, 500.0)?;
        Ok(())
    }
}
