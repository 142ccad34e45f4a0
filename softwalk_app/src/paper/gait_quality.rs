//! Gait quality: the figures of the design's "gait quality on every scene"
//! goals, measured from one character's recorded walk.
//!
//! Every figure is taken over the walking samples ([`super::walking_samples`]):
//! - pelvis step: the largest change of the pelvis height between two
//!   consecutive walking samples, less the rise of the ground's slope under
//!   the walk over that step (a walker going up a steady 20° slope at
//!   1.3 m/s rises 0.8 cm a step without any pop), cm (goal ≤ 1 cm);
//! - knee step: the largest change of either knee's flexion between two
//!   consecutive walking samples, degrees (goal ≤ 10°);
//! - knee reversals: the share of planted foot-samples whose knee is more than
//!   10° above both neighbouring samples or more than 10° below both (a
//!   flicker), percent (goal ≤ 1 %);
//! - stance knee: the mean knee flexion of planted legs (in the stance of
//!   their walk cycle, bearing weight), degrees (goal ≤ 25°);
//! - knee max: the largest knee flexion of either leg, degrees (goal ≤ 120°);
//! - sole below ground: how far the heel or toe sits below the ground under
//!   it, at worst, cm (goal ≤ 2 cm);
//! - planted float: how far the lower end of a planted sole sits above the
//!   ground under it, at worst, cm (reported; its goal depends on the
//!   ground, see `tests/tests/gait_unseen.rs` and `paper::character::float_limit`).

use std::fmt;

use softwalk_systems::sim::WalkerMetrics;

use super::walking_samples::walking_mask;

/// Goal: largest pelvis height change in one step, cm.
pub const PELVIS_STEP_GOAL_CM: f32 = 1.0;
/// Goal: largest knee flexion change in one step, degrees.
pub const KNEE_STEP_GOAL_DEG: f32 = 10.0;
/// A stance knee this far (degrees) above or below both neighbours is a reversal.
pub const KNEE_REVERSAL_DEG: f32 = 10.0;
/// Goal: share of stance samples with a knee reversal, percent.
pub const KNEE_REVERSAL_GOAL_PCT: f32 = 1.0;
/// Goal: mean stance knee flexion, degrees.
pub const STANCE_KNEE_GOAL_DEG: f32 = 25.0;
/// Built-in scenes whose walk steps up onto props and down again: the
/// stance knee bends there as on a stair, so the level-walk goal of a mean
/// stance knee (the figure `"stance knee mean"`, [`STANCE_KNEE_GOAL_DEG`])
/// does not apply to them; every other goal does.
pub const STEP_UP_SCENES: [&str; 1] = ["props"];
/// The figure [`STEP_UP_SCENES`] are not held to.
pub const LEVEL_WALK_FIGURE: &str = "stance knee mean";
/// Goal: largest knee flexion anywhere, degrees.
pub const KNEE_MAX_GOAL_DEG: f32 = 120.0;
/// Goal: lowest sole point below the ground, cm.
pub const SOLE_BELOW_GOAL_CM: f32 = 2.0;

/// The gait-quality figures of one character's walk.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct GaitQuality {
    /// Walking samples measured.
    pub walking_samples: usize,
    /// Stance foot-samples measured (a sample with both feet down counts twice).
    pub stance_samples: usize,
    /// Largest pelvis height change in one step less the slope's rise, cm.
    pub pelvis_step_cm: f32,
    /// Largest knee flexion change in one step, either knee, degrees.
    pub knee_step_deg: f32,
    /// Share of stance foot-samples with a knee reversal, percent.
    pub knee_reversal_pct: f32,
    /// Mean knee flexion of planted legs, degrees.
    pub stance_knee_deg: f32,
    /// Largest knee flexion of either leg, degrees.
    pub knee_max_deg: f32,
    /// Deepest heel or toe below the ground under it, cm (negative: always above).
    pub sole_below_cm: f32,
    /// Highest a planted sole's lower end (heel or toe) stands above the
    /// ground under it, cm (0 when every planted sole touches or is pressed in).
    pub planted_float_cm: f32,
}

/// One figure against its goal (the figure must not exceed the limit).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Goal {
    /// What is measured.
    pub figure: &'static str,
    /// The measured value.
    pub value: f32,
    /// The largest accepted value.
    pub limit: f32,
    /// Unit, with its leading space where one is written (` cm`, `°`, ` %`).
    pub unit: &'static str,
}

impl Goal {
    /// The goal that `figure`, measured as `value` (in `unit`), is at most `limit`.
    pub fn new(figure: &'static str, value: f32, limit: f32, unit: &'static str) -> Goal {
        Goal {
            figure,
            value,
            limit,
            unit,
        }
    }

    /// The pelvis step `cm` against [`PELVIS_STEP_GOAL_CM`].
    pub fn pelvis_step(cm: f32) -> Goal {
        Goal::new("pelvis step", cm, PELVIS_STEP_GOAL_CM, " cm")
    }

    /// The knee step `deg` against [`KNEE_STEP_GOAL_DEG`].
    pub fn knee_step(deg: f32) -> Goal {
        Goal::new("knee step", deg, KNEE_STEP_GOAL_DEG, "°")
    }

    /// The largest knee flexion `deg` against [`KNEE_MAX_GOAL_DEG`].
    pub fn knee_max(deg: f32) -> Goal {
        Goal::new("knee max", deg, KNEE_MAX_GOAL_DEG, "°")
    }

    /// The deepest sole `cm` below the ground against [`SOLE_BELOW_GOAL_CM`].
    pub fn sole_below(cm: f32) -> Goal {
        Goal::new("sole below ground", cm, SOLE_BELOW_GOAL_CM, " cm")
    }

    /// True when the value is at most the limit (NaN fails).
    pub fn met(&self) -> bool {
        self.value <= self.limit
    }

    /// The value with its unit.
    pub fn measured(&self) -> String {
        format!("{:.2}{}", self.value, self.unit)
    }

    /// The goal as a condition (`≤ 1 cm`).
    pub fn threshold(&self) -> String {
        format!("≤ {}{}", self.limit, self.unit)
    }
}

impl fmt::Display for Goal {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} {} (goal {})",
            self.figure,
            self.measured(),
            self.threshold()
        )
    }
}

impl GaitQuality {
    /// Measures a character's recorded walk: `series[s]` is its state after
    /// step `s`, stepped at `dt` seconds.
    pub fn measure(series: &[WalkerMetrics], dt: f32) -> GaitQuality {
        let walking = walking_mask(series, dt);
        let mut q = GaitQuality {
            sole_below_cm: f32::NEG_INFINITY,
            ..GaitQuality::default()
        };
        let (mut stance_sum, mut reversals) = (0.0f64, 0usize);
        for (s, m) in series.iter().enumerate() {
            if !walking[s] {
                continue;
            }
            q.walking_samples += 1;
            let c = &m.character;
            q.sole_below_cm = q.sole_below_cm.max(100.0 * deepest_sole(m));
            q.planted_float_cm = q.planted_float_cm.max(100.0 * planted_float(m));
            for (k, &knee) in c.knee_flexion.iter().enumerate() {
                q.knee_max_deg = q.knee_max_deg.max(knee.to_degrees());
                if c.planted[k] {
                    q.stance_samples += 1;
                    stance_sum += f64::from(knee.to_degrees());
                    reversals += usize::from(knee_reversal(series, s, k));
                }
            }
            if s > 0 && walking[s - 1] {
                let before = &series[s - 1].character;
                let pelvis = pelvis_step(m, &series[s - 1], dt);
                q.pelvis_step_cm = q.pelvis_step_cm.max(100.0 * pelvis);
                for k in 0..2 {
                    let knee = (c.knee_flexion[k] - before.knee_flexion[k]).abs();
                    q.knee_step_deg = q.knee_step_deg.max(knee.to_degrees());
                }
            }
        }
        if q.walking_samples == 0 {
            q.sole_below_cm = 0.0;
        }
        if q.stance_samples > 0 {
            q.stance_knee_deg = (stance_sum / q.stance_samples as f64) as f32;
            q.knee_reversal_pct = 100.0 * reversals as f32 / q.stance_samples as f32;
        }
        q
    }

    /// Every figure against its goal, in the order of the design's table.
    pub fn goals(&self) -> [Goal; 6] {
        [
            Goal::pelvis_step(self.pelvis_step_cm),
            Goal::knee_step(self.knee_step_deg),
            Goal::new(
                "stance knee reversals",
                self.knee_reversal_pct,
                KNEE_REVERSAL_GOAL_PCT,
                " %",
            ),
            Goal::new(
                LEVEL_WALK_FIGURE,
                self.stance_knee_deg,
                STANCE_KNEE_GOAL_DEG,
                "°",
            ),
            Goal::knee_max(self.knee_max_deg),
            Goal::sole_below(self.sole_below_cm),
        ]
    }

    /// The goals missed, each naming its figure, value and goal; a walk with
    /// no walking sample fails as such.
    pub fn failures(&self) -> Vec<String> {
        self.failures_held_to(false)
    }

    /// [`Self::failures`] of a walk that steps up onto something
    /// (`step_up`, see [`STEP_UP_SCENES`]): it is not held to the level
    /// walk's figure, [`LEVEL_WALK_FIGURE`].
    pub fn failures_held_to(&self, step_up: bool) -> Vec<String> {
        let mut failed: Vec<String> = self
            .goals()
            .iter()
            .filter(|g| !(step_up && g.figure == LEVEL_WALK_FIGURE))
            .filter(|g| !g.met())
            .map(Goal::to_string)
            .collect();
        if self.walking_samples == 0 {
            failed.insert(0, "no walking sample to measure".to_owned());
        }
        failed
    }

    /// True when every goal is met on at least one walking sample.
    pub fn passes(&self) -> bool {
        self.failures().is_empty()
    }
}

impl fmt::Display for GaitQuality {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let figures: Vec<String> = self
            .goals()
            .iter()
            .map(|g| format!("{} {}", g.figure, g.measured()))
            .collect();
        write!(
            f,
            "{}, planted float {:.2} cm ({} walking samples)",
            figures.join(", "),
            self.planted_float_cm,
            self.walking_samples
        )
    }
}

/// How far the pelvis moves up or down from `before` to `now`, a step of
/// `dt` seconds apart, beyond the rise of the slope it walks on, metres.
pub fn pelvis_step(now: &WalkerMetrics, before: &WalkerMetrics, dt: f32) -> f32 {
    let rise = 0.5 * (slope_rise_rate(now) + slope_rise_rate(before)) * dt;
    (now.character.pelvis_y - before.character.pelvis_y - rise).abs()
}

/// How fast the ground's slope under the pelvis rises along the walk, m/s:
/// the walking speed times the slope's tangent (uphill positive).
fn slope_rise_rate(m: &WalkerMetrics) -> f32 {
    m.velocity.length() * m.character.ground_slope.tan()
}

/// How far the lower of heel and toe of either foot sits below the ground
/// under it, metres (negative when both soles are above the ground).
pub fn deepest_sole(m: &WalkerMetrics) -> f32 {
    (0..2)
        .map(|k| m.sole_ground[k].buried(&m.character.soles[k]))
        .fold(f32::NEG_INFINITY, f32::max)
}

/// How far the lower end of the higher planted sole stands above the
/// ground under it, metres (0 when no planted sole is above the ground).
fn planted_float(m: &WalkerMetrics) -> f32 {
    (0..2)
        .filter(|&k| m.character.planted[k])
        .map(|k| -m.sole_ground[k].buried(&m.character.soles[k]))
        .fold(0.0, f32::max)
}

/// True when leg `k`'s knee at sample `s` is more than [`KNEE_REVERSAL_DEG`]
/// above both neighbouring samples or below both (false at either end).
fn knee_reversal(series: &[WalkerMetrics], s: usize, k: usize) -> bool {
    if s == 0 || s + 1 >= series.len() {
        return false;
    }
    let knee = |i: usize| series[i].character.knee_flexion[k].to_degrees();
    let (before, now, after) = (knee(s - 1), knee(s), knee(s + 1));
    now - before.max(after) > KNEE_REVERSAL_DEG || before.min(after) - now > KNEE_REVERSAL_DEG
}

#[cfg(test)]
mod tests {
    use softwalk_systems::sim::SoleGround;

    use super::*;
    use crate::runner::test_records;

    const DT: f32 = 0.25;

    /// Eight samples at 4 Hz (walking from the fourth on, one second), planted,
    /// knees at 5°.
    fn walk() -> Vec<WalkerMetrics> {
        let mut m = test_records::standing();
        m.character.knee_flexion = [5f32.to_radians(); 2];
        vec![m; 8]
    }

    #[test]
    fn a_steady_walk_meets_every_goal() {
        let q = GaitQuality::measure(&walk(), DT);
        assert_eq!(q.walking_samples, 5);
        assert_eq!(q.stance_samples, 10);
        assert!((q.stance_knee_deg - 5.0).abs() < 1e-4);
        assert_eq!(q.pelvis_step_cm, 0.0);
        assert_eq!(q.sole_below_cm, 0.0);
        assert!(q.passes(), "{:?}", q.failures());
    }

    #[test]
    fn pops_flickers_and_buried_soles_are_named() {
        let mut series = walk();
        // A 3 cm pelvis pop at sample 5, a 30° flicker of the left knee at sample 6.
        series[5].character.pelvis_y += 0.03;
        series[6].character.knee_flexion[0] = 35f32.to_radians();
        // The right toe 5 cm under the ground at sample 7.
        series[7].sole_ground[1] = SoleGround {
            toe: 0.05,
            ..SoleGround::default()
        };
        // Before the first second nothing counts.
        series[0].character.knee_flexion[1] = 3.0;
        let q = GaitQuality::measure(&series, DT);
        assert!((q.pelvis_step_cm - 3.0).abs() < 1e-3);
        assert!((q.knee_step_deg - 30.0).abs() < 1e-3);
        assert!((q.knee_reversal_pct - 10.0).abs() < 1e-4, "1 of 10");
        assert!((q.knee_max_deg - 35.0).abs() < 1e-3);
        assert!((q.sole_below_cm - 5.0).abs() < 1e-4);
        let failures = q.failures();
        assert_eq!(failures.len(), 4, "{failures:?}");
        assert_eq!(failures[0], "pelvis step 3.00 cm (goal ≤ 1 cm)");
        assert!(failures[2].starts_with("stance knee reversals 10.00 %"));
        assert!(q.to_string().contains("knee step 30.00°"), "{q}");
    }

    #[test]
    fn only_a_planted_sole_above_the_ground_floats() {
        let mut series = walk();
        assert_eq!(GaitQuality::measure(&series, DT).planted_float_cm, 0.0);
        // The left heel 6 cm above the ground under it at sample 5 (its toe
        // higher still), planted: it floats 6 cm.
        series[5].sole_ground[0] = SoleGround {
            heel: -0.06,
            toe: -0.08,
            ..SoleGround::default()
        };
        // The right sole 20 cm up at sample 6, but swinging: no float.
        series[6].sole_ground[1] = SoleGround {
            heel: -0.2,
            toe: -0.2,
            ..SoleGround::default()
        };
        series[6].character.planted[1] = false;
        let q = GaitQuality::measure(&series, DT);
        assert!((q.planted_float_cm - 6.0).abs() < 1e-3, "{q}");
        assert!(q.to_string().contains("planted float 6.00 cm"), "{q}");
    }

    #[test]
    fn a_steady_climb_is_not_a_pop_but_a_pop_on_it_is() {
        // Up 20° at 1 m/s: the pelvis rises with the ground, 9.1 cm a sample.
        let slope = 20f32.to_radians();
        let mut series = walk();
        for (s, m) in series.iter_mut().enumerate() {
            m.velocity = glam::Vec3::new(1.0, 0.0, 0.0);
            m.character.ground_slope = slope;
            m.character.pelvis_y += s as f32 * DT * slope.tan();
        }
        assert!(GaitQuality::measure(&series, DT).pelvis_step_cm < 1e-3);
        series[5].character.pelvis_y -= 0.02;
        let q = GaitQuality::measure(&series, DT);
        assert!((q.pelvis_step_cm - 2.0).abs() < 1e-3, "{q}");
    }

    #[test]
    fn no_walking_sample_is_a_failure() {
        let mut series = walk();
        series.iter_mut().for_each(|m| m.path_finished = true);
        let q = GaitQuality::measure(&series, DT);
        assert_eq!(q.failures(), ["no walking sample to measure"]);
    }
}
