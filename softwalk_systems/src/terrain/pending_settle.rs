//! Settling work a step's budget left for later steps, kept with the height
//! field between steps.

use engine::geom::GridRect;

/// Settling work left for later steps: a window (grid samples) and where
/// its next sweep starts.
#[derive(Debug, Clone)]
pub(crate) struct PendingSettle {
    /// The window to settle (grid samples).
    pub(super) window: GridRect,
    pub(super) start: Start,
    /// Sweeps made so far (the run stops at `settle_max_sweeps`).
    pub(super) sweeps: usize,
}

/// Where a relaxation starts.
#[derive(Debug, Clone)]
pub(crate) enum Start {
    /// A first sweep over the steep samples of this rectangle (grid samples).
    Scan(GridRect),
    /// A sweep over the samples an interrupted run had queued (grid indices,
    /// row-major).
    Queued(Vec<usize>),
}
