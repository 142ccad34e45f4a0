//! Loose grounds (paper §3.2 and §4): a deformable [`Heightfield`] with a
//! material per sample, and the stages a stance foot drives each step:
//!
//! 1. [`carve`]: the sole presses its footprint in, up to the material's
//!    print depth and never below the firm floor under the loose layer;
//!    c_t of the volume is compacted, the rest goes to the rim;
//! 2. [`smooth`]: the paper's Gaussian filter of strength s_t, as
//!    conservative diffusion in the dirty window;
//! 3. [`settle`] (beyond the paper): disturbed slopes steeper than the angle
//!    of repose slump (Sumner 1999), mass-conserving.
//!
//! Every parameter is in metres and seconds ([`REFERENCE_CELL_M`] and
//! [`REFERENCE_RATE_HZ`] state the paper's cell- and step-based ones), so the
//! same scene gives the same prints at any grid resolution and step rate.
//!
//! Each stage returns the rectangle it may have changed and reports it with
//! [`Heightfield::mark_dirty`]: this step's changed rectangles
//! ([`StepChanges::rects`], a [`DirtyRects`] list) are what the BVH refit
//! and the renderer redo.
//!
//! ```
//! use glam::Vec2;
//! use softwalk_systems::terrain::*;
//!
//! let table = MaterialTable::with_presets();
//! let sand = table.id("sand").unwrap();
//! let grid = generate::flat(generate::GridSpec::square(2.0, 101), 1.0).unwrap();
//! let mut hf = Heightfield::from_grid(grid, table, sand).unwrap();
//! let mut print = FootPrint::new();
//! let size = FootSize::default();
//! plant_foothold(&mut hf, &mut print, Vec2::splat(1.0), Vec2::X, size, 18, 1.0 / 60.0).unwrap();
//! let floor = hf.lowest_in(Vec2::splat(0.95), Vec2::splat(1.05)).unwrap();
//! assert!(floor < 1.0 - 0.03);
//! ```

mod carve;
mod dirty_rects;
mod error;
mod footprint;
pub mod generate;
mod heightfield;
mod held;
mod material;
mod material_table;
pub mod noise;
mod patch;
mod pending_settle;
mod settle;
mod smooth;
mod step;
mod units;
mod waves;

pub use carve::{
    CONTACT_TOLERANCE, FootPrint, PRINT_MARGIN_M, Pressed, RIM_MIN_WIDTH_M, RIM_WIDTH_FRACTION,
    carve, deposit_rim, press, rim_width,
};
pub use dirty_rects::DirtyRects;
pub use error::TerrainError;
pub use footprint::Footprint;
pub use heightfield::{
    DISTURBED_PRESSED, DISTURBED_RIM, DISTURBED_SLUMPED, Heightfield, StepChanges,
};
pub use held::HeldSamples;
pub use material::{DEPTH_SCALE_M, GaitResponse, SINK_TIME_S, TerrainMaterial};
pub use material_table::{MaterialId, MaterialTable};
pub use settle::{
    SETTLE_AREA_RATE_M2_S, SETTLE_MARGIN_M, SETTLE_MAX_SWEEPS, SETTLE_OVERRELAXATION,
    SETTLE_RUNOUT_SLOPE, SETTLE_TOLERANCE, SettleScratch, settle, settle_each, settle_from,
    settle_margin_cells, settle_max_sweeps, settle_pending, settle_pending_with, settle_step,
    settle_step_visits, settle_step_with, stage_window,
};
pub use smooth::{
    DIFFUSION_RATE, MAX_SMOOTHING_PASSES, SmoothScratch, smooth, smooth_each, smooth_with,
    smoothing_duration, smoothing_pass_equivalent, smoothing_radius, smoothing_reach_m,
    smoothing_variance_rate,
};
pub use step::{
    FootSize, FootholdReport, StageScratch, plant_foothold, press_into, sole_on_ground, step_foot,
    step_foot_with,
};
pub use units::{REFERENCE_CELL_M, REFERENCE_RATE_HZ, cells_covering};
pub use waves::ScratchPool;
