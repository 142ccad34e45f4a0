//! Output writers: `metrics.csv`, `summary.json`, frame PNGs and the printed summary.
//! Every file is written whole or not at all.

mod character_stats;
mod frames;
mod metrics_csv;
mod run_report;
mod text_summary;

pub use character_stats::{CharacterStats, StatsCollector};
pub use frames::FrameWriter;
pub use metrics_csv::{METRICS_HEADER, MetricsCsv};
pub use run_report::{CharacterReport, RunReport, TerrainReport, TimingReport, write_summary_json};
pub use text_summary::text_summary;
