//! The three terrain stages chained for one foot, and a synthetic planted foot
//! (for tests, benchmarks and demos without a character).

use engine::geom::GridRect;
use glam::{Vec2, Vec3};

use super::carve::{FootPrint, carve};
use super::error::TerrainError;
use super::heightfield::{Heightfield, StepChanges};
use super::settle::{SettleScratch, settle_pending_with, settle_step_with, stage_window};
use super::smooth::{SmoothScratch, smooth_with};
use crate::foot::FootSole;

/// Carve, smooth and settle for one foot, as the terrain systems do in one
/// fixed step; returns the rectangle that may have changed ([`stage_window`]
/// of the carve rectangle, joined with what the settling left pending by
/// earlier steps changed; empty when nothing).
///
/// The usual chain of the carve, smooth and settle systems, for one foot:
/// `let r = carve(..)?; let s = smooth(hf, r, dt); settle_pending(hf, dt);
/// settle_step(hf, stage_window(hf, r), s, dt)`. Settling is spread over steps
/// (`settle_step`): after a release, keep stepping (the foot lifted) until
/// [`Heightfield::settling_pending`] is false for the print's final shape.
pub fn step_foot(
    hf: &mut Heightfield,
    print: &mut FootPrint,
    sole: &FootSole,
    contact: bool,
    dt: f32,
) -> Result<GridRect, TerrainError> {
    step_foot_with(hf, &mut StageScratch::default(), print, sole, contact, dt)
}

/// The work buffers of smoothing and settling for [`step_foot_with`].
#[derive(Debug, Default)]
pub struct StageScratch {
    /// Smoothing's buffers.
    pub smooth: SmoothScratch,
    /// Settling's buffers.
    pub settle: SettleScratch,
}

/// [`step_foot`] in the buffers of `scratch` (reused from step to step).
pub fn step_foot_with(
    hf: &mut Heightfield,
    scratch: &mut StageScratch,
    print: &mut FootPrint,
    sole: &FootSole,
    contact: bool,
    dt: f32,
) -> Result<GridRect, TerrainError> {
    let carved = carve(hf, print, sole, contact, dt)?;
    let smoothed = if carved.is_empty() {
        GridRect::EMPTY
    } else {
        smooth_with(hf, &mut scratch.smooth, carved, dt)
    };
    let earlier = settle_pending_with(hf, &mut scratch.settle, dt);
    if carved.is_empty() {
        return Ok(earlier);
    }
    let window = stage_window(hf, carved);
    settle_step_with(hf, &mut scratch.settle, window, smoothed, dt);
    Ok(window.union(&earlier))
}

/// Size of a synthetic foot.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FootSize {
    /// Heel to toe, metres.
    pub length: f32,
    /// Sole width, metres.
    pub width: f32,
}

impl Default for FootSize {
    /// An adult foot: 26 cm by 10 cm.
    fn default() -> Self {
        FootSize {
            length: 0.26,
            width: 0.10,
        }
    }
}

/// A sole of `size` centred at `center` (XZ), pointing along `heading`, laid
/// on the current ground as a foot ray and IK would place it: the sole is the
/// line through the ground heights under the centres of its rounded ends
/// (points off the grid read the nearest edge of the grid).
pub fn sole_on_ground(
    hf: &Heightfield,
    center: Vec2,
    heading: Vec2,
    size: FootSize,
) -> Result<FootSole, TerrainError> {
    let dir = heading
        .try_normalize()
        .ok_or(TerrainError::InvalidParameter {
            name: "heading",
            reason: format!("{heading} is not a finite non-zero direction"),
        })?;
    if !center.is_finite() {
        return Err(TerrainError::InvalidParameter {
            name: "center",
            reason: format!("{center} is not finite"),
        });
    }
    let grid = hf.grid();
    let (lo, hi) = (grid.origin(), grid.origin() + grid.extent());
    let ground = |p: Vec2| {
        let q = p.clamp(lo, hi);
        grid.height_at(q.x, q.y).unwrap_or(0.0)
    };
    let half = 0.5 * size.length;
    let inset = (half - 0.5 * size.width).max(0.0);
    let (back, front) = (ground(center - dir * inset), ground(center + dir * inset));
    // Extend the line through the two ground samples to the heel and the toe.
    let grade = if inset > 0.0 {
        (front - back) / (2.0 * inset)
    } else {
        0.0
    };
    let heel = center - dir * half;
    let toe = center + dir * half;
    let rise = grade * (half - inset);
    Ok(FootSole {
        heel: Vec3::new(heel.x, back - rise, heel.y),
        toe: Vec3::new(toe.x, front + rise, toe.y),
        width: size.width,
    })
}

/// What planting one foothold did: the changed rectangle and the volumes
/// (cubic metres) summed over its steps.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct FootholdReport {
    /// Union of the rectangles that may have changed.
    pub rect: GridRect,
    /// Volume removed by carving.
    pub carved_volume: f64,
    /// Part of it compacted (lost).
    pub compacted_volume: f64,
    /// Part of it pushed onto the rim.
    pub rim_volume: f64,
}

impl FootholdReport {
    fn add(&mut self, rect: GridRect, changes: &StepChanges) {
        self.rect = self.rect.union(&rect);
        self.carved_volume += changes.carved_volume;
        self.compacted_volume += changes.compacted_volume;
        self.rim_volume += changes.rim_volume;
    }
}

/// `sole` pushed one step of `dt` into the ground under its centre (the
/// nearest point of the grid when off it): lowered by that material's [`super::TerrainMaterial::sink_speed`] × `dt` (a
/// synthetic foot pressing the ground as a character's does).
pub fn press_into(hf: &Heightfield, mut sole: FootSole, dt: f32) -> FootSole {
    let grid = hf.grid();
    let c = sole.center();
    let at = Vec2::new(c.x, c.z).clamp(grid.origin(), grid.origin() + grid.extent());
    let sink = hf
        .material_at(at.x, at.y)
        .map_or(0.0, |m| m.sink_speed() * dt);
    sole.heel.y -= sink;
    sole.toe.y -= sink;
    sole
}

/// Plants a synthetic foot at `center` for `steps` steps of `dt`, re-laying
/// the sole on the ground each step and pushing it one sink step into it
/// ([`press_into`]), then lifts it (one release step) and keeps it lifted until the print has
/// settled ([`Heightfield::settling_pending`] is false). Each step starts with
/// [`Heightfield::begin_step`].
pub fn plant_foothold(
    hf: &mut Heightfield,
    print: &mut FootPrint,
    center: Vec2,
    heading: Vec2,
    size: FootSize,
    steps: usize,
    dt: f32,
) -> Result<FootholdReport, TerrainError> {
    let mut report = FootholdReport::default();
    let mut scratch = StageScratch::default();
    let mut k = 0;
    while k <= steps || hf.settling_pending() {
        hf.begin_step();
        let sole = press_into(hf, sole_on_ground(hf, center, heading, size)?, dt);
        let rect = step_foot_with(hf, &mut scratch, print, &sole, k < steps, dt)?;
        report.add(rect, hf.changes());
        k += 1;
    }
    Ok(report)
}
