//! Systems, their order, and the fixed-step [`App`].
//!
//! A system is any `FnMut(&mut World) + Send + 'static`, added under a name.
//! [`Schedule`] resolves `after`/`before`/set constraints once into a fixed
//! order (ties by insertion order) and applies the world's deferred commands
//! after each system. [`App`] steps a world at a fixed `dt`, keeping the
//! [`Time`] resource and the event queues up to date.
//!
//! [`World`]: crate::ecs::World

#![forbid(unsafe_code)]

mod app;
mod error;
mod graph;
#[allow(clippy::module_inception)] // the module is named after its main type
mod schedule;
mod time;

pub use app::App;
pub use error::{AppError, ScheduleError};
pub use schedule::{BoxedSystem, Schedule, SetConfig, SystemConfig};
pub use time::Time;
