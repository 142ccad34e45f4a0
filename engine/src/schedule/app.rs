//! A fixed-step application: a world, a schedule and a clock.

use super::error::AppError;
use super::schedule::{Schedule, SystemConfig};
use super::time::Time;
use crate::ecs::World;

/// A world stepped at a fixed `dt` by a schedule.
///
/// Each [`App::step`]: set the [`Time`] resource to the current step, advance
/// every registered event queue ([`World::update_events`]), run the schedule
/// (which applies deferred commands after each system), then count the step.
///
/// ```
/// use engine::ecs::World;
/// use engine::schedule::{App, Time};
///
/// struct Distance(f64);
/// let mut app = App::new(0.5).unwrap();
/// app.world.insert_resource(Distance(0.0));
/// app.add_system("walk", |w: &mut World| {
///     let dt = w.resource::<Time>().dt;
///     w.resource_mut::<Distance>().0 += 1.2 * f64::from(dt);
/// });
/// app.run_for(2.0).unwrap();
/// assert_eq!(app.world.resource::<Time>().step, 4);
/// assert!((app.world.resource::<Distance>().0 - 2.4).abs() < 1e-9);
/// ```
pub struct App {
    /// The simulated world.
    pub world: World,
    /// The systems run each step.
    pub schedule: Schedule,
    dt: f32,
    steps_done: u64,
}

impl App {
    /// An app with fixed step `dt` seconds (finite, > 0, <= 1) and a [`Time`] resource.
    pub fn new(dt: f32) -> Result<App, AppError> {
        if !(dt.is_finite() && dt > 0.0 && dt <= 1.0) {
            return Err(AppError::InvalidDt(dt));
        }
        let mut world = World::new();
        world.insert_resource(Time::new(dt));
        Ok(App {
            world,
            schedule: Schedule::new(),
            dt,
            steps_done: 0,
        })
    }

    /// The fixed time step in seconds.
    pub fn dt(&self) -> f32 {
        self.dt
    }

    /// Number of completed steps.
    pub fn steps_done(&self) -> u64 {
        self.steps_done
    }

    /// Adds a system to the schedule (see [`Schedule::add_system`]).
    pub fn add_system(
        &mut self,
        name: impl Into<String>,
        system: impl FnMut(&mut World) + Send + 'static,
    ) -> SystemConfig<'_> {
        self.schedule.add_system(name, system)
    }

    /// Runs one fixed step.
    pub fn step(&mut self) -> Result<(), AppError> {
        self.set_clock(self.steps_done);
        self.world.update_events();
        self.schedule.run(&mut self.world)?;
        self.steps_done += 1;
        self.set_clock(self.steps_done);
        Ok(())
    }

    /// Runs `n` steps, stopping at the first error.
    pub fn run_steps(&mut self, n: u64) -> Result<(), AppError> {
        (0..n).try_for_each(|_| self.step())
    }

    /// Runs `round(seconds / dt)` steps.
    pub fn run_for(&mut self, seconds: f64) -> Result<(), AppError> {
        if !(seconds.is_finite() && seconds >= 0.0) {
            return Err(AppError::InvalidDuration(seconds));
        }
        self.run_steps((seconds / f64::from(self.dt)).round() as u64)
    }

    /// Writes the clock, re-inserting the `Time` resource if a system removed it.
    fn set_clock(&mut self, step: u64) {
        let mut time = Time::new(self.dt);
        time.set_step(step);
        self.world.insert_resource(time);
    }
}
