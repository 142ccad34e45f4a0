//! The `softwalk` program's library: scene files, runs, outputs, the paper
//! report, recorded inputs and the live viewer. The `softwalk` binary (crate
//! `demos`) only parses its arguments and calls [`commands::execute`].
//!
//! - [`scene`]: scene files (TOML), validation and the built-in scenes;
//! - [`runner`]: runs a scene's simulation for the command line, drawing
//!   frames with a [`softwalk_systems::view::WorldView`];
//! - [`view`]: the camera and settings a scene chooses for its view;
//! - [`output`]: `metrics.csv`, `summary.json`, frames and the printed summary;
//! - [`paper`]: the paper's claims measured on reproduction scenes (`softwalk paper`);
//! - [`memory_estimate`]: the memory a run needs, checked against a budget before it starts;
//! - [`inputs`]: recorded steering inputs, replayed headless;
//! - [`live`]: the live viewer's window-free logic (keys, camera, clock, heads-up line);
//! - [`cli`] and [`commands`]: the `softwalk` command line, one file per subcommand.
#![warn(missing_docs)]
#![forbid(unsafe_code)]

pub mod cli;
pub mod commands;
pub mod inputs;
pub mod live;
pub mod memory_estimate;
pub mod out_dir;
pub mod out_files;
pub mod output;
pub mod paper;
pub mod progress;
pub mod runner;
pub mod scene;
pub mod scene_source;
pub mod view;
