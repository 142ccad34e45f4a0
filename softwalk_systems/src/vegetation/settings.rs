//! Per-vegetation-type parameters, with the paper's small (0.5 m) and medium
//! (0.9 m) grass as presets.

use serde::{Deserialize, Serialize};

use super::error::{VegetationError, check};
use super::field::DeformationField;
use super::platform::{PlatformDrop, PlatformSettings};
use super::recovery::time_to_5_percent;

/// Everything that defines one kind of grass: its look, how feet push it, how
/// it recovers or breaks, and how its virtual platform behaves.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct GrassSettings {
    /// Nominal blade height (metres); also the height sensed by the character.
    pub height: f32,
    /// Relative spread of blade heights: each blade is `height * (1 ± variation)`.
    pub height_variation: f32,
    /// Blade width at the root (metres).
    pub blade_width: f32,
    /// Blades per square metre.
    pub density: f32,
    /// The paper's deformation field (eq. 2).
    pub field: DeformationField,
    /// Natural angular frequency of the recovery spring (rad/s) for a blade of
    /// stiffness 1; a blade of stiffness `s` recovers with `omega * s`.
    pub recovery_omega: f32,
    /// Relative spread of blade stiffness around 1.
    pub stiffness_variation: f32,
    /// A blade breaks when its tip is pushed further than
    /// `break_bend * stiffness * blade height`.
    pub break_bend: f32,
    /// A blade also breaks when trodden this many separate times.
    pub treads_to_break: u16,
    /// Two pushes closer than this (seconds) belong to the same tread.
    pub tread_gap: f32,
    /// Fraction of its largest bend a broken blade keeps for good
    /// (0 = recovers fully, 1 = stays fully down).
    pub broken_residual: f32,
    /// Base colour (linear RGB) of a healthy blade.
    pub colour: [f32; 3],
    /// The virtual platform under a foot in this grass.
    pub platform: PlatformSettings,
    /// Seed of the scattering.
    pub seed: u64,
}

impl GrassSettings {
    /// The paper's small grass: 0.5 m.
    pub fn small() -> Self {
        Self {
            height: 0.5,
            height_variation: 0.2,
            blade_width: 0.012,
            density: 1000.0,
            field: DeformationField {
                t_max: 0.35,
                gamma: 0.8,
            },
            recovery_omega: 2.5,
            stiffness_variation: 0.2,
            break_bend: 0.55,
            treads_to_break: 3,
            tread_gap: 0.3,
            broken_residual: 0.7,
            colour: [0.22, 0.48, 0.12],
            platform: PlatformSettings {
                drop: PlatformDrop::Fall { speed: 2.5 },
                ..PlatformSettings::default()
            },
            seed: 0x5EED_0001,
        }
    }

    /// The paper's medium grass: 0.9 m.
    pub fn medium() -> Self {
        Self {
            height: 0.9,
            blade_width: 0.015,
            density: 700.0,
            field: DeformationField {
                t_max: 0.5,
                gamma: 0.8,
            },
            recovery_omega: 1.8,
            break_bend: 0.45,
            colour: [0.26, 0.45, 0.14],
            platform: PlatformSettings {
                drop: PlatformDrop::Fall { speed: 3.5 },
                ..PlatformSettings::default()
            },
            seed: 0x5EED_0002,
            ..Self::small()
        }
    }

    /// Seconds an elastic blade of stiffness 1 takes to come back within 5 %
    /// of upright after the foot leaves.
    pub fn recovery_time(&self) -> f32 {
        time_to_5_percent(self.recovery_omega)
    }

    /// Checks every field; the error names the first bad one.
    pub fn validate(&self) -> Result<(), VegetationError> {
        let positive = "must be finite and > 0";
        let fraction = "must be finite and in [0, 1)";
        let unit = "must be finite and in [0, 1]";
        check("height", self.height, positive, |v| v > 0.0)?;
        check("height_variation", self.height_variation, fraction, |v| {
            (0.0..1.0).contains(&v)
        })?;
        check("blade_width", self.blade_width, positive, |v| v > 0.0)?;
        check("density", self.density, positive, |v| v > 0.0)?;
        check("field.t_max", self.field.t_max, positive, |v| v > 0.0)?;
        check("field.gamma", self.field.gamma, positive, |v| v > 0.0)?;
        check("recovery_omega", self.recovery_omega, positive, |v| v > 0.0)?;
        check(
            "stiffness_variation",
            self.stiffness_variation,
            fraction,
            |v| (0.0..1.0).contains(&v),
        )?;
        check("break_bend", self.break_bend, positive, |v| v > 0.0)?;
        check("tread_gap", self.tread_gap, positive, |v| v > 0.0)?;
        check("broken_residual", self.broken_residual, unit, |v| {
            (0.0..=1.0).contains(&v)
        })?;
        if self.treads_to_break == 0 {
            return Err(VegetationError::BadSetting {
                field: "treads_to_break",
                value: 0.0,
                reason: "must be >= 1",
            });
        }
        for c in self.colour {
            check("colour", c, unit, |v| (0.0..=1.0).contains(&v))?;
        }
        self.platform.validate()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn presets_are_valid_and_match_the_paper_heights() {
        assert!(GrassSettings::small().validate().is_ok());
        assert!(GrassSettings::medium().validate().is_ok());
        assert_eq!(GrassSettings::small().height, 0.5);
        assert_eq!(GrassSettings::medium().height, 0.9);
    }

    #[test]
    fn bad_fields_are_named() {
        let mut s = GrassSettings::small();
        s.density = -1.0;
        let err = s.validate().unwrap_err();
        assert!(err.to_string().contains("density"), "{err}");
        let mut s = GrassSettings::small();
        s.field.gamma = f32::NAN;
        assert!(
            s.validate()
                .unwrap_err()
                .to_string()
                .contains("field.gamma")
        );
        let mut s = GrassSettings::small();
        s.treads_to_break = 0;
        assert!(
            s.validate()
                .unwrap_err()
                .to_string()
                .contains("treads_to_break")
        );
    }
}
