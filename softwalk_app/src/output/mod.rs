//! Output writers: `metrics.csv`, `summary.json`, frame PNGs, animations, the
//! contact sheet, plots, heightmaps and the printed summary, and [`LastFrame`],
//! which keeps a run's last frame in memory. Every file is
//! written whole or not at all.

mod animation;
mod character_stats;
mod decimated_series;
mod frame_thread;
mod frames;
mod heightmaps;
mod last_frame;
mod metrics_csv;
mod metrics_row;
mod plots;
mod run_report;
mod text_summary;

pub use animation::{AnimationWriter, ContactSheet};
pub use character_stats::{CharacterStats, StatsCollector};
pub use frame_thread::FrameThread;
pub use frames::FrameWriter;
pub use heightmaps::HeightmapWriter;
pub use last_frame::LastFrame;
pub use metrics_csv::MetricsCsv;
pub use metrics_row::{metric_column, metrics_header};
pub use plots::{PlotCollector, PlotsSaved};
pub use run_report::{
    CharacterReport, HeightmapReport, RunReport, TerrainReport, TimingReport, write_summary_json,
};
pub use text_summary::text_summary;
