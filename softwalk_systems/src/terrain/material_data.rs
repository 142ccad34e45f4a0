//! A [`TerrainMaterial`] as written in data: the same fields, with `layer`
//! optional so files written before it existed still load.

use serde::Deserialize;

use super::material::{DEPTH_SCALE_M, GaitResponse, TerrainMaterial};

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
