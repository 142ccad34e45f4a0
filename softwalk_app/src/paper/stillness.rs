//! Standing still after the path's end: how far the centre of mass moves and
//! how much the distance walked grows over the last seconds of a run.

use std::fmt;

use softwalk_systems::sim::WalkerMetrics;

/// Motion over the last seconds of a walk whose path has ended.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Stillness {
    /// Length of the window measured, seconds.
    pub window_s: f32,
    /// Whether the path had ended at the window's start (else the figures mean little).
    pub path_finished: bool,
    /// Length of the centre of mass's trajectory (3D) over the window, metres.
    pub com_travel_m: f32,
    /// Horizontal distance the centre of mass walked over the window (what a
    /// run's `distance_walked` adds), metres.
    pub distance_walked_m: f32,
    /// Growth of the gait's distance along its path over the window, metres.
    pub path_distance_added_m: f32,
    /// Straight-line distance between the centre of mass at the window's
    /// start and at its end, metres (drift, as opposed to jitter).
    pub com_displacement_m: f32,
}

impl Stillness {
    /// Measures the last `window_s` seconds of `series` (stepped at `dt`).
    pub fn measure(series: &[WalkerMetrics], dt: f32, window_s: f32) -> Stillness {
        // n intervals of dt need n + 1 samples.
        let len = ((f64::from(window_s) / f64::from(dt)).round() as usize + 1).min(series.len());
        let window = &series[series.len() - len..];
        let Some(first) = window.first() else {
            return Stillness {
                window_s: 0.0,
                ..Stillness::default()
            };
        };
        let (mut travel, mut walked) = (0.0f64, 0.0f64);
        for pair in window.windows(2) {
            let d = pair[1].character.com - pair[0].character.com;
            travel += f64::from(d.length());
            walked += f64::from(d.x.hypot(d.z));
        }
        let last = window[window.len() - 1];
        Stillness {
            window_s: ((len - 1) as f64 * f64::from(dt)) as f32,
            path_finished: first.path_finished,
            com_travel_m: travel as f32,
            distance_walked_m: walked as f32,
            path_distance_added_m: last.path_distance - first.path_distance,
            com_displacement_m: last.character.com.distance(first.character.com),
        }
    }
}

impl fmt::Display for Stillness {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "over the last {:.1} s (path ended: {}): COM travel {:.2} cm (net {:.2} cm), distance walked +{:.2} cm, path distance +{:.2} cm",
            self.window_s,
            self.path_finished,
            100.0 * self.com_travel_m,
            100.0 * self.com_displacement_m,
            100.0 * self.distance_walked_m,
            100.0 * self.path_distance_added_m
        )
    }
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::*;
    use crate::runner::test_records;

    #[test]
    fn travel_and_distance_over_the_last_window_only() {
        let mut series = vec![test_records::standing(); 10];
        for (s, m) in series.iter_mut().enumerate() {
            m.path_finished = s >= 4;
            m.path_distance = (s as f32).min(4.0);
            // Walks 1 m per sample until sample 4, then bobs 1 cm up and down.
            m.character.com = Vec3::new((s as f32).min(4.0), 0.9 + 0.01 * (s % 2) as f32, 0.0);
        }
        let still = Stillness::measure(&series, 0.5, 2.5);
        assert_eq!(still.window_s, 2.5);
        assert!(still.path_finished);
        assert!((still.com_travel_m - 0.05).abs() < 1e-5, "{still}");
        assert_eq!(still.distance_walked_m, 0.0);
        assert_eq!(still.path_distance_added_m, 0.0);
        assert!((still.com_displacement_m - 0.01).abs() < 1e-5);
        let all = Stillness::measure(&series, 0.5, 100.0);
        assert!(!all.path_finished);
        assert_eq!(all.window_s, 4.5);
        assert!((all.distance_walked_m - 4.0).abs() < 1e-5);
    }
}
