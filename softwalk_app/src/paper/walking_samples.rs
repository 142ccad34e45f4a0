//! Which samples of a recorded walk count as walking, for the gait figures.
//!
//! A sample counts when its step ends at or after [`SETTLE_S`] (the start
//! transient is skipped) and the gait has not yet reached the end of its path
//! ([`WalkerMetrics::path_finished`]). The path's end is used rather than the
//! gait's stopped state or a velocity threshold: it flips exactly once, on the
//! step the gait's distance reaches the path's length, whatever the step rate,
//! and it leaves out the stopping step the walker completes after the end
//! (neither walking nor standing). A looped path never ends.

use softwalk_systems::sim::WalkerMetrics;

/// The start transient skipped before measuring, seconds.
pub const SETTLE_S: f64 = 1.0;

/// `mask[s]` is true when sample `s` (the state after step `s`, stepped at `dt`
/// seconds) counts as walking.
pub fn walking_mask(series: &[WalkerMetrics], dt: f32) -> Vec<bool> {
    let first = first_settled_step(dt);
    series
        .iter()
        .enumerate()
        .map(|(s, m)| s >= first && !m.path_finished)
        .collect()
}

/// The first step (0-based) that ends at or after [`SETTLE_S`].
pub fn first_settled_step(dt: f32) -> usize {
    // Step s ends at (s + 1) dt; the slack absorbs the rounding of dt.
    ((SETTLE_S / f64::from(dt) - 1.0 - 1e-6).ceil()).max(0.0) as usize
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::runner::test_records;

    #[test]
    fn skips_the_first_second_and_everything_after_the_path_end() {
        assert_eq!(first_settled_step(1.0 / 60.0), 59);
        assert_eq!(first_settled_step(1.0 / 30.0), 29);
        assert_eq!(first_settled_step(0.5), 1);
        let mut series = vec![test_records::standing(); 6];
        series[4].path_finished = true;
        series[5].path_finished = true;
        assert_eq!(
            walking_mask(&series, 0.25),
            [false, false, false, true, false, false]
        );
    }
}
