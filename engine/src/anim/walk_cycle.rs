//! [`WalkCycle`]: the timing and sizes of a walk clip, found from where its
//! feet touch the ground.

use glam::{Mat4, Vec3};
use thiserror::Error;

use super::{BoneMap, Clip, LegChain, Playback, RigChains, RigError, Skeleton};

/// Samples per second at which a clip is analysed.
const ANALYSIS_RATE: f32 = 120.0;
/// An ankle counts as low within this fraction of its height range above its lowest.
const LOW_FRACTION: f32 = 0.2;
/// An ankle counts as slow below this fraction of the root's mean speed.
const SLOW_FRACTION: f32 = 0.35;
/// A root slower than this many leg lengths per second walks in place.
const IN_PLACE_SPEED: f32 = 0.1;
/// Largest spread of the strike-to-strike intervals around their median.
const PERIOD_TOLERANCE: f32 = 0.2;
/// Most samples one analysis takes (a clip over about 2.3 hours is refused).
const MAX_ANALYSIS_SAMPLES: usize = 1 << 20;

/// Why a clip could not be read as a walk.
#[derive(Debug, Error, PartialEq)]
pub enum WalkCycleError {
    /// The skeleton's legs were not found through the bone map.
    #[error("the clip's rig: {0}")]
    Rig(#[source] RigError),
    /// The clip has no length to analyse, or too much.
    #[error(
        "the clip lasts {duration} s: a walk clip must last more than 0 s and at most {} s",
        MAX_ANALYSIS_SAMPLES as f32 / ANALYSIS_RATE
    )]
    Duration {
        /// Its length, seconds.
        duration: f32,
    },
    /// The rig's legs have no length.
    #[error("the clip's rig has legs of zero length")]
    DegenerateLegs,
    /// The root does not travel, so feet on the ground cannot be told by their speed.
    #[error(
        "the root moves {speed:.3} leg lengths per second: a walk clip must travel forward, not walk in place"
    )]
    InPlace {
        /// Root speed in leg lengths per second.
        speed: f32,
    },
    /// No foot ever rests on the ground.
    #[error("no foot is ever low and still: the clip has no ground contacts")]
    NoContacts,
    /// Only one foot ever rests on the ground.
    #[error("only the {touching} foot touches the ground; a walk needs both")]
    OneFoot {
        /// `left` or `right`.
        touching: &'static str,
    },
    /// A foot lands fewer than twice, or its steps are not evenly spaced.
    #[error("the {foot} foot's landings are not periodic: {reason}")]
    NotPeriodic {
        /// `left` or `right`.
        foot: &'static str,
        /// What was seen.
        reason: String,
    },
}

/// A walk clip's cycle: how long, how far, how much of it each foot stands.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WalkCycle {
    /// One cycle (two steps), seconds.
    pub period: f32,
    /// Fraction of the cycle a foot is on the ground (both feet averaged).
    pub duty: f32,
    /// Distance the root travels in one cycle, in the skeleton's units.
    pub stride: f32,
    /// Root speed, skeleton units per second.
    pub speed: f32,
    /// Clip time of the first left heel strike, seconds.
    pub left_strike: f32,
    /// Phase of the right heel strike after the left one, in `[0, 1)` (about 0.5).
    pub right_phase: f32,
    /// Rest length of the legs (hip to knee to ankle, both averaged), skeleton units.
    pub leg_length: f32,
}

/// Where one foot stands, sample by sample.
struct FootTrack {
    name: &'static str,
    contact: Vec<bool>,
}

impl FootTrack {
    /// Sample indices where the foot lands (not in contact, then in contact).
    fn strikes(&self) -> Vec<usize> {
        (1..self.contact.len())
            .filter(|&k| self.contact[k] && !self.contact[k - 1])
            .collect()
    }
}

impl WalkCycle {
    /// Analyses `clip` playing on `skeleton`, whose legs `map` names: a foot
    /// is on the ground while its ankle is low (within a fifth of its height
    /// range above its lowest) and slow (below about a third of the root's
    /// mean speed); a heel strike is where a contact starts. Up is +Y.
    pub fn analyse(
        clip: &Clip,
        skeleton: &Skeleton,
        map: &BoneMap,
    ) -> Result<WalkCycle, WalkCycleError> {
        let chains = RigChains::find(skeleton, map).map_err(WalkCycleError::Rig)?;
        let leg_length = 0.5
            * (chains.leg_length(skeleton, &chains.left)
                + chains.leg_length(skeleton, &chains.right));
        if leg_length.is_nan() || leg_length <= 0.0 {
            return Err(WalkCycleError::DegenerateLegs);
        }
        let duration = clip.duration();
        let fits = duration * ANALYSIS_RATE < MAX_ANALYSIS_SAMPLES as f32;
        if !(duration > 0.0 && fits) {
            return Err(WalkCycleError::Duration { duration });
        }
        let samples = (duration * ANALYSIS_RATE).floor() as usize + 1;
        let dt = 1.0 / ANALYSIS_RATE;
        let paths = joint_paths(clip, skeleton, samples, dt, &chains);
        let root_travel = horizontal(paths.pelvis[samples - 1] - paths.pelvis[0]).length();
        let root_speed = root_travel / ((samples - 1) as f32 * dt);
        if root_speed.is_nan() || root_speed < IN_PLACE_SPEED * leg_length {
            return Err(WalkCycleError::InPlace {
                speed: root_speed / leg_length,
            });
        }
        let slow = root_speed * SLOW_FRACTION;
        let feet = [
            foot_track("left", &paths.ankles[0], &paths.toes[0], slow, dt),
            foot_track("right", &paths.ankles[1], &paths.toes[1], slow, dt),
        ];
        let touches = feet.each_ref().map(|f| f.contact.iter().any(|&c| c));
        match touches {
            [false, false] => return Err(WalkCycleError::NoContacts),
            [true, false] => return Err(WalkCycleError::OneFoot { touching: "left" }),
            [false, true] => return Err(WalkCycleError::OneFoot { touching: "right" }),
            [true, true] => {}
        }
        let strikes = feet.each_ref().map(FootTrack::strikes);
        let periods = [
            period(&feet[0], &strikes[0])?,
            period(&feet[1], &strikes[1])?,
        ];
        let period_samples = 0.5 * (periods[0] + periods[1]);
        let duty = 0.5 * (duty(&feet[0], &strikes[0]) + duty(&feet[1], &strikes[1]));
        let period = period_samples * dt;
        let left_strike = strikes[0][0] as f32 * dt;
        let right_phase =
            ((strikes[1][0] as f32 - strikes[0][0] as f32) / period_samples).rem_euclid(1.0);
        Ok(WalkCycle {
            period,
            duty,
            stride: root_speed * period,
            speed: root_speed,
            left_strike,
            right_phase,
            leg_length,
        })
    }

    /// Steps per minute (two per cycle).
    pub fn cadence(&self) -> f32 {
        120.0 / self.period
    }

    /// The walk phase at clip time `time`: 0 at a left heel strike, in `[0, 1)`.
    pub fn phase_at(&self, time: f32) -> f32 {
        ((time - self.left_strike) / self.period).rem_euclid(1.0)
    }

    /// The clip time of walk phase `phase` (0 = left heel strike) within the
    /// clip's first cycle after its first left heel strike, or the cycle before
    /// it where the clip is too short to hold that much after it.
    pub fn clip_time(&self, phase: f32, duration: f32) -> f32 {
        let t = self.left_strike + phase.rem_euclid(1.0) * self.period;
        if t > duration {
            (t - self.period).max(0.0)
        } else {
            t
        }
    }
}

/// World positions of the pelvis and of both feet's ankle and toe joints (the
/// ankle for a foot without a toe joint),
/// sample by sample.
struct JointPaths {
    pelvis: Vec<Vec3>,
    ankles: [Vec<Vec3>; 2],
    toes: [Vec<Vec3>; 2],
}

fn joint_paths(
    clip: &Clip,
    skeleton: &Skeleton,
    samples: usize,
    dt: f32,
    chains: &RigChains,
) -> JointPaths {
    let mut paths = JointPaths {
        pelvis: Vec::with_capacity(samples),
        ankles: [Vec::with_capacity(samples), Vec::with_capacity(samples)],
        toes: [Vec::with_capacity(samples), Vec::with_capacity(samples)],
    };
    let mut pose = skeleton.rest_pose();
    let mut globals: Vec<Mat4> = Vec::with_capacity(skeleton.len());
    let at = |globals: &[Mat4], j: usize| globals[j].w_axis.truncate();
    let legs: [&LegChain; 2] = [&chains.left, &chains.right];
    for k in 0..samples {
        clip.sample(k as f32 * dt, Playback::Once, skeleton, &mut pose);
        pose.globals(skeleton, &mut globals);
        paths.pelvis.push(at(&globals, chains.pelvis));
        for (side, leg) in legs.iter().enumerate() {
            paths.ankles[side].push(at(&globals, leg.ankle));
            paths.toes[side].push(at(&globals, leg.toe.unwrap_or(leg.ankle)));
        }
    }
    paths
}

fn horizontal(v: Vec3) -> Vec3 {
    Vec3::new(v.x, 0.0, v.z)
}

/// A foot's contact per sample: its ankle (heel down) or its toe joint (heel up;
/// the ankle again on a rig without toes) low and slower than `slow`.
fn foot_track(name: &'static str, ankle: &[Vec3], toe: &[Vec3], slow: f32, dt: f32) -> FootTrack {
    let (ankle_rests, toe_rests) = (resting(ankle, slow, dt), resting(toe, slow, dt));
    let contact = ankle_rests
        .iter()
        .zip(&toe_rests)
        .map(|(&a, &t)| a || t)
        .collect();
    FootTrack { name, contact }
}

/// Per sample, whether a joint is low (within [`LOW_FRACTION`] of its height
/// range above its lowest) and its horizontal speed below `slow`.
fn resting(path: &[Vec3], slow: f32, dt: f32) -> Vec<bool> {
    let (lowest, highest) = path
        .iter()
        .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(p.y), hi.max(p.y))
        });
    let low = lowest + LOW_FRACTION * (highest - lowest);
    let last = path.len() - 1;
    (0..path.len())
        .map(|k| {
            let (before, after) = (k.saturating_sub(1), (k + 1).min(last));
            let span = (after - before).max(1) as f32 * dt;
            let speed = horizontal(path[after] - path[before]).length() / span;
            path[k].y <= low && speed < slow
        })
        .collect()
}

/// The median samples between a foot's strikes; refused if it lands fewer
/// than twice or its intervals stray from the median.
fn period(foot: &FootTrack, strikes: &[usize]) -> Result<f32, WalkCycleError> {
    let not_periodic = |reason: String| WalkCycleError::NotPeriodic {
        foot: foot.name,
        reason,
    };
    if strikes.len() < 2 {
        return Err(not_periodic(format!(
            "it lands {} time(s); a cycle needs two landings",
            strikes.len()
        )));
    }
    let mut gaps: Vec<f32> = strikes.windows(2).map(|w| (w[1] - w[0]) as f32).collect();
    gaps.sort_by(f32::total_cmp);
    let median = gaps[gaps.len() / 2];
    let (shortest, longest) = (gaps[0], gaps[gaps.len() - 1]);
    if shortest < median * (1.0 - PERIOD_TOLERANCE) || longest > median * (1.0 + PERIOD_TOLERANCE) {
        return Err(not_periodic(format!(
            "landings {:.3} to {:.3} s apart",
            shortest / ANALYSIS_RATE,
            longest / ANALYSIS_RATE
        )));
    }
    Ok(median)
}

/// The fraction of samples in contact from a foot's first strike to its last.
fn duty(foot: &FootTrack, strikes: &[usize]) -> f32 {
    let (first, last) = (strikes[0], strikes[strikes.len() - 1]);
    let on = foot.contact[first..last].iter().filter(|&&c| c).count();
    on as f32 / (last - first) as f32
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::anim::Property;
    use crate::anim::bvh::{BvhClip, load_bvh, load_bvh_from_str};
    use std::path::Path;

    fn shipped_path() -> std::path::PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/clips/walk.bvh")
    }

    fn shipped() -> BvhClip {
        load_bvh(&shipped_path()).unwrap()
    }

    #[test]
    fn the_shipped_walk_has_a_normal_adult_cycle() {
        let bvh = shipped();
        let map = BoneMap::detect(&bvh.skeleton);
        let cycle = WalkCycle::analyse(&bvh.clip, &bvh.skeleton, &map).unwrap();
        assert!((cycle.period - 1.1).abs() < 0.02, "{cycle:?}");
        assert!((0.5..0.7).contains(&cycle.duty), "{cycle:?}");
        assert!((120.0..160.0).contains(&cycle.speed), "cm/s: {cycle:?}");
        assert!((cycle.stride - cycle.speed * cycle.period).abs() < 1e-3);
        assert!((0.45..0.55).contains(&cycle.right_phase), "{cycle:?}");
        assert!((cycle.leg_length - 85.0).abs() < 1.0, "{cycle:?}");
        // The generator puts the left heel strike at every multiple of 1.1 s.
        let k = (cycle.left_strike / 1.1).round();
        assert!((cycle.left_strike - 1.1 * k).abs() < 0.05, "{cycle:?}");
        assert!((cycle.phase_at(cycle.left_strike + 0.25 * cycle.period) - 0.25).abs() < 1e-4);
        let t = cycle.clip_time(0.75, bvh.clip.duration());
        assert!((cycle.phase_at(t) - 0.75).abs() < 1e-4);
        assert!(t <= bvh.clip.duration());
    }

    /// The clip with the rotations of the named joints removed.
    fn without(bvh: &BvhClip, joints: &[&str]) -> Clip {
        let drop: Vec<usize> = joints.iter().filter_map(|n| bvh.skeleton.find(n)).collect();
        let channels = bvh
            .clip
            .channels()
            .iter()
            .filter(|c| !(drop.contains(&c.joint()) && c.property() == Property::Rotation))
            .cloned()
            .collect();
        Clip::new("cut".into(), channels, bvh.skeleton.len()).unwrap()
    }

    /// The shipped clip cut to its first `frames` frames.
    fn first_frames(frames: usize) -> BvhClip {
        let text = std::fs::read_to_string(shipped_path()).unwrap();
        let (head, motion) = text.split_once("MOTION").unwrap();
        let lines: Vec<&str> = motion.lines().skip(3).take(frames).collect();
        let cut = format!(
            "{head}MOTION\nFrames: {frames}\nFrame Time: 0.016667\n{}\n",
            lines.join("\n")
        );
        load_bvh_from_str(&cut, Path::new("cut.bvh")).unwrap()
    }

    #[test]
    fn clips_that_are_not_walks_are_refused_with_their_reason() {
        let bvh = shipped();
        let map = BoneMap::detect(&bvh.skeleton);
        let analyse = |clip: &Clip| WalkCycle::analyse(clip, &bvh.skeleton, &map);
        // Standing still: the rest pose everywhere.
        let still = Clip::new("still".into(), Vec::new(), bvh.skeleton.len()).unwrap();
        assert!(matches!(
            analyse(&still),
            Err(WalkCycleError::Duration { .. })
        ));
        // The root travels but the legs stay in rest pose, floating: the
        // feet never move relative to it, so they are never slow.
        let gliding = without(
            &bvh,
            &[
                "LeftUpLeg",
                "LeftLeg",
                "LeftFoot",
                "RightUpLeg",
                "RightLeg",
                "RightFoot",
                "Hips",
            ],
        );
        let e = analyse(&gliding).unwrap_err();
        assert!(matches!(e, WalkCycleError::NoContacts), "{e}");
        // The right leg frozen in rest: only the left foot steps.
        let hopping = without(&bvh, &["RightUpLeg", "RightLeg", "RightFoot"]);
        let e = analyse(&hopping).unwrap_err();
        assert_eq!(e, WalkCycleError::OneFoot { touching: "left" });
        // The first 0.9 s (55 frames): the left foot stands from the start and
        // never lands again.
        let e = analyse(&first_frames(55).clip).unwrap_err();
        assert!(matches!(e, WalkCycleError::NotPeriodic { .. }), "{e}");
    }
}
