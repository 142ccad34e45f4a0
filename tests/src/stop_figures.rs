//! A stop measured from a recorded walk: how long from the key to both feet
//! flat on the ground, and the gait goals over the whole stop, including the
//! closing step (the gait-quality report leaves out every sample after the
//! path's end, where that step is taken).

use std::fmt;

use glam::{Vec2, Vec3};
use softwalk_app::paper::gait_quality::{Goal, deepest_sole, pelvis_step};
use softwalk_systems::sim::WalkerMetrics;

use crate::sole_contact::StanceSlide;

/// The foot-slide goal: a planted heel or toe moves at most this far per stance, metres.
pub const SLIDE_GOAL_M: f32 = 0.02;
/// A sole point within this of the ground counts as touching it, metres.
const TOUCHING_M: f32 = 0.005;
/// A foot touching the ground and pitched no more than this from the slope
/// along the walk is flat, degrees. The roll at the ends of a step (heel
/// strike about 20°, heel rise up to 34°) is far beyond it.
const FLAT_DEG: f32 = 5.0;
/// The longest a stop may take from the key to both feet flat, seconds: the
/// step being taken and one closing step at a walking cadence.
pub const FLAT_AFTER_GOAL_S: f32 = 1.2;
/// The name [`StopFigures::failures`] gives the time to both feet flat.
const FLAT_FIGURE: &str = "key to both feet flat";
/// The most the centre of mass may move over the last second at rest, metres.
const REST_DRIFT_GOAL_M: f32 = 0.01;

/// Each foot's contact and its heel and toe, with heights measured above
/// the ground under them.
pub type SoleSample = [(bool, [Vec3; 2]); 2];

/// Each step's soles of `walked` against the ground under them.
pub fn sole_samples(walked: &[WalkerMetrics]) -> Vec<SoleSample> {
    walked
        .iter()
        .map(|m| {
            [0, 1].map(|k| {
                let (sole, under) = (m.character.soles[k], m.sole_ground[k]);
                let heel = sole.heel - Vec3::Y * under.heel;
                (
                    m.character.contact[k],
                    [heel, sole.toe - Vec3::Y * under.toe],
                )
            })
        })
        .collect()
}

/// The largest horizontal drift of a touching heel or toe (within
/// [`TOUCHING_M`] above the ground) from where it first touched, over each
/// stance.
pub fn worst_slide(samples: &[SoleSample]) -> f32 {
    let mut worst = 0.0f32;
    for k in 0..2 {
        let mut slide = StanceSlide::new(TOUCHING_M);
        for s in samples {
            let (contact, points) = s[k];
            if !contact {
                slide = StanceSlide::new(TOUCHING_M);
                continue;
            }
            worst = worst.max(slide.add_over(&points, 0.0));
        }
    }
    worst
}

/// The pitch of a sole from heel to toe, less the ground's slope along the
/// walk, degrees (toe up positive).
fn pitch_from_ground(m: &WalkerMetrics, k: usize) -> f32 {
    let sole = m.character.soles[k];
    let along = sole.toe - sole.heel;
    let pitch = along.y.atan2(Vec2::new(along.x, along.z).length());
    (pitch - m.character.ground_slope).to_degrees()
}

/// True when both feet of `m` touch the ground, flat ([`FLAT_DEG`]).
fn both_flat(m: &WalkerMetrics) -> bool {
    (0..2).all(|k| m.character.contact[k] && pitch_from_ground(m, k).abs() <= FLAT_DEG)
}

/// One stop's figures, from the key to the end of the recording.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StopFigures {
    /// Seconds from the key to both feet flat for good (`None`: never).
    pub flat_after_s: Option<f32>,
    /// Largest pelvis height change in one step, less the slope's rise, cm.
    pub pelvis_step_cm: f32,
    /// Largest knee flexion change in one step, either knee, degrees.
    pub knee_step_deg: f32,
    /// Largest knee flexion, degrees.
    pub knee_max_deg: f32,
    /// Deepest sole point below the ground, cm.
    pub sole_below_cm: f32,
    /// Worst slide of a planted heel or toe, cm.
    pub slide_cm: f32,
    /// How far the centre of mass moves over the last second, cm.
    pub rest_drift_cm: f32,
}

impl StopFigures {
    /// The figures of the stop keyed before step `key` of `walked`
    /// (stepped at `dt`); the recording must end at least a second at rest.
    pub fn measure(walked: &[WalkerMetrics], dt: f32, key: usize) -> StopFigures {
        let flat_from = (key..walked.len())
            .rev()
            .take_while(|&s| both_flat(&walked[s]))
            .last();
        let mut f = StopFigures {
            flat_after_s: flat_from.map(|s| (s + 1 - key) as f32 * dt),
            pelvis_step_cm: 0.0,
            knee_step_deg: 0.0,
            knee_max_deg: 0.0,
            sole_below_cm: f32::NEG_INFINITY,
            slide_cm: 100.0 * worst_slide(&sole_samples(&walked[key.saturating_sub(60)..])),
            rest_drift_cm: 0.0,
        };
        for s in key..walked.len() {
            let (now, before) = (&walked[s], &walked[s - 1]);
            let (c, b) = (&now.character, &before.character);
            f.pelvis_step_cm = f.pelvis_step_cm.max(100.0 * pelvis_step(now, before, dt));
            for k in 0..2 {
                let knee = (c.knee_flexion[k] - b.knee_flexion[k]).abs().to_degrees();
                f.knee_step_deg = f.knee_step_deg.max(knee);
                f.knee_max_deg = f.knee_max_deg.max(c.knee_flexion[k].to_degrees());
            }
            f.sole_below_cm = f.sole_below_cm.max(100.0 * deepest_sole(now));
        }
        let second = (1.0 / dt).round() as usize;
        let last = walked.len() - 1;
        let drift = walked[last].character.com - walked[last.saturating_sub(second)].character.com;
        f.rest_drift_cm = 100.0 * drift.length();
        f
    }

    /// The goals this stop misses, each named with its figure; empty when it meets them all.
    pub fn failures(&self) -> Vec<String> {
        let goal = Goal::new;
        let flat = self.flat_after_s.unwrap_or(f32::INFINITY);
        [
            goal(FLAT_FIGURE, flat, FLAT_AFTER_GOAL_S, " s"),
            Goal::pelvis_step(self.pelvis_step_cm),
            Goal::knee_step(self.knee_step_deg),
            Goal::knee_max(self.knee_max_deg),
            Goal::sole_below(self.sole_below_cm),
            goal("slide", self.slide_cm, 100.0 * SLIDE_GOAL_M, " cm"),
            goal(
                "drift at rest",
                self.rest_drift_cm,
                100.0 * REST_DRIFT_GOAL_M,
                " cm",
            ),
        ]
        .iter()
        .filter(|g| !g.met())
        .map(Goal::to_string)
        .collect()
    }
}

impl fmt::Display for StopFigures {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let flat = self
            .flat_after_s
            .map_or("never".to_string(), |s| format!("{s:.2} s"));
        write!(
            f,
            "both feet flat after {flat}, pelvis step {:.2} cm, knee step {:.1}°, knee max {:.1}°, \
             sole below {:.2} cm, slide {:.2} cm, drift at rest {:.2} cm",
            self.pelvis_step_cm,
            self.knee_step_deg,
            self.knee_max_deg,
            self.sole_below_cm,
            self.slide_cm,
            self.rest_drift_cm
        )
    }
}
