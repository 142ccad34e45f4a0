//! The character's claims (paper §3.1): the tilt follows the slope only with
//! the controller, a higher centre of mass tilts and oscillates more, stance
//! feet neither slide nor float, and long walks stay bounded.

use softwalk_systems::character::{CharacterDesc, CharacterMetrics};

use super::measure::stance_errors;
use super::report::{Check, Claim};
use super::stats::{mean, peak_to_peak, std_dev};
use super::trace::{Trace, trace};
use super::variants::{RIGID, along_x, builtin, checked, walker, with_material, with_slope};
use super::{PaperError, PaperOptions};
use crate::scene::{PathSpec, Scene, TerrainShape};

/// The slopes of the tilt claim, degrees (uphill along the walk).
pub const SLOPES: [f32; 5] = [-20.0, -10.0, 0.0, 10.0, 20.0];
/// The start transient skipped before measuring tilts, seconds.
const SETTLE_S: f32 = 2.0;
/// Length of a measured walk, seconds.
const WALK_S: f32 = 7.0;
/// Largest stance drift the tests accept, and the sole-ground gap on level
/// ground, metres.
pub const STANCE_LIMIT: f32 = 0.01;
/// Largest sole-ground gap over a long loop with bumps and descents, metres
/// (see [`float_limit`]).
pub const LOOP_FLOAT_LIMIT: f32 = 0.075;

/// Largest gap accepted between a foot on the ground and the ground on a
/// slope of `angle_deg` degrees (positive uphill), metres.
///
/// From 5° down to 15° up a foot on the ground touches it
/// ([`STANCE_LIMIT`]). Down a slope, and up a steep one, the pelvis, which
/// moves at a bounded speed, reaches the height a foot needs a little after
/// the foot arrives: a foot a straight leg cannot reach is held above the
/// ground rather than dragged (it never slides) for a few steps (a known
/// limit of the bounded pelvis): held to 6 cm down 15° and steeper, and to
/// 5.5 cm elsewhere.
pub fn float_limit(angle_deg: f32) -> f32 {
    if angle_deg <= -15.0 {
        STEEP_DESCENT_FLOAT_LIMIT
    } else if !(-5.0..15.0).contains(&angle_deg) {
        SLOPE_FLOAT_LIMIT
    } else {
        STANCE_LIMIT
    }
}
/// [`float_limit`] off the range from 5° down to 15° up, metres.
const SLOPE_FLOAT_LIMIT: f32 = 0.055;
/// [`float_limit`] down 15° and steeper, metres.
const STEEP_DESCENT_FLOAT_LIMIT: f32 = 0.06;
/// Largest tilt of the long walk the tests accept, radians.
const MAX_TILT: f32 = 0.35;

fn deg(list: &[f32]) -> String {
    let parts: Vec<String> = list
        .iter()
        .map(|t| format!("{:+.2}°", t.to_degrees()))
        .collect();
    parts.join(", ")
}

/// Rigid ground sloped `angle_deg` along the walk; an adult with the
/// controller (`walker`), one without (`uncontrolled`) and a child (`child`).
pub fn slope_scene(angle_deg: f32) -> Result<Scene, PaperError> {
    let mut scene = with_slope(with_material(builtin("sand-flat")?, RIGID), angle_deg);
    scene.name = match angle_deg {
        a if a < 0.0 => format!("paper-slope-down-{:.0}", -a),
        a if a > 0.0 => format!("paper-slope-up-{a:.0}"),
        _ => "paper-slope-flat".to_owned(),
    };
    scene.description = format!("Rigid {angle_deg}° slope: controller on, off, and a child");
    scene.sim.duration = WALK_S;
    scene.characters = vec![
        walker(
            "walker",
            CharacterDesc::adult(),
            true,
            along_x(1.0, 3.0, 8.0),
        ),
        walker(
            "uncontrolled",
            CharacterDesc::adult(),
            false,
            along_x(1.0, 5.0, 8.0),
        ),
        walker(
            "child",
            CharacterDesc::child(),
            true,
            along_x(1.0, 7.0, 8.0),
        ),
    ];
    checked(scene)
}

fn settled_tilts(trace: &Trace, c: usize) -> Vec<f32> {
    let m = trace.walking_from(c, SETTLE_S);
    m.iter().map(|m| m.character.tilt).collect()
}

fn character_metrics(trace: &Trace, c: usize) -> impl Iterator<Item = &CharacterMetrics> {
    trace.walkers[c].iter().map(|m| &m.character)
}

/// The slope walks: tilt per slope with and without the controller, plus stance errors.
pub fn slope_claims(options: &PaperOptions) -> Result<Vec<Claim>, PaperError> {
    let (mut with, mut without) = (Vec::new(), Vec::new());
    let (mut drift, mut gaps) = (0.0f32, Vec::new());
    for angle in SLOPES {
        let scene = slope_scene(angle)?;
        options.say(&format!("walking {}", scene.name));
        let t = trace(&scene, scene.steps() as usize, |_| {})?;
        with.push(mean(settled_tilts(&t, 0)));
        without.push(mean(settled_tilts(&t, 1)));
        let mut gap = 0.0f32;
        for c in [0, 2] {
            let (d, g) = stance_errors(character_metrics(&t, c), &t.last);
            drift = drift.max(d);
            gap = gap.max(g);
        }
        gaps.push(gap);
    }
    let gaps_ok = SLOPES.iter().zip(&gaps).all(|(&a, &g)| g <= float_limit(a));
    let visible = 5.0f32.to_radians();
    let spread_with = with[4] - with[0];
    let spread_without = peak_to_peak(&without);
    let tilt = Claim {
        title: "Tilt follows the slope with the controller".into(),
        statement: "The PD controller keeps the centre of mass over the support: the body leans \
                    forward uphill and backward downhill; without it the body does not follow the slope."
            .into(),
        method: format!(
            "Scenes `paper-slope-*` (rigid ground, adult 1.75 m, 8 m along +X, {WALK_S} s); mean proxy \
             tilt after {SETTLE_S} s while walking; slopes {SLOPES:?}°."
        ),
        checks: vec![
            Check::new(
                "mean tilt with controller",
                deg(&with),
                "increasing with slope",
                with.windows(2).all(|w| w[1] > w[0]),
            ),
            Check::new(
                "lean at ∓20°",
                format!("{:+.2}° / {:+.2}°", with[0].to_degrees(), with[4].to_degrees()),
                "≤ −5° downhill, ≥ +5° uphill",
                with[0] < -visible && with[4] > visible,
            ),
            Check::new(
                "mean tilt without controller",
                deg(&without),
                format!("spread < 10 % of the controlled spread ({:.2}°)", spread_with.to_degrees()),
                spread_without < 0.1 * spread_with,
            ),
        ],
    };
    let stance = Claim {
        title: "Stance feet neither slide nor float".into(),
        statement: "Foot IK puts the planted sole on the ray-cast ground: no sliding, no floating."
            .into(),
        method: "Adult and child on the five `paper-slope-*` scenes; heel and toe anchored while \
                 within 5 mm of the ground; gap = lowest sole point to the ground while in contact."
            .into(),
        checks: vec![
            Check::new(
                "worst stance drift",
                format!("{:.4} m", drift),
                format!("≤ {STANCE_LIMIT} m"),
                drift <= STANCE_LIMIT,
            ),
            Check::new(
                "worst sole-ground gap per slope",
                gaps.iter()
                    .map(|g| format!("{g:.4} m"))
                    .collect::<Vec<_>>()
                    .join(", "),
                format!(
                    "≤ {STANCE_LIMIT} m from −5° to 15°, {SLOPE_FLOAT_LIMIT} m elsewhere, \
                     {STEEP_DESCENT_FLOAT_LIMIT} m down 15° and steeper"
                ),
                gaps_ok,
            ),
        ],
    };
    Ok(vec![tilt, stance])
}

/// Flat rigid ground with two pairs of bodies: long vs short legs, tall vs child.
pub fn com_scene() -> Result<Scene, PaperError> {
    let mut scene = with_material(builtin("sand-flat")?, RIGID);
    scene.name = "paper-com".into();
    scene.description = "Higher and lower centres of mass side by side on rigid ground".into();
    scene.sim.duration = WALK_S;
    let bodies = [
        ("walker", CharacterDesc::long_legged()),
        ("short-legged", CharacterDesc::short_legged()),
        ("tall", CharacterDesc::tall()),
        ("child", CharacterDesc::child()),
    ];
    scene.characters = bodies
        .iter()
        .enumerate()
        .map(|(k, (name, body))| walker(name, *body, true, along_x(1.0, 2.0 + 2.0 * k as f32, 8.0)))
        .collect();
    checked(scene)
}

/// A higher centre of mass tilts and oscillates more.
pub fn com_claim(options: &PaperOptions) -> Result<Claim, PaperError> {
    let scene = com_scene()?;
    options.say(&format!("walking {}", scene.name));
    let t = trace(&scene, scene.steps() as usize, |_| {})?;
    let tilts: Vec<Vec<f32>> = (0..4).map(|c| settled_tilts(&t, c)).collect();
    let pairs = [
        ("long vs short legs", 0, 1),
        ("tall 1.9 m vs child 1.0 m", 2, 3),
    ];
    let checks = pairs
        .iter()
        .map(|&(name, high, low)| {
            let (h, l) = (&tilts[high], &tilts[low]);
            Check::new(
                format!("tilt std / peak-to-peak, {name}"),
                format!(
                    "{:.3}° / {:.3}° vs {:.3}° / {:.3}°",
                    std_dev(h).to_degrees(),
                    peak_to_peak(h).to_degrees(),
                    std_dev(l).to_degrees(),
                    peak_to_peak(l).to_degrees()
                ),
                "higher COM: both larger",
                std_dev(h) > std_dev(l) && peak_to_peak(h) > peak_to_peak(l),
            )
        })
        .collect();
    Ok(Claim {
        title: "A higher centre of mass tilts and oscillates more".into(),
        statement:
            "Morphology changes the proxy's centre of mass and inertia; a higher COM swings more."
                .into(),
        method: format!(
            "Scene `paper-com` (flat rigid ground, {WALK_S} s); tilt after {SETTLE_S} s while walking."
        ),
        checks,
    })
}

/// The looped route of the long walk: laps of a 6 x 6 m square.
fn square_laps(laps: usize) -> PathSpec {
    let corners = [[2.0, 2.0], [8.0, 2.0], [8.0, 8.0], [2.0, 8.0]];
    let mut points: Vec<[f32; 2]> = corners.iter().cycle().take(4 * laps).copied().collect();
    points.push(corners[0]);
    PathSpec::Waypoints {
        points,
        corner_radius: 1.0,
    }
}

/// Gentle rigid bumps; every morphology walks laps of a square for `seconds`.
pub fn long_walk_scene(seconds: f32) -> Result<Scene, PaperError> {
    let mut scene = with_material(builtin("sand-flat")?, RIGID);
    scene.name = "paper-long-walk".into();
    scene.description = "Every morphology walks laps over gentle bumps".into();
    scene.terrain.shape = TerrainShape::Noise {
        amplitude: 0.05,
        feature_size: 1.5,
        octaves: 3,
        gain: 0.5,
        seed: 7,
    };
    scene.sim.duration = seconds;
    // Faster than the slowest walker covers it, so nobody reaches the end.
    let laps = (seconds * 2.0 / 24.0).ceil() as usize + 1;
    let bodies = [
        ("walker", CharacterDesc::adult()),
        ("child", CharacterDesc::child()),
        ("tall", CharacterDesc::tall()),
        ("long-legged", CharacterDesc::long_legged()),
        ("short-legged", CharacterDesc::short_legged()),
    ];
    scene.characters = bodies
        .iter()
        .map(|(name, body)| walker(name, *body, true, square_laps(laps)))
        .collect();
    checked(scene)
}

/// Minutes of walking stay bounded for every morphology.
pub fn long_walk_claim(options: &PaperOptions) -> Result<Claim, PaperError> {
    let seconds = options.long_walk_seconds();
    let scene = long_walk_scene(seconds)?;
    options.say(&format!("walking {} for {seconds} s", scene.name));
    let t = trace(&scene, scene.steps() as usize, |_| {})?;
    let checks = scene
        .characters
        .iter()
        .enumerate()
        .map(|(c, spec)| {
            let m = &t.walkers[c];
            let finite = m.iter().all(|m| {
                let m = &m.character;
                m.com.is_finite() && m.tilt.is_finite() && m.feet.iter().all(|f| f.is_finite())
            });
            let max_tilt = m.iter().map(|m| m.character.tilt.abs()).fold(0.0, f32::max);
            let (drift, gap) = stance_errors(character_metrics(&t, c), &t.last);
            let h = spec.body.height;
            let last = m.last().map_or(0.0, |m| m.character.com.y - m.ground_y);
            let ok = finite
                && max_tilt < MAX_TILT
                && drift <= STANCE_LIMIT
                && gap <= LOOP_FLOAT_LIMIT
                && last > 0.3 * h
                && last < h;
            Check::new(
                format!("{} ({h} m, legs ×{})", spec.name, spec.body.leg_length_factor),
                format!(
                    "finite {finite}, max tilt {:.2}°, drift {drift:.4} m, gap {gap:.4} m, final COM {last:.2} m above ground",
                    max_tilt.to_degrees()
                ),
                format!(
                    "finite, tilt < {:.0}°, drift ≤ {STANCE_LIMIT} m, gap ≤ {LOOP_FLOAT_LIMIT} m, COM in (0.3 h, h)",
                    MAX_TILT.to_degrees()
                ),
                ok,
            )
        })
        .collect();
    Ok(Claim {
        title: format!("{} of walking stay bounded", duration_words(seconds)),
        statement: "Real-time use: the controller and IK stay stable over long walks, for every morphology.".into(),
        method: format!(
            "Scene `paper-long-walk` (rigid value-noise bumps ±5 cm, laps of a 6 m square with 1 m corner arcs), {seconds} s."
        ),
        checks,
    })
}

fn duration_words(seconds: f32) -> String {
    if seconds >= 120.0 {
        format!("{:.0} minutes", seconds / 60.0)
    } else {
        format!("{seconds:.0} seconds")
    }
}
