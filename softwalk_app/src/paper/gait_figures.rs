//! The figures compared across step rates and terrain resolutions: print
//! depth, mean pelvis height and swing-peak knee. The design requires them not
//! to depend on `dt` or on the grid (every parameter is in metres and seconds).

use std::fmt;

use softwalk_systems::sim::WalkerMetrics;

use super::walking_samples::walking_mask;
use crate::runner::DepthStats;

/// Largest relative difference of the mean print depth from the reference.
pub const DEPTH_TOLERANCE: f32 = 0.10;
/// Largest difference of the mean pelvis height from the reference, metres.
pub const PELVIS_TOLERANCE_M: f32 = 0.02;
/// Largest difference of the mean swing-peak knee from the reference, degrees.
pub const SWING_KNEE_TOLERANCE_DEG: f32 = 5.0;

/// A walk's rate- and resolution-independent figures.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct GaitFigures {
    /// Mean print depth (the run summary's), metres.
    pub print_depth_m: f32,
    /// Mean pelvis height over the walking samples, metres.
    pub pelvis_mean_m: f32,
    /// Mean over the complete swings of each swing's largest knee flexion, degrees.
    pub swing_peak_knee_deg: f32,
    /// Complete swings measured.
    pub swings: usize,
}

impl GaitFigures {
    /// The figures of `series` (stepped at `dt`) with the run's print depths.
    /// Only swings that start and end within the walking samples count.
    pub fn measure(series: &[WalkerMetrics], dt: f32, depth: &DepthStats) -> GaitFigures {
        let walking = walking_mask(series, dt);
        let (mut pelvis_sum, mut pelvis_n) = (0.0f64, 0usize);
        let mut peaks: Vec<f32> = Vec::new();
        // Per leg: None before a stance is seen, Some(peak) during a swing.
        let mut swing: [Option<f32>; 2] = [None; 2];
        let mut planted = [false; 2];
        for (s, m) in series.iter().enumerate() {
            if !walking[s] {
                swing = [None; 2];
                planted = [false; 2];
                continue;
            }
            let c = &m.character;
            pelvis_sum += f64::from(c.pelvis_y);
            pelvis_n += 1;
            for k in 0..2 {
                let knee = c.knee_flexion[k].to_degrees();
                if c.contact[k] {
                    if let Some(peak) = swing[k].take() {
                        peaks.push(peak);
                    }
                    planted[k] = true;
                } else if planted[k] {
                    let peak = swing[k].get_or_insert(knee);
                    *peak = peak.max(knee);
                }
            }
        }
        GaitFigures {
            print_depth_m: depth.mean_m,
            pelvis_mean_m: (pelvis_sum / pelvis_n.max(1) as f64) as f32,
            swing_peak_knee_deg: super::stats::mean(peaks.iter().copied()),
            swings: peaks.len(),
        }
    }

    /// How these figures differ from `reference` beyond the tolerances; empty when within.
    pub fn differences(&self, reference: &GaitFigures) -> Vec<String> {
        let mut out = Vec::new();
        let depth = (self.print_depth_m - reference.print_depth_m).abs();
        if !within(depth, DEPTH_TOLERANCE * reference.print_depth_m) {
            out.push(format!(
                "print depth {:.2} cm vs {:.2} cm (more than {:.0} % apart)",
                100.0 * self.print_depth_m,
                100.0 * reference.print_depth_m,
                100.0 * DEPTH_TOLERANCE
            ));
        }
        if !within(
            (self.pelvis_mean_m - reference.pelvis_mean_m).abs(),
            PELVIS_TOLERANCE_M,
        ) {
            out.push(format!(
                "mean pelvis {:.3} m vs {:.3} m (more than {} cm apart)",
                self.pelvis_mean_m,
                reference.pelvis_mean_m,
                100.0 * PELVIS_TOLERANCE_M
            ));
        }
        let knee = self.swing_peak_knee_deg - reference.swing_peak_knee_deg;
        if !within(knee.abs(), SWING_KNEE_TOLERANCE_DEG) || self.swings == 0 {
            out.push(format!(
                "swing-peak knee {:.1}° ({} swings) vs {:.1}° (more than {SWING_KNEE_TOLERANCE_DEG}° apart, or no swing)",
                self.swing_peak_knee_deg, self.swings, reference.swing_peak_knee_deg
            ));
        }
        out
    }
}

/// True when `value` is at most `limit`; NaN is never within.
pub fn within(value: f32, limit: f32) -> bool {
    value <= limit
}

impl fmt::Display for GaitFigures {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "print depth {:.2} cm, mean pelvis {:.3} m, swing-peak knee {:.1}° ({} swings)",
            100.0 * self.print_depth_m,
            self.pelvis_mean_m,
            self.swing_peak_knee_deg,
            self.swings
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::runner::test_records;

    #[test]
    fn swing_peaks_count_only_whole_swings_after_the_first_second() {
        let mut series = vec![test_records::standing(); 12];
        // Left leg: planted, swings over samples 5..=7 peaking at 60°, planted again.
        for (s, knee) in [(5, 20.0f32), (6, 60.0), (7, 30.0)] {
            series[s].character.contact[0] = false;
            series[s].character.knee_flexion[0] = knee.to_radians();
        }
        // Right leg: in the air from sample 9 to the end (never lands: not counted).
        for m in &mut series[9..] {
            m.character.contact[1] = false;
            m.character.knee_flexion[1] = 1.0;
        }
        let depth = DepthStats {
            prints: 2,
            mean_m: 0.05,
            max_m: 0.06,
        };
        let f = GaitFigures::measure(&series, 0.25, &depth);
        assert_eq!(f.swings, 1);
        assert!((f.swing_peak_knee_deg - 60.0).abs() < 1e-3);
        assert!((f.pelvis_mean_m - 0.95).abs() < 1e-6);
        assert_eq!(f.print_depth_m, 0.05);
        assert!(f.differences(&f).is_empty());
        let deeper = GaitFigures {
            print_depth_m: 0.056,
            swing_peak_knee_deg: 66.0,
            ..f
        };
        let d = deeper.differences(&f);
        assert_eq!(d.len(), 2, "{d:?}");
        assert!(d[0].starts_with("print depth 5.60 cm vs 5.00 cm"), "{d:?}");
    }
}
