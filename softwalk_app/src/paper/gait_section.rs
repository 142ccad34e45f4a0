//! The report's gait-quality section: every built-in scene, every character
//! in it, each figure of [`GaitQuality`] against the design's goal.

use super::gait_quality::{GaitQuality, LEVEL_WALK_FIGURE, STEP_UP_SCENES};
use super::recorded_run::record_run;
use super::report::{Check, Claim};
use super::variants::builtin;
use super::walking_samples::SETTLE_S;
use super::{PaperError, PaperOptions};
use crate::scene::{Scene, builtin_scenes};

/// Title of the report's section.
pub const GAIT_SECTION_TITLE: &str = "Gait quality";
/// Longest walk measured per scene with `--quick`, seconds.
const QUICK_GAIT_S: f32 = 6.0;
/// Scenes with more characters than this report, per goal, the worst
/// character and how many miss it, instead of one row per character.
const MAX_LISTED_CHARACTERS: usize = 8;

/// What each scene's claim states (the design's "gait quality on every scene").
const STATEMENT: &str = "Every character walks without a pelvis pop, a knee flicker or a buried \
                         sole: at 60 Hz a pelvis step ≤ 1 cm, a knee step ≤ 10°, stance knee \
                         reversals ≤ 1 %, a mean stance knee ≤ 25°, a knee ≤ 120° anywhere and no \
                         heel or toe more than 2 cm below the ground.";

/// Walks `scene` headless for `seconds` at its own step and turns every
/// character's [`GaitQuality`] into a claim (one check per character and goal).
pub fn gait_quality_claim(scene: &Scene, seconds: f32) -> Result<Claim, PaperError> {
    let steps = scene.sim.steps_for(f64::from(seconds));
    let run = record_run(scene, steps).map_err(|source| PaperError::Run {
        scene: scene.name.clone(),
        source,
    })?;
    let qualities: Vec<(&str, GaitQuality)> = scene
        .characters
        .iter()
        .enumerate()
        .map(|(c, spec)| (spec.name.as_str(), run.quality(c)))
        .collect();
    let checks = if qualities.len() > MAX_LISTED_CHARACTERS {
        crowd_checks(&qualities)
    } else {
        qualities
            .iter()
            .flat_map(|(name, q)| character_checks(name, q))
            .collect()
    };
    let step_up = STEP_UP_SCENES.contains(&scene.name.as_str());
    let checks: Vec<Check> = (checks.into_iter())
        .filter(|c| !(step_up && c.quantity.ends_with(LEVEL_WALK_FIGURE)))
        .collect();
    Ok(Claim {
        title: format!("{GAIT_SECTION_TITLE}: {}", scene.name),
        statement: STATEMENT.into(),
        method: format!(
            "Scene `{}` headless, {seconds} s at dt {:.4} s; walking samples from {SETTLE_S} s \
             until the path's end (figures defined in `softwalk_app/src/paper/gait_quality.rs`){}.",
            scene.name,
            scene.sim.dt,
            if step_up {
                "; the walk steps up onto a prop, so the level-walk stance knee mean is not checked"
            } else {
                ""
            }
        ),
        checks,
    })
}

/// The checks of one character: one per goal, or one failing check when
/// nothing was walking.
fn character_checks(name: &str, q: &GaitQuality) -> Vec<Check> {
    if q.walking_samples == 0 {
        return vec![Check::new(
            format!("{name}: walking samples"),
            "0",
            "> 0",
            false,
        )];
    }
    q.goals()
        .iter()
        .map(|g| {
            Check::new(
                format!("{name}: {}", g.figure),
                g.measured(),
                g.threshold(),
                g.met(),
            )
        })
        .collect()
}

/// The checks of a crowd: per goal, the worst character and how many of
/// the walking characters miss the goal; one failing check for characters
/// that never walked.
fn crowd_checks(qualities: &[(&str, GaitQuality)]) -> Vec<Check> {
    let walking: Vec<&(&str, GaitQuality)> = qualities
        .iter()
        .filter(|(_, q)| q.walking_samples > 0)
        .collect();
    let idle = qualities.len() - walking.len();
    let mut checks = Vec::new();
    if idle > 0 {
        checks.push(Check::new(
            "characters without walking samples",
            idle.to_string(),
            "0",
            false,
        ));
    }
    let Some((_, first)) = walking.first() else {
        return checks;
    };
    for k in 0..first.goals().len() {
        let goal_of = |q: &GaitQuality| q.goals()[k];
        let Some((worst_name, worst)) = walking
            .iter()
            .map(|(name, q)| (*name, goal_of(q)))
            .max_by(|a, b| a.1.value.total_cmp(&b.1.value))
        else {
            continue;
        };
        let missing = walking.iter().filter(|(_, q)| !goal_of(q).met()).count();
        checks.push(Check::new(
            format!(
                "{}: worst of {} ({worst_name}); {missing} miss it",
                worst.figure,
                walking.len()
            ),
            worst.measured(),
            worst.threshold(),
            missing == 0,
        ));
    }
    checks
}

/// One claim per built-in scene, each walked for its own duration (at most
/// `QUICK_GAIT_S` with `--quick`).
pub fn gait_quality_claims(options: &PaperOptions) -> Result<Vec<Claim>, PaperError> {
    let mut claims = Vec::new();
    for b in builtin_scenes() {
        let scene = builtin(&b.name)?;
        let seconds = match options.quick {
            true => scene.sim.duration.min(QUICK_GAIT_S),
            false => scene.sim.duration,
        };
        options.say(&format!("gait quality on {}", b.name));
        claims.push(gait_quality_claim(&scene, seconds)?);
    }
    Ok(claims)
}
