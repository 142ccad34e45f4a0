//! `[sim]`: how long and with which fixed step.

use serde::{Deserialize, Serialize};

use super::SceneError;
use super::check::positive;

/// Largest accepted number of steps in a run.
pub const MAX_STEPS: u64 = 10_000_000;

/// The `[sim]` table.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SimSettings {
    /// Simulated time, seconds.
    pub duration: f32,
    /// Fixed time step, seconds, in `(0, 0.1]`.
    pub dt: f32,
}

impl SimSettings {
    /// Number of steps: `duration / dt`, rounded to the nearest whole step (at least 1).
    pub fn steps(&self) -> u64 {
        ((self.duration as f64 / self.dt as f64).round() as u64).max(1)
    }

    /// Steps that cover `seconds` of simulated time at this `dt` (at least 1).
    pub fn steps_for(&self, seconds: f64) -> u64 {
        ((seconds / self.dt as f64).round() as u64).max(1)
    }

    pub(crate) fn validate(&self) -> Result<(), SceneError> {
        positive("sim.dt", self.dt, 0.1)?;
        positive("sim.duration", self.duration, 1.0e6)?;
        if self.steps() > MAX_STEPS {
            return Err(SceneError::invalid(
                "sim.duration",
                format!(
                    "{} s at dt {} is {} steps, more than the maximum {MAX_STEPS}",
                    self.duration,
                    self.dt,
                    self.steps()
                ),
            ));
        }
        Ok(())
    }
}
