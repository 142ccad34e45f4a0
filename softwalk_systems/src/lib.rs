//! `softwalk_systems`: the components and systems of *Soft Walks* (Eurographics 2021).
//!
//! - [`character`]: skeleton, walk cycle, rigid proxy with the PD balance controller, foot IK;
//! - [`terrain`]: loose-ground materials, carving, smoothing, settling;
//! - [`vegetation`]: grass patches, the deformation field, virtual platforms;
//! - [`view`]: drawing a world into frames ([`view::WorldView`]);
//! - [`foot`] and [`ground`]: the per-foot state and ground queries they share.
#![warn(missing_docs)]
#![forbid(unsafe_code)]

pub mod character;
pub mod foot;
pub mod ground;
pub mod sim;
pub mod terrain;
pub mod vegetation;
pub mod view;
