//! Stepping a simulation, turning system faults into errors.

use engine::schedule::App;

use super::components::SystemFault;
use super::error::SimError;

/// Runs one fixed step; a fault reported by a system becomes [`SimError::System`].
pub fn step(app: &mut App) -> Result<(), SimError> {
    app.step()?;
    let fault = app
        .world
        .get_resource_mut::<SystemFault>()
        .and_then(|mut f| f.0.take());
    match fault {
        Some((system, message)) => Err(SimError::System {
            system,
            step: app.steps_done(),
            message,
        }),
        None => Ok(()),
    }
}

/// Runs `n` steps, stopping at the first error.
pub fn run_steps(app: &mut App, n: u64) -> Result<(), SimError> {
    (0..n).try_for_each(|_| step(app))
}
