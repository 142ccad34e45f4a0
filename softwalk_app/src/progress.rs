//! A progress bar on standard error while a run steps; hidden when that is not a terminal.

use std::io::IsTerminal;

use indicatif::{ProgressBar, ProgressDrawTarget};

use crate::runner::{ObserverError, RunObserver};

/// Advances a progress bar at the end of every step.
pub struct Progress {
    bar: ProgressBar,
}

impl Progress {
    /// A bar of `steps` steps, drawn only when standard error is a terminal.
    pub fn new(steps: u64) -> Progress {
        let target = if std::io::stderr().is_terminal() {
            ProgressDrawTarget::stderr()
        } else {
            ProgressDrawTarget::hidden()
        };
        Progress {
            bar: ProgressBar::with_draw_target(Some(steps), target),
        }
    }

    /// Removes the bar from the terminal.
    pub fn finish(&self) {
        self.bar.finish_and_clear();
    }
}

impl RunObserver for Progress {
    fn on_step_end(&mut self, step: u64, _t: f64) -> Result<(), ObserverError> {
        self.bar.set_position(step + 1);
        Ok(())
    }
}
