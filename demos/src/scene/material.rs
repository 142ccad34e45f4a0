//! Ground materials as data: the built-in presets and user-defined `[[materials]]`.

use serde::{Deserialize, Serialize};

use super::SceneError;
use super::check::{identifier, in_range};

/// How a material changes the gait of a character walking on it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GaitResponse {
    /// Multiplier on the walking speed, in `(0, 2]` (1 = unchanged).
    #[serde(default = "one")]
    pub speed_factor: f32,
    /// Extra swing-foot clearance in metres, in `[0, 0.5]` (deep snow makes people lift their knees).
    #[serde(default)]
    pub knee_lift: f32,
}

fn one() -> f32 {
    1.0
}

impl Default for GaitResponse {
    fn default() -> Self {
        GaitResponse {
            speed_factor: 1.0,
            knee_lift: 0.0,
        }
    }
}

/// One loose-ground material (the paper's d_t, c_t, s_t plus an angle of repose).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialSpec {
    /// Name used by `terrain.material` and `terrain.regions[..].material`.
    pub name: String,
    /// Print depth in metres, in `[0, 1]`: the paper's d_t scaled by 0.1 m (sand 0.5 -> 0.05 m).
    pub depth: f32,
    /// Compression c_t in `[0, 1]`: the compacted fraction of the displaced volume; the rim gets `1 - c_t`.
    pub compression: f32,
    /// Smoothness s_t in `[0, 16]`: strength of the smoothing applied around a print.
    pub smoothness: f32,
    /// Angle of repose in degrees, in `(0, 90]`: steeper material slides down.
    pub repose_deg: f32,
    /// Effect on the gait.
    #[serde(default)]
    pub gait: GaitResponse,
}

/// Names of the built-in materials, in the order they are listed.
pub const BUILTIN_MATERIALS: [&str; 5] = ["sand", "soil", "mud", "snow", "rock"];

impl MaterialSpec {
    /// The built-in preset with this name, if any.
    ///
    /// Depth, smoothness and compression follow the paper's table (depth x 0.1 m);
    /// the angles of repose follow measured values (dry sand 34 degrees) and, for
    /// mud and snow, which hold steep walls, Sumner et al. 1999. `rock` does not deform.
    pub fn preset(name: &str) -> Option<MaterialSpec> {
        let (depth, smoothness, compression, repose_deg, speed_factor, knee_lift) = match name {
            "sand" => (0.05, 3.0, 0.2, 34.0, 0.95, 0.0),
            "soil" => (0.04, 2.0, 0.6, 40.0, 1.0, 0.0),
            "mud" => (0.2, 2.0, 0.6, 63.0, 0.8, 0.03),
            "snow" => (0.3, 4.0, 0.9, 80.0, 0.75, 0.08),
            "rock" => (0.0, 0.0, 1.0, 90.0, 1.0, 0.0),
            _ => return None,
        };
        Some(MaterialSpec {
            name: name.to_owned(),
            depth,
            compression,
            smoothness,
            repose_deg,
            gait: GaitResponse {
                speed_factor,
                knee_lift,
            },
        })
    }

    /// Checks every number; `field` is this material's path, e.g. `materials[0]`.
    pub(crate) fn validate(&self, field: &str) -> Result<(), SceneError> {
        identifier(&format!("{field}.name"), &self.name)?;
        in_range(&format!("{field}.depth"), self.depth, 0.0, 1.0)?;
        in_range(&format!("{field}.compression"), self.compression, 0.0, 1.0)?;
        in_range(&format!("{field}.smoothness"), self.smoothness, 0.0, 16.0)?;
        in_range(&format!("{field}.repose_deg"), self.repose_deg, 0.0, 90.0)?;
        if self.repose_deg == 0.0 {
            return Err(SceneError::invalid(
                format!("{field}.repose_deg"),
                "0 must be > 0",
            ));
        }
        let speed = format!("{field}.gait.speed_factor");
        in_range(&speed, self.gait.speed_factor, 0.0, 2.0)?;
        if self.gait.speed_factor == 0.0 {
            return Err(SceneError::invalid(speed, "0 must be > 0"));
        }
        in_range(
            &format!("{field}.gait.knee_lift"),
            self.gait.knee_lift,
            0.0,
            0.5,
        )?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_preset_is_valid_and_named() {
        for name in BUILTIN_MATERIALS {
            let m = MaterialSpec::preset(name).unwrap();
            assert_eq!(m.name, name);
            m.validate("m").unwrap();
        }
        assert!(MaterialSpec::preset("quicksand").is_none());
    }

    #[test]
    fn presets_follow_the_paper_ordering() {
        let p = |n| MaterialSpec::preset(n).unwrap();
        assert!(p("soil").depth < p("sand").depth);
        assert!(p("sand").depth < p("mud").depth && p("mud").depth < p("snow").depth);
        assert!(p("soil").compression > p("sand").compression);
        assert!(p("snow").smoothness > p("mud").smoothness);
    }
}
