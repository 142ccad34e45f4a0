//! Errors of the schedule and the app.

use crate::ecs::CommandsError;

/// A schedule that cannot be resolved or run.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum ScheduleError {
    /// The ordering constraints form a cycle; the systems are listed in cycle order.
    #[error("ordering constraints form a cycle: {}", cycle_text(systems))]
    Cycle {
        /// The systems on the cycle, in order (the first is not repeated at the end).
        systems: Vec<String>,
    },
    /// Two systems share a name.
    #[error("two systems are named `{0}`")]
    DuplicateName(String),
    /// A constraint names neither a system nor a set.
    #[error("`{system}` is ordered relative to `{label}`, which is neither a system nor a set")]
    UnknownLabel {
        /// The system (or `set <name>`) whose constraint is broken.
        system: String,
        /// The unknown name.
        label: String,
    },
    /// No system has this name.
    #[error("no system is named `{0}`")]
    UnknownSystem(String),
    /// The world's deferred commands failed after a system ran.
    #[error("deferred commands recorded by system `{system}` failed: {source}")]
    Commands {
        /// The system after which the commands were applied.
        system: String,
        /// The failures.
        source: CommandsError,
    },
}

fn cycle_text(systems: &[String]) -> String {
    let mut parts: Vec<&str> = systems.iter().map(String::as_str).collect();
    if let Some(first) = systems.first() {
        parts.push(first);
    }
    parts.join(" -> ")
}

/// An app that cannot be built or stepped.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum AppError {
    /// The fixed time step is not finite, not positive, or longer than one second.
    #[error("time step dt must be finite, > 0 and <= 1 s; got {0}")]
    InvalidDt(f32),
    /// A duration given to [`super::App::run_for`] is negative or not finite.
    #[error("duration must be finite and >= 0 s; got {0}")]
    InvalidDuration(f64),
    /// The schedule failed.
    #[error(transparent)]
    Schedule(#[from] ScheduleError),
}
