//! `[[grass]]`: vegetation patches, a library preset plus optional overrides.

use glam::Vec2;
use serde::{Deserialize, Serialize};
use softwalk_systems::vegetation::{GrassSettings, MAX_BLADES, VegetationError, XzRect};

use super::SceneError;
use super::check::{interval, positive};

/// Tallest accepted grass blade, metres (tall grass is a metre or two).
pub const MAX_GRASS_HEIGHT: f32 = 3.0;
/// Widest accepted blade at the root, metres (grass blades are millimetres to centimetres wide).
pub const MAX_BLADE_WIDTH: f32 = 0.05;
/// Densest accepted grass, blades per square metre.
pub const MAX_GRASS_DENSITY: f32 = 50_000.0;
/// Largest accepted displacement `t_max` at the foot, metres.
pub const MAX_T_MAX: f32 = 2.0;
/// Largest accepted fall-off `gamma`, per metre.
pub const MAX_GAMMA: f32 = 1000.0;
/// Largest accepted recovery frequency, rad/s.
pub const MAX_RECOVERY_OMEGA: f32 = 1000.0;
/// Largest accepted break threshold `break_bend`.
pub const MAX_BREAK_BEND: f32 = 100.0;

/// The paper's grass kinds, the starting point of a patch's settings.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum GrassPreset {
    /// 0.5 m grass ([`GrassSettings::small`]).
    #[default]
    Small,
    /// 0.9 m grass ([`GrassSettings::medium`]).
    Medium,
}

/// A rectangle of grass: a preset, then any of the overrides, each mapped onto
/// the [`GrassSettings`] field of the same name (`t_max` and `gamma` are the
/// paper's deformation field `t(p) = clamp(t_max - gamma |p - p_f|) ...`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GrassPatchSpec {
    /// `[min, max]` along X, metres, on the terrain.
    pub x: [f32; 2],
    /// `[min, max]` along Z, metres, on the terrain.
    pub z: [f32; 2],
    /// The preset the settings start from (`"small"` or `"medium"`).
    #[serde(default)]
    pub preset: GrassPreset,
    /// Blade height, metres.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub height: Option<f32>,
    /// Relative spread of blade heights, in `[0, 1)`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub height_variation: Option<f32>,
    /// Blade width at the root, metres.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub blade_width: Option<f32>,
    /// Blades per square metre.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub density: Option<f32>,
    /// Largest displacement t_max at the foot, metres.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub t_max: Option<f32>,
    /// Fall-off gamma of the displacement per metre of distance.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gamma: Option<f32>,
    /// Recovery spring frequency, rad/s.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub recovery_omega: Option<f32>,
    /// Break threshold: a blade breaks when its tip is pushed further than
    /// `break_bend * stiffness * blade height`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub break_bend: Option<f32>,
    /// A blade also breaks when trodden this many separate times (>= 1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub treads_to_break: Option<u16>,
    /// Fraction of its largest bend a broken blade keeps, in `[0, 1]`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub broken_residual: Option<f32>,
    /// Seed of the blade scattering.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub seed: Option<u64>,
}

impl GrassPatchSpec {
    /// The patch's rectangle.
    pub fn area(&self) -> XzRect {
        XzRect::new(
            Vec2::new(self.x[0], self.z[0]),
            Vec2::new(self.x[1], self.z[1]),
        )
    }

    /// The preset with the overrides applied.
    pub fn settings(&self) -> GrassSettings {
        let mut s = match self.preset {
            GrassPreset::Small => GrassSettings::small(),
            GrassPreset::Medium => GrassSettings::medium(),
        };
        let set = |target: &mut f32, value: Option<f32>| {
            if let Some(v) = value {
                *target = v;
            }
        };
        set(&mut s.height, self.height);
        set(&mut s.height_variation, self.height_variation);
        set(&mut s.blade_width, self.blade_width);
        set(&mut s.density, self.density);
        set(&mut s.field.t_max, self.t_max);
        set(&mut s.field.gamma, self.gamma);
        set(&mut s.recovery_omega, self.recovery_omega);
        set(&mut s.break_bend, self.break_bend);
        set(&mut s.broken_residual, self.broken_residual);
        s.treads_to_break = self.treads_to_break.unwrap_or(s.treads_to_break);
        s.seed = self.seed.unwrap_or(s.seed);
        s
    }

    /// Number of blades the patch scatters: density times area.
    pub fn blade_count(&self) -> f64 {
        f64::from(self.settings().density) * f64::from(self.area().area())
    }

    /// Height of the virtual platform under a foot in this grass (a third of the blade height).
    pub fn platform_height(&self) -> f32 {
        let s = self.settings();
        s.height * s.platform.height_fraction
    }

    /// Checks the patch; `field` is its path (`grass[0]`), `size` the terrain extent.
    pub(crate) fn validate(&self, field: &str, size: [f32; 2]) -> Result<(), SceneError> {
        interval(&format!("{field}.x"), self.x, 0.0, size[0])?;
        interval(&format!("{field}.z"), self.z, 0.0, size[1])?;
        let settings = self.settings();
        let bounds = [
            ("height", settings.height, MAX_GRASS_HEIGHT),
            ("blade_width", settings.blade_width, MAX_BLADE_WIDTH),
            ("density", settings.density, MAX_GRASS_DENSITY),
            ("t_max", settings.field.t_max, MAX_T_MAX),
            ("gamma", settings.field.gamma, MAX_GAMMA),
            (
                "recovery_omega",
                settings.recovery_omega,
                MAX_RECOVERY_OMEGA,
            ),
            ("break_bend", settings.break_bend, MAX_BREAK_BEND),
        ];
        for (key, value, max) in bounds {
            positive(&format!("{field}.{key}"), value, max)?;
        }
        settings.validate().map_err(|e| match e {
            VegetationError::BadSetting {
                field: name,
                value,
                reason,
            } => {
                // The deformation field's members are flat keys in the scene.
                let key = name.strip_prefix("field.").unwrap_or(name);
                SceneError::invalid(format!("{field}.{key}"), format!("{value} {reason}"))
            }
            other => SceneError::invalid(field, other.to_string()),
        })?;
        let blades = self.blade_count();
        if blades > MAX_BLADES as f64 {
            return Err(SceneError::invalid(
                format!("{field}.density"),
                format!(
                    "{} blades/m\u{b2} over {} m\u{b2} is {blades:.0} blades, more than the limit {MAX_BLADES}",
                    settings.density,
                    self.area().area()
                ),
            ));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn patch() -> GrassPatchSpec {
        toml::from_str("x = [1.0, 2.0]\nz = [1.0, 3.0]\npreset = \"medium\"\ngamma = 2.0").unwrap()
    }

    #[test]
    fn overrides_apply_on_top_of_the_preset() {
        let p = patch();
        let s = p.settings();
        assert_eq!(s.height, 0.9);
        assert_eq!(s.field.gamma, 2.0);
        assert_eq!(s.field.t_max, GrassSettings::medium().field.t_max);
        assert!((p.platform_height() - 0.3).abs() < 1e-6);
        assert_eq!(p.area().area(), 2.0);
        p.validate("grass[0]", [10.0, 10.0]).unwrap();
    }

    #[test]
    fn bad_overrides_name_the_scene_key() {
        let mut p = patch();
        p.t_max = Some(f32::NAN);
        let e = p.validate("grass[1]", [10.0, 10.0]).unwrap_err();
        assert_eq!(e.field(), Some("grass[1].t_max"));
        p.t_max = None;
        p.x = [1.0, 20.0];
        let e = p.validate("grass[1]", [10.0, 10.0]).unwrap_err();
        assert_eq!(e.field(), Some("grass[1].x[1]"));
    }
}
