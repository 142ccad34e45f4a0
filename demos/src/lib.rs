//! The `softwalk` program's library: scenes, the command line and outputs.
//!
//! - [`scene`]: scene files (TOML), validation and the built-in scenes;
//! - [`runner`]: runs a scene's simulation for the command line, drawing
//!   frames with a [`softwalk_systems::view::WorldView`];
//! - [`view`]: the camera and settings a scene chooses for its view;
//! - [`output`]: `metrics.csv`, `summary.json`, frames and the printed summary;
//! - [`paper`]: the paper's claims measured on reproduction scenes (`softwalk paper`);
//! - [`cli`]: the `softwalk` command line.
#![warn(missing_docs)]

pub mod cli;
pub mod commands;
pub mod out_dir;
pub mod output;
pub mod paper;
pub mod progress;
pub mod runner;
pub mod scene;
pub mod scene_source;
pub mod view;

/// The runner under its former path, for modules not yet moved to
/// [`runner`] (private: `demos::sim` is no longer a public name).
mod sim {
    #[cfg(test)]
    pub(crate) use crate::runner::test_records;
    pub(crate) use crate::runner::{ObserverError, RunObserver, StepRecord};
}
