//! Stepping a simulation, turning system faults into errors.

use engine::ecs::World;
use engine::schedule::App;

use super::components::SystemFault;
use super::error::SimError;

/// Runs one fixed step; a fault reported by a system becomes [`SimError::System`].
pub fn step(app: &mut App) -> Result<(), SimError> {
    app.step()?;
    let step = app.steps_done();
    take_fault(&mut app.world, step)
}

/// The fault a system reported during step `step`, taken from `world` as
/// [`SimError::System`].
pub(super) fn take_fault(world: &mut World, step: u64) -> Result<(), SimError> {
    let fault = world
        .get_resource_mut::<SystemFault>()
        .and_then(|mut f| f.0.take());
    match fault {
        Some((system, message)) => Err(SimError::System {
            system,
            step,
            message,
        }),
        None => Ok(()),
    }
}

/// Runs `n` steps, stopping at the first error.
pub fn run_steps(app: &mut App, n: u64) -> Result<(), SimError> {
    (0..n).try_for_each(|_| step(app))
}
