//! Per-system wall-clock timings, for `softwalk bench`. Not part of the world's state.

use std::time::Instant;

use engine::ecs::World;

/// Resource: total time and call count per system, in schedule order of first call.
#[derive(Debug, Clone, Default)]
pub struct SystemTimings {
    entries: Vec<(&'static str, u128, u64)>,
}

impl SystemTimings {
    fn record(&mut self, name: &'static str, nanos: u128) {
        match self.entries.iter_mut().find(|e| e.0 == name) {
            Some(e) => {
                e.1 += nanos;
                e.2 += 1;
            }
            None => self.entries.push((name, nanos, 1)),
        }
    }

    /// `(system, mean nanoseconds per call)` in order of first call.
    pub fn means(&self) -> Vec<(&'static str, f64)> {
        self.entries
            .iter()
            .map(|&(n, total, calls)| (n, total as f64 / calls.max(1) as f64))
            .collect()
    }

    /// Forgets everything measured so far.
    pub fn clear(&mut self) {
        self.entries.clear();
    }
}

/// Wraps a system so that each call's duration goes to [`SystemTimings`].
pub(crate) fn timed(
    name: &'static str,
    mut system: impl FnMut(&mut World) + Send + 'static,
) -> impl FnMut(&mut World) + Send + 'static {
    move |world: &mut World| {
        let start = Instant::now();
        system(world);
        let nanos = start.elapsed().as_nanos();
        if let Some(mut t) = world.get_resource_mut::<SystemTimings>() {
            t.record(name, nanos);
        }
    }
}
