//! Vegetation (paper §3.2, §4): grass patches deformed by every foot with the
//! paper's field (eq. 2), persistent bending with closed-form recovery and
//! breaking, the virtual platforms of the perceived ground, and the
//! vegetation friction law on the balance controller.
//!
//! The stages are plain functions on explicit state, for the schedule to wire:
//! - `platform` (after the foot raycast): [`VirtualPlatform::update`] per foot,
//!   then cast the foot rays through [`PlatformGround`];
//! - `grass_deform` (end of the step): [`GrassPatch::deform`] with every
//!   character's feet;
//! - balance: [`VegetationFriction::beta`] of [`vegetation_height_at`] under the character.

mod area;
mod blade;
mod columns;
mod error;
mod field;
mod field_batch;
mod field_memo;
mod foot_bins;
mod foot_motion;
mod friction;
mod grid;
mod lanes;
mod patch;
mod platform;
mod platform_ground;
pub mod recovery;
mod settings;
mod state_columns;

pub use area::XzRect;
pub use blade::{Bend, Blade, BladeState};
pub use engine::rng::SplitMix64;
pub use error::VegetationError;
pub use field::DeformationField;
pub use friction::{VegetationFriction, beta_for_vegetation};
pub use grid::BladeGrid;
pub use patch::{BladePolyline, DeformStats, GrassPatch, MAX_BLADES, vegetation_height_at};
pub use platform::{PHASE_LOG_LEN, PlatformDrop, PlatformPhase, PlatformSettings, VirtualPlatform};
pub use platform_ground::{PlatformGround, PlatformTop};
pub use settings::GrassSettings;
