//! `summary.json`: the scene, the grid, per-character figures and timings of a run.

use std::path::Path;

use engine::io::{WriteError, write_atomic};
use serde::Serialize;

use super::CharacterStats;
use crate::runner::{DepthStats, RunOptions, RunSummary, SystemTiming};
use crate::scene::{Scene, TerrainShape};

/// The heightmap grid of the run.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TerrainReport {
    /// Samples along X.
    pub grid_nx: usize,
    /// Samples along Z.
    pub grid_nz: usize,
    /// Distance between samples, metres.
    pub cell_size: f32,
    /// Highest allowed height, metres.
    pub max_height: f32,
    /// Metres per full-scale pixel of the heightmap file, when the terrain is a heightmap.
    pub height_scale: Option<f32>,
    /// The heightmap file, when the terrain is a heightmap.
    pub heightmap: Option<String>,
}

/// Figures for one character.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CharacterReport {
    /// Character name.
    pub name: String,
    /// Figures from the metric rows.
    #[serde(flatten)]
    pub stats: CharacterStats,
    /// Footprint depths, when the simulation measured them.
    pub print_depth: Option<DepthStats>,
}

/// Where the time went.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TimingReport {
    /// Wall-clock time of the whole run (simulation and outputs), seconds.
    pub wall_seconds: f64,
    /// Wall-clock time of building the world (terrain, BVH, grass,
    /// characters) and the renderer before the first step, seconds.
    pub setup_seconds: f64,
    /// Mean wall-clock time per step after set-up (simulation, rendering and
    /// the run's observers), milliseconds.
    pub ms_per_step: f64,
    /// Worker threads.
    pub threads: usize,
    /// Per-system costs, in schedule order.
    pub systems: Vec<SystemTiming>,
}

/// Everything `summary.json` holds.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RunReport {
    /// Scene name.
    pub scene: String,
    /// Steps simulated.
    pub steps: u64,
    /// Fixed step, seconds.
    pub dt: f64,
    /// Simulated time, seconds.
    pub duration_seconds: f64,
    /// The terrain grid.
    pub terrain: TerrainReport,
    /// Per-character figures, in scene order.
    pub characters: Vec<CharacterReport>,
    /// Timings.
    pub timings: TimingReport,
    /// Hash of the final world as 16 hex digits, when computed.
    pub world_hash: Option<String>,
    /// The 16-bit heightmaps written (`terrain_initial.png`, `terrain_final.png`) and how to read heights back.
    pub heightmaps: Vec<HeightmapReport>,
}

/// How to turn a 16-bit heightmap's values back into heights:
/// `height = min + value * height_scale`, metres.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct HeightmapReport {
    /// File name.
    pub file: String,
    /// Pixels along X and Z.
    pub width: u32,
    /// Pixels along Z.
    pub height: u32,
    /// Height of value 0, metres.
    pub min: f32,
    /// Height of value 65535, metres.
    pub max: f32,
    /// Metres per unit of the 16-bit value.
    pub height_scale: f32,
    /// Distance between samples, metres.
    pub cell_size: f32,
}

impl HeightmapReport {
    /// The report of a heightmap written to `path`.
    pub fn new(path: &std::path::Path, info: &engine::asset::HeightmapInfo) -> Self {
        HeightmapReport {
            file: path
                .file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default(),
            width: info.width,
            height: info.height,
            min: info.min,
            max: info.max,
            height_scale: info.height_scale(),
            cell_size: info.cell,
        }
    }
}

impl RunReport {
    /// Assembles the report of a finished run.
    pub fn new(
        scene: &Scene,
        options: &RunOptions,
        summary: &RunSummary,
        stats: &[CharacterStats],
        wall_seconds: f64,
    ) -> RunReport {
        let (grid_nx, grid_nz) = scene.terrain.grid_samples();
        let (height_scale, heightmap) = match &scene.terrain.shape {
            TerrainShape::Heightmap { path, height_scale } => {
                (Some(*height_scale), Some(path.display().to_string()))
            }
            _ => (None, None),
        };
        let characters = scene
            .characters
            .iter()
            .enumerate()
            .map(|(k, c)| CharacterReport {
                name: c.name.clone(),
                stats: stats.get(k).copied().unwrap_or_default(),
                print_depth: summary.print_depth.get(k).copied(),
            })
            .collect();
        RunReport {
            scene: scene.name.clone(),
            steps: summary.steps,
            dt: options.dt,
            duration_seconds: summary.sim_seconds,
            terrain: TerrainReport {
                grid_nx,
                grid_nz,
                cell_size: scene.terrain.cell_size(),
                max_height: scene.terrain.max_height,
                height_scale,
                heightmap,
            },
            characters,
            timings: TimingReport {
                wall_seconds,
                setup_seconds: summary.setup_seconds,
                ms_per_step: if summary.steps == 0 {
                    0.0
                } else {
                    summary.stepping_seconds * 1000.0 / summary.steps as f64
                },
                threads: options.threads,
                systems: summary.timings.clone(),
            },
            world_hash: summary.world_hash.map(|h| format!("{h:016x}")),
            heightmaps: Vec::new(),
        }
    }
}

/// Writes `report` as pretty JSON to `path`, atomically.
pub fn write_summary_json(path: &Path, report: &RunReport) -> Result<(), WriteError> {
    write_atomic(path, |w| {
        serde_json::to_writer_pretty(&mut *w, report).map_err(std::io::Error::other)?;
        writeln!(w)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn summary_json_parses_back() {
        let scene = Scene::builtin("controller-compare").unwrap();
        let options = RunOptions::from_scene(&scene);
        let summary = RunSummary {
            steps: 10,
            sim_seconds: 10.0 * options.dt,
            world_hash: Some(0xabc),
            setup_seconds: 0.3,
            stepping_seconds: 0.4,
            print_depth: vec![DepthStats {
                prints: 3,
                mean_m: 0.04,
                max_m: 0.05,
            }],
            timings: vec![SystemTiming {
                name: "carve".into(),
                mean_ns: 1500.0,
            }],
        };
        let report = RunReport::new(&scene, &options, &summary, &[], 0.5);
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("summary.json");
        write_summary_json(&path, &report).unwrap();
        let v: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
        assert_eq!(v["scene"], "controller-compare");
        assert_eq!(v["steps"], 10);
        assert_eq!(v["terrain"]["grid_nx"], 512);
        assert_eq!(v["characters"][1]["name"], "uncontrolled");
        assert_eq!(v["characters"][0]["print_depth"]["prints"], 3);
        assert!(v["characters"][1]["print_depth"].is_null());
        assert_eq!(v["world_hash"], "0000000000000abc");
        assert_eq!(v["timings"]["ms_per_step"], 40.0);
        assert_eq!(v["timings"]["setup_seconds"], 0.3);
    }
}
