//! Per-character figures gathered from the metric rows of a run.

use glam::Vec3;
use serde::Serialize;

use crate::runner::{ObserverError, RunObserver, StepRecord};

/// Figures for one character over a run.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct CharacterStats {
    /// Rows seen.
    pub samples: u64,
    /// Mean tilt, radians.
    pub mean_tilt: f64,
    /// Standard deviation of the tilt, radians.
    pub std_tilt: f64,
    /// Horizontal distance the centre of mass travelled, metres.
    pub distance_walked: f64,
    /// Mean pelvis height, metres.
    pub mean_pelvis_y: f64,
    /// Largest knee flexion of either leg, radians.
    pub max_knee_flexion: f32,
}

#[derive(Debug, Clone, Default)]
struct Accumulator {
    samples: u64,
    tilt_sum: f64,
    tilt_sq_sum: f64,
    pelvis_sum: f64,
    distance: f64,
    last_com: Option<Vec3>,
    max_knee: f32,
}

/// Gathers [`CharacterStats`] for every character, as an observer.
#[derive(Debug, Clone, Default)]
pub struct StatsCollector {
    per_character: Vec<Accumulator>,
}

impl StatsCollector {
    /// A collector for `characters` characters.
    pub fn new(characters: usize) -> StatsCollector {
        StatsCollector {
            per_character: vec![Accumulator::default(); characters],
        }
    }

    /// Adds one row.
    pub fn add(&mut self, r: &StepRecord) {
        if r.character >= self.per_character.len() {
            self.per_character
                .resize(r.character + 1, Accumulator::default());
        }
        let a = &mut self.per_character[r.character];
        let m = &r.walker.character;
        a.samples += 1;
        a.tilt_sum += f64::from(m.tilt);
        a.tilt_sq_sum += f64::from(m.tilt) * f64::from(m.tilt);
        a.pelvis_sum += f64::from(m.pelvis_y);
        if let Some(last) = a.last_com {
            a.distance += f64::from((m.com.x - last.x).hypot(m.com.z - last.z));
        }
        a.last_com = Some(m.com);
        a.max_knee = a.max_knee.max(m.knee_flexion[0]).max(m.knee_flexion[1]);
    }

    /// The figures so far, one per character in scene order.
    pub fn stats(&self) -> Vec<CharacterStats> {
        self.per_character
            .iter()
            .map(|a| {
                if a.samples == 0 {
                    return CharacterStats::default();
                }
                let n = a.samples as f64;
                let mean = a.tilt_sum / n;
                let variance = (a.tilt_sq_sum / n - mean * mean).max(0.0);
                CharacterStats {
                    samples: a.samples,
                    mean_tilt: mean,
                    std_tilt: variance.sqrt(),
                    distance_walked: a.distance,
                    mean_pelvis_y: a.pelvis_sum / n,
                    max_knee_flexion: a.max_knee,
                }
            })
            .collect()
    }
}

impl RunObserver for StatsCollector {
    fn on_step(&mut self, record: &StepRecord) -> Result<(), ObserverError> {
        self.add(record);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use softwalk_systems::character::CharacterMetrics;
    use softwalk_systems::sim::WalkerMetrics;

    use super::*;
    use crate::runner::test_records;

    #[test]
    fn figures_match_hand_computation() {
        let mut c = StatsCollector::new(2);
        for (k, tilt) in [0.1f32, 0.3].into_iter().enumerate() {
            let standing = test_records::standing();
            c.add(&StepRecord {
                step: k as u64,
                t: k as f64,
                character: 1,
                walker: WalkerMetrics {
                    character: CharacterMetrics {
                        com: Vec3::new(3.0 * k as f32, 1.0, 4.0 * k as f32),
                        tilt,
                        pelvis_y: 0.9 + k as f32 * 0.2,
                        knee_flexion: [0.4, 0.7 - k as f32],
                        ..standing.character
                    },
                    ..standing
                },
                terrain_volume: 0.0,
            });
        }
        let s = c.stats();
        assert_eq!(s[0], CharacterStats::default());
        assert_eq!(s[1].samples, 2);
        assert!((s[1].mean_tilt - 0.2).abs() < 1e-6);
        assert!((s[1].std_tilt - 0.1).abs() < 1e-6);
        assert!((s[1].distance_walked - 5.0).abs() < 1e-6);
        assert!((s[1].mean_pelvis_y - 1.0).abs() < 1e-6);
        assert_eq!(s[1].max_knee_flexion, 0.7);
    }
}
