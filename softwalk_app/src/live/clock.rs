//! The fixed-step clock: the simulation runs at its own step whatever the
//! display rate.

use std::time::Duration;

/// How many steps of real time the simulation may owe before it drops the
/// rest (so a long stall does not freeze the window catching up).
const MAX_OWED_STEPS: u32 = 8;

/// Turns wall-clock time into whole simulation steps.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FixedStepClock {
    dt: f64,
    owed: f64,
    /// Steps dropped because the simulation fell behind real time.
    pub dropped: u64,
}

impl FixedStepClock {
    /// A clock for steps of `dt` seconds.
    pub fn new(dt: f64) -> Self {
        FixedStepClock {
            dt: dt.max(1.0e-6),
            owed: 0.0,
            dropped: 0,
        }
    }

    /// Adds `elapsed` real time and returns the steps due now; more than
    /// `MAX_OWED_STEPS` are dropped and counted.
    pub fn advance(&mut self, elapsed: Duration) -> u32 {
        self.owed += elapsed.as_secs_f64();
        let due = (self.owed / self.dt).floor();
        self.owed -= due * self.dt;
        let due = due as u64;
        let max = u64::from(MAX_OWED_STEPS);
        if due > max {
            self.dropped += due - max;
        }
        due.min(max) as u32
    }

    /// Forgets owed time (on pause, so resuming does not jump).
    pub fn hold(&mut self) {
        self.owed = 0.0;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn steps_follow_real_time_and_keep_the_remainder() {
        let mut c = FixedStepClock::new(0.01);
        assert_eq!(c.advance(Duration::from_millis(25)), 2);
        assert_eq!(c.advance(Duration::from_millis(5)), 1);
        assert_eq!(c.advance(Duration::from_millis(9)), 0);
        c.hold();
        assert_eq!(c.advance(Duration::from_millis(9)), 0);
    }

    #[test]
    fn a_stall_is_dropped_and_counted() {
        let mut c = FixedStepClock::new(0.01);
        assert_eq!(c.advance(Duration::from_secs(1)), MAX_OWED_STEPS);
        assert_eq!(c.dropped, 100 - u64::from(MAX_OWED_STEPS));
    }
}
