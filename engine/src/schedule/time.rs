//! The fixed-step clock resource.

/// The fixed-step clock, kept as a resource by [`super::App`].
///
/// While step `k` runs (counting from 0), `step == k` and
/// `elapsed == k * dt`, the time at the start of the step. `elapsed` is
/// computed as `step as f64 * dt as f64`, never accumulated, so it does not drift.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Time {
    /// The fixed time step in seconds.
    pub dt: f32,
    /// Seconds simulated before the current step.
    pub elapsed: f64,
    /// Index of the current step (number of steps completed before it).
    pub step: u64,
}

impl Time {
    /// The clock before the first step.
    pub fn new(dt: f32) -> Self {
        Time {
            dt,
            elapsed: 0.0,
            step: 0,
        }
    }

    /// Sets the clock to step `step`.
    pub(crate) fn set_step(&mut self, step: u64) {
        self.step = step;
        self.elapsed = step as f64 * f64::from(self.dt);
    }
}
