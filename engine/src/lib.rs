//! `engine`: a small headless game engine.
//!
//! It knows nothing of feet, materials or grass. It provides:
//! - [`ecs`]: entities, components, queries, resources, commands and events;
//! - [`schedule`]: named systems ordered by constraints, and a fixed-step [`schedule::App`];
//! - [`geom`]: rays, boxes, a deformable [`geom::HeightGrid`] and BVH ray casts;
//! - [`io`]: atomic file output;
//! - [`asset`]: OBJ meshes and heightmap PNGs in and out;
//! - [`anim`]: skeletons, skinned meshes, clips, CPU skinning, glTF and BVH import, retargeting;
//! - [`render`]: a software rasterizer, overlays, plots and image/animation output;
//! - [`rng`]: the seeded SplitMix64 generator everything random uses;
//! - [`snapshot`]: golden-image tests on rendered PNGs.
#![warn(missing_docs)]

pub mod anim;
pub mod asset;
pub mod canvas;
pub mod ecs;
pub mod geom;
pub mod io;
pub mod output;
pub mod render;
pub mod rng;
pub mod schedule;
pub mod snapshot;

pub use glam;
