//! The `softwalk` program's library: scenes, the command line and outputs.
//!
//! - [`scene`]: scene files (TOML), validation and the built-in scenes;
//! - [`sim`]: the interface between the command line and the simulation;
//! - [`output`]: `metrics.csv`, `summary.json`, frames and the printed summary;
//! - [`paper`]: the paper's claims measured on reproduction scenes (`softwalk paper`);
//! - [`memory_estimate`]: the memory a run needs, checked against a budget before it starts;
//! - [`cli`]: the `softwalk` command line.
#![warn(missing_docs)]
#![forbid(unsafe_code)]

pub mod cli;
pub mod commands;
pub mod memory_estimate;
pub mod out_dir;
pub mod out_files;
pub mod output;
pub mod paper;
pub mod progress;
pub mod scene;
pub mod scene_source;
pub mod sim;
pub mod view;
