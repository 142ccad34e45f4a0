//! `[sim]`: how long and with which fixed step.

use serde::{Deserialize, Serialize};

use super::SceneError;
use super::check::positive;

/// Largest accepted number of steps in a run.
pub const MAX_STEPS: u64 = 10_000_000;
/// Smallest accepted fixed step, seconds (240 Hz).
pub const MIN_DT: f32 = 1.0 / 240.0;
/// Largest accepted fixed step, seconds (20 Hz).
pub const MAX_DT: f32 = 1.0 / 20.0;
/// Slack on the `dt` bounds, seconds, so `1/240` and `1/20` written as decimals pass.
const DT_SLACK: f32 = 1.0e-7;

/// The `[sim]` table.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SimSettings {
    /// Simulated time, seconds.
    pub duration: f32,
    /// Fixed time step, seconds, in `[1/240, 1/20]`.
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
        positive("sim.dt", self.dt, 1.0)?;
        if self.dt < MIN_DT - DT_SLACK || self.dt > MAX_DT + DT_SLACK {
            return Err(SceneError::invalid(
                "sim.dt",
                format!(
                    "{} s is outside [1/240, 1/20] s ({MIN_DT:.6} to {MAX_DT} s): \
                     the gait is tuned for 20 to 240 steps per second",
                    self.dt
                ),
            ));
        }
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
