//! Loose-ground materials: the paper's d_t, c_t, s_t, an angle of repose,
//! the loose layer's thickness and a gait response.

use serde::{Deserialize, Serialize};

use super::error::TerrainError;

/// Print depth in metres per unit of the depth coefficient d_t: a print is
/// `DEPTH_SCALE_M * d_t` deep below the surface the foot first touched
/// (the authors' Unity code uses the same 0.1 m factor).
pub const DEPTH_SCALE_M: f32 = 0.1;

/// Time in seconds a foot takes to press a print to its full depth: it
/// pushes into the ground at `print_depth / SINK_TIME_S` metres per second,
/// i.e. `d_t` m/s (a character over the end of its swing, a synthetic foot
/// with [`super::press_into`]); carving presses the samples down with the
/// sole, and the print's edge samples at that speed.
pub const SINK_TIME_S: f32 = 0.1;

/// How a material changes the character's walk, as plain data.
///
/// The character's gait system multiplies its nominal speed and step length by
/// the scales and raises its swing apex by `extra_clearance`. Values of the
/// presets are stylised (deep or sticky grounds slow the walk and lift the feet).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GaitResponse {
    /// Multiplier on walking speed (1 = unchanged), in (0, 2].
    pub speed_scale: f32,
    /// Multiplier on step length (1 = unchanged), in (0, 2].
    pub step_length_scale: f32,
    /// Extra swing-foot clearance in metres, in [0, 0.5].
    pub extra_clearance: f32,
}

impl GaitResponse {
    /// No change to the gait.
    pub const NEUTRAL: GaitResponse = GaitResponse {
        speed_scale: 1.0,
        step_length_scale: 1.0,
        extra_clearance: 0.0,
    };
}

impl Default for GaitResponse {
    fn default() -> Self {
        Self::NEUTRAL
    }
}

/// A loose-ground material (paper §3.2 and §4), loadable from data.
///
/// - `depth` is the paper's d_t: the print is [`TerrainMaterial::print_depth`]
///   = 0.1 m × d_t deep and a foot presses it at d_t m/s ([`SINK_TIME_S`]);
/// - `compression` is c_t: the fraction of the displaced volume that is
///   compacted (lost); the rim receives `1 - c_t` of it;
/// - `smoothness` is s_t: the strength of the Gaussian filter, as the
///   paper's passes per step at the reference grid and rate
///   ([`super::smoothing_variance_rate`] turns it into m²/s);
/// - `repose_deg` is the angle of repose: steeper disturbed slopes slump;
/// - `layer` is the thickness of the loose layer over firm ground, metres:
///   carving, compaction and settling never take a sample below its initial
///   height minus `layer` ([`super::Heightfield::firm_floor`]). Omitted in
///   data, it takes the preset's value for a preset's name
///   ([`TerrainMaterial::default_layer`]), else the print depth.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(from = "TerrainMaterialData")]
pub struct TerrainMaterial {
    /// Unique name, used for lookups.
    pub name: String,
    /// Depth coefficient d_t (>= 0).
    pub depth: f32,
    /// Compression coefficient c_t in [0, 1].
    pub compression: f32,
    /// Smoothness coefficient s_t in [0, 16].
    pub smoothness: f32,
    /// Angle of repose in degrees, in (0, 90].
    pub repose_deg: f32,
    /// Thickness of the loose layer over firm ground, metres, in [0, 10].
    pub layer: f32,
    /// How this ground changes the walk.
    pub gait: GaitResponse,
}

impl TerrainMaterial {
    /// Largest accepted smoothness (passes per step).
    pub const MAX_SMOOTHNESS: f32 = 16.0;

    /// Largest accepted layer thickness, metres.
    pub const MAX_LAYER_M: f32 = 10.0;

    /// Dry sand: d 0.5 (5 cm), s 3, c 0.2, repose 34°, a 5 cm layer.
    pub fn dry_sand() -> Self {
        Self::preset("sand", 0.5, 0.2, 3.0, 34.0, (0.85, 0.9, 0.02))
    }

    /// Soil: d 0.4 (4 cm), s 2, c 0.6, repose 40°, a 4 cm layer.
    pub fn soil() -> Self {
        Self::preset("soil", 0.4, 0.6, 2.0, 40.0, (0.95, 0.97, 0.0))
    }

    /// Mud: d 2 (20 cm), s 2, c 0.6, repose 80° (cohesive, holds walls), a
    /// 15 cm layer (so mud prints are 15 cm deep).
    pub fn mud() -> Self {
        Self::preset("mud", 2.0, 0.6, 2.0, 80.0, (0.7, 0.8, 0.05))
    }

    /// Snow: d 3 (30 cm), s 4, c 0.9, repose 84° (holds near-vertical walls),
    /// a 30 cm layer.
    pub fn snow() -> Self {
        Self::preset("snow", 3.0, 0.9, 4.0, 84.0, (0.65, 0.75, 0.08))
    }

    /// The layer thickness a material called `name` with print depth
    /// `print_depth` gets when its data omit `layer`: the preset's for a
    /// preset's name (sand 0.05, soil 0.04, mud 0.15, snow 0.30 m), else the
    /// print depth (one print reaches firm ground).
    pub fn default_layer(name: &str, print_depth: f32) -> f32 {
        match name {
            "sand" => 0.05,
            "soil" => 0.04,
            "mud" => 0.15,
            "snow" => 0.30,
            _ => print_depth,
        }
    }

    fn preset(
        name: &str,
        depth: f32,
        compression: f32,
        smoothness: f32,
        repose_deg: f32,
        (speed_scale, step_length_scale, extra_clearance): (f32, f32, f32),
    ) -> Self {
        TerrainMaterial {
            name: name.to_owned(),
            depth,
            compression,
            smoothness,
            repose_deg,
            layer: Self::default_layer(name, DEPTH_SCALE_M * depth),
            gait: GaitResponse {
                speed_scale,
                step_length_scale,
                extra_clearance,
            },
        }
    }

    /// The four presets of the paper: sand, soil, mud, snow.
    pub fn presets() -> [TerrainMaterial; 4] {
        [Self::dry_sand(), Self::soil(), Self::mud(), Self::snow()]
    }

    /// Depth of a print below the surface first touched, metres.
    pub fn print_depth(&self) -> f32 {
        DEPTH_SCALE_M * self.depth
    }

    /// Speed at which contact cells sink, metres per second.
    pub fn sink_speed(&self) -> f32 {
        self.print_depth() / SINK_TIME_S
    }

    /// Tangent of the angle of repose (infinite at 90°): the steepest stable slope.
    pub fn repose_slope(&self) -> f32 {
        if self.repose_deg >= 90.0 {
            f32::INFINITY
        } else {
            self.repose_deg.to_radians().tan()
        }
    }

    /// Checks every field, naming the first one out of range.
    pub fn validate(&self) -> Result<(), TerrainError> {
        let fail = |field: &'static str, value: f32, range: &str| {
            Err(TerrainError::InvalidMaterial {
                material: self.name.clone(),
                field,
                reason: format!("{value} is not in {range}"),
            })
        };
        let inside = |v: f32, lo: f32, hi: f32| v.is_finite() && v >= lo && v <= hi;
        if self.name.is_empty() {
            return Err(TerrainError::InvalidMaterial {
                material: String::new(),
                field: "name",
                reason: "the name is empty".into(),
            });
        }
        if !inside(self.depth, 0.0, 100.0) {
            return fail("depth", self.depth, "[0, 100]");
        }
        if !inside(self.compression, 0.0, 1.0) {
            return fail("compression", self.compression, "[0, 1]");
        }
        if !inside(self.smoothness, 0.0, Self::MAX_SMOOTHNESS) {
            return fail("smoothness", self.smoothness, "[0, 16]");
        }
        if !(inside(self.repose_deg, 0.0, 90.0) && self.repose_deg > 0.0) {
            return fail("repose_deg", self.repose_deg, "(0, 90]");
        }
        if !inside(self.layer, 0.0, Self::MAX_LAYER_M) {
            return fail("layer", self.layer, "[0, 10]");
        }
        let g = &self.gait;
        if !(inside(g.speed_scale, 0.0, 2.0) && g.speed_scale > 0.0) {
            return fail("gait.speed_scale", g.speed_scale, "(0, 2]");
        }
        if !(inside(g.step_length_scale, 0.0, 2.0) && g.step_length_scale > 0.0) {
            return fail("gait.step_length_scale", g.step_length_scale, "(0, 2]");
        }
        if !inside(g.extra_clearance, 0.0, 0.5) {
            return fail("gait.extra_clearance", g.extra_clearance, "[0, 0.5]");
        }
        Ok(())
    }
}

// A material as written in data: the same fields, with `layer` optional so
// files written before it existed still load.

/// The fields of a [`TerrainMaterial`] as read from data (unknown fields are
/// refused). A missing `layer` takes [`TerrainMaterial::default_layer`];
/// a missing `gait` is [`GaitResponse::NEUTRAL`].
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct TerrainMaterialData {
    name: String,
    depth: f32,
    compression: f32,
    smoothness: f32,
    repose_deg: f32,
    #[serde(default)]
    layer: Option<f32>,
    #[serde(default)]
    gait: GaitResponse,
}

impl From<TerrainMaterialData> for TerrainMaterial {
    fn from(d: TerrainMaterialData) -> Self {
        let layer = d
            .layer
            .unwrap_or_else(|| TerrainMaterial::default_layer(&d.name, DEPTH_SCALE_M * d.depth));
        TerrainMaterial {
            name: d.name,
            depth: d.depth,
            compression: d.compression,
            smoothness: d.smoothness,
            repose_deg: d.repose_deg,
            layer,
            gait: d.gait,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn presets_are_valid_and_ordered_by_depth() {
        let [sand, soil, mud, snow] = TerrainMaterial::presets();
        for m in TerrainMaterial::presets() {
            m.validate().unwrap();
        }
        assert!(soil.print_depth() < sand.print_depth());
        assert!(sand.print_depth() < mud.print_depth());
        assert!(mud.print_depth() < snow.print_depth());
        assert!((sand.print_depth() - 0.05).abs() < 1e-6);
        assert!((snow.sink_speed() - 3.0).abs() < 1e-5);
    }

    #[test]
    fn bad_fields_are_named() {
        let mut m = TerrainMaterial::mud();
        m.compression = f32::NAN;
        let e = m.validate().unwrap_err();
        assert!(matches!(
            e,
            TerrainError::InvalidMaterial {
                field: "compression",
                ..
            }
        ));
        let mut m = TerrainMaterial::snow();
        m.depth = -1.0;
        assert!(matches!(
            m.validate(),
            Err(TerrainError::InvalidMaterial { field: "depth", .. })
        ));
        let mut m = TerrainMaterial::soil();
        m.repose_deg = 0.0;
        assert!(m.validate().is_err());
        let mut m = TerrainMaterial::soil();
        m.layer = f32::INFINITY;
        assert!(matches!(
            m.validate(),
            Err(TerrainError::InvalidMaterial { field: "layer", .. })
        ));
        m.layer = 10.5;
        assert!(m.validate().is_err());
        let mut m = TerrainMaterial::soil();
        m.gait.speed_scale = -0.5;
        assert!(matches!(
            m.validate(),
            Err(TerrainError::InvalidMaterial {
                field: "gait.speed_scale",
                ..
            })
        ));
    }

    #[test]
    fn presets_have_their_layers_and_data_without_a_layer_load() {
        let layers = TerrainMaterial::presets().map(|m| m.layer);
        assert_eq!(layers, [0.05, 0.04, 0.15, 0.30]);
        let sand = r#"{"name": "sand", "depth": 0.2, "compression": 0.5,
            "smoothness": 1.0, "repose_deg": 40.0}"#;
        let m: TerrainMaterial = serde_json::from_str(sand).unwrap();
        assert_eq!(m.layer, 0.05);
        let ash = sand.replace("\"sand\"", "\"ash\"");
        let m: TerrainMaterial = serde_json::from_str(&ash).unwrap();
        assert!((m.layer - 0.02).abs() < 1e-7);
        let thick = ash.replace("40.0}", "40.0, \"layer\": 0.5}");
        let m: TerrainMaterial = serde_json::from_str(&thick).unwrap();
        assert_eq!(m.layer, 0.5);
        let back: TerrainMaterial =
            serde_json::from_str(&serde_json::to_string(&m).unwrap()).unwrap();
        assert_eq!(back, m);
        let e = serde_json::from_str::<TerrainMaterial>(&ash.replace("40.0}", "40.0, \"x\": 1}"));
        assert!(e.is_err());
    }

    #[test]
    fn vertical_repose_is_infinite_slope() {
        let mut m = TerrainMaterial::snow();
        m.repose_deg = 90.0;
        assert!(m.repose_slope().is_infinite());
        assert!(
            (TerrainMaterial::dry_sand().repose_slope() - 34f32.to_radians().tan()).abs() < 1e-6
        );
    }
}
