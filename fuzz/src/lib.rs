//! A fuzz harness for softwalk on stable Rust, with its own small mutator.
//!
//! Inputs are mutated built-in scenes (and the scene files of `fuzz/corpus`),
//! random and broken heightmap PNGs, and random OBJ files (including rows and
//! fans of triangles). Each is fed in-process to the loaders and, when
//! accepted, to a few simulation steps ([`oracle::check`]); an input whose
//! memory estimate exceeds [`oracle::INPUT_BUDGET`] is skipped before anything
//! is allocated. A campaign ([`campaign::run`]) counts panics, hangs and
//! scenes accepted by validation that then fail mid-run.
//!
//! `cargo test -p fuzz` runs a few seconds of it and replays `fuzz/corpus`;
//! `cargo run --release -p fuzz -- --minutes 10` runs a long campaign.
#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod campaign;
pub mod mutate;
pub mod obj_input;
pub mod oracle;
pub mod png_input;
pub mod rng;
