//! Screen batches kept from frame to frame, so that a renderer's per-frame
//! buffers (projected vertices, set-up triangles, band lists) keep their
//! memory instead of being allocated, faulted in and freed every frame.

use std::sync::{Mutex, PoisonError};

use super::batch::ScreenBatch;

/// Spare [`ScreenBatch`]es, shared by the parallel jobs of a frame.
#[derive(Debug, Default)]
pub(crate) struct BatchPool(Mutex<Vec<ScreenBatch>>);

impl BatchPool {
    /// A spare batch to rebuild (a new, empty one when none is left).
    pub fn take(&self) -> ScreenBatch {
        self.spares().pop().unwrap_or_default()
    }

    /// Keeps `batches` for later frames.
    pub fn give_back(&self, batches: Vec<ScreenBatch>) {
        self.spares().extend(batches);
    }

    /// How many batches are waiting to be reused.
    #[cfg(test)]
    pub fn len(&self) -> usize {
        self.spares().len()
    }

    fn spares(&self) -> std::sync::MutexGuard<'_, Vec<ScreenBatch>> {
        // A panic while the lock was held leaves a list of whole batches:
        // still fit to reuse.
        self.0.lock().unwrap_or_else(PoisonError::into_inner)
    }
}
