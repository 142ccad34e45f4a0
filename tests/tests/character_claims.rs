//! The character's measurable claims (paper §3.1 and the brief): tilt follows
//! the slope with the controller, a higher COM tilts and oscillates more,
//! stance feet neither slide nor float, and long walks stay bounded.

use engine::geom::HeightGrid;
use glam::{Vec2, Vec3};
use softwalk_app::paper::character::{LOOP_FLOAT_LIMIT, STANCE_LIMIT, float_limit};
use softwalk_app::paper::stats::{mean, peak_to_peak, std_dev};
use softwalk_systems::character::{
    Character, CharacterDesc, CharacterMetrics, PathSegment, WalkPath, step_character,
};
use softwalk_systems::ground::Ground;

const DT: f32 = 1.0 / 60.0;

/// A ramp rising along +Z at `degrees`, 6 m wide, 18 m long.
fn ramp(degrees: f32) -> HeightGrid {
    let grade = degrees.to_radians().tan();
    HeightGrid::from_fn(Vec2::new(-3.0, -3.0), 0.05, 121, 361, |_, z| grade * z).unwrap()
}

/// Gentle bumps of a few centimetres over a 14 x 14 m patch.
fn bumpy() -> HeightGrid {
    HeightGrid::from_fn(Vec2::new(-7.0, -7.0), 0.05, 281, 281, |x, z| {
        0.04 * (1.7 * x).sin() * (1.3 * z).cos() + 0.02 * (3.1 * x + 2.3 * z).sin()
    })
    .unwrap()
}

/// Walks `desc` along `path` for `seconds`, returning every step's metrics.
fn walk(
    desc: CharacterDesc,
    path: &WalkPath,
    ground: &dyn Ground,
    seconds: f32,
    controller: bool,
) -> Vec<CharacterMetrics> {
    let mut c = Character::new(desc, path, ground).unwrap();
    c.balance.enabled = controller;
    let steps = (seconds / DT) as usize;
    (0..steps)
        .map(|_| {
            step_character(&mut c, path, ground, DT);
            c.metrics
        })
        .collect()
}

fn straight(length: f32) -> WalkPath {
    WalkPath::straight(Vec3::ZERO, Vec3::Z, length).unwrap()
}

/// Tilts after the first two seconds (the start transient), while walking.
fn settled_tilts(metrics: &[CharacterMetrics]) -> Vec<f32> {
    metrics[120..].iter().map(|m| m.tilt).collect()
}

#[test]
fn tilt_follows_the_slope_only_with_the_controller() {
    let slopes = [-20.0f32, -10.0, 0.0, 10.0, 20.0];
    let path = straight(12.0);
    let mean_tilt = |controller: bool| -> Vec<f32> {
        slopes
            .iter()
            .map(|&deg| {
                let m = walk(CharacterDesc::adult(), &path, &ramp(deg), 7.0, controller);
                mean(settled_tilts(&m))
            })
            .collect()
    };
    let with = mean_tilt(true);
    let without = mean_tilt(false);
    println!(
        "mean tilt (deg) with controller: {:?}",
        with.iter().map(|t| t.to_degrees()).collect::<Vec<_>>()
    );
    println!(
        "mean tilt (deg) without: {:?}",
        without.iter().map(|t| t.to_degrees()).collect::<Vec<_>>()
    );
    assert!(
        with.windows(2).all(|w| w[1] > w[0]),
        "not monotonic: {with:?}"
    );
    assert!(
        with[0] < 0.0 && with[4] > 0.0,
        "downhill back, uphill forward: {with:?}"
    );
    let visible = 5.0f32.to_radians();
    assert!(
        with[0] < -visible && with[4] > visible,
        "the lean at ±20° is not visible (5° or more): {with:?}"
    );
    let spread_with = with[4] - with[0];
    let spread_without = peak_to_peak(&without);
    assert!(
        spread_without < 0.1 * spread_with,
        "without the controller the tilt still follows the slope: {without:?}"
    );
}

#[test]
fn a_higher_com_tilts_and_oscillates_more() {
    let path = straight(12.0);
    let flat = ramp(0.0);
    let pairs = [
        (CharacterDesc::long_legged(), CharacterDesc::short_legged()),
        (CharacterDesc::tall(), CharacterDesc::child()),
    ];
    for (high, low) in pairs {
        let h = settled_tilts(&walk(high, &path, &flat, 7.0, true));
        let l = settled_tilts(&walk(low, &path, &flat, 7.0, true));
        println!(
            "COM high: std {:.3} deg p2p {:.3} deg; low: std {:.3} deg p2p {:.3} deg",
            std_dev(&h).to_degrees(),
            peak_to_peak(&h).to_degrees(),
            std_dev(&l).to_degrees(),
            peak_to_peak(&l).to_degrees()
        );
        assert!(std_dev(&h) > std_dev(&l));
        assert!(peak_to_peak(&h) > peak_to_peak(&l));
    }
}

/// A sole point counts as touching the ground within this height, metres.
const TOUCHING: f32 = 0.005;

/// Largest horizontal drift of a sole point (heel or toe) while it touches the
/// ground during one stance, and the largest gap between a planted sole's
/// lowest point and the ground under it. The foot rolls (heel strike, heel
/// rise), so the part that touches changes; each touching part must stay put.
fn stance_errors(metrics: &[CharacterMetrics], ground: &HeightGrid) -> (f32, f32) {
    let (mut drift, mut gap) = (0.0f32, 0.0f32);
    let height = |p: Vec3| ground.height_at(p.x, p.z).unwrap();
    for k in 0..2 {
        let mut anchors: [Option<Vec3>; 2] = [None; 2];
        for m in metrics {
            if !m.contact[k] {
                anchors = [None; 2];
                continue;
            }
            let lowest = m.feet[k];
            gap = gap.max((lowest.y - height(lowest)).abs());
            for (anchor, p) in anchors.iter_mut().zip([m.soles[k].heel, m.soles[k].toe]) {
                if (p.y - height(p)).abs() > TOUCHING {
                    continue;
                }
                let a = *anchor.get_or_insert(p);
                drift = drift.max(Vec2::new(p.x - a.x, p.z - a.z).length());
            }
        }
    }
    (drift, gap)
}

#[test]
fn stance_feet_neither_slide_nor_float() {
    let path = straight(9.0);
    let mut grounds: Vec<(String, HeightGrid, f32)> = [-20.0f32, -10.0, 0.0, 10.0, 20.0]
        .iter()
        .map(|&d| (format!("slope {d}°"), ramp(d), float_limit(d)))
        .collect();
    grounds.push(("bumpy".into(), bumpy(), STANCE_LIMIT));
    for (name, ground, limit) in &grounds {
        for desc in [CharacterDesc::adult(), CharacterDesc::child()] {
            let m = walk(desc, &path, ground, 10.0, true);
            let (drift, gap) = stance_errors(&m, ground);
            println!(
                "{name} h={}: drift {:.4} m, gap {:.4} m",
                desc.height, drift, gap
            );
            assert!(drift <= STANCE_LIMIT, "{name}: stance drift {drift} m");
            assert!(gap <= *limit, "{name}: sole-ground gap {gap} m");
        }
    }
}

#[test]
fn ten_minutes_of_walking_stay_bounded_for_every_morphology() {
    let ground = bumpy();
    // A looped path: a straight run, a half circle, back, and another half circle.
    let segments = vec![
        PathSegment::Straight { length: 6.0 },
        PathSegment::Arc {
            radius: 2.0,
            angle: std::f32::consts::PI,
        },
        PathSegment::Straight { length: 6.0 },
        PathSegment::Arc {
            radius: 2.0,
            angle: std::f32::consts::PI,
        },
    ];
    let path = WalkPath::new(Vec3::new(2.0, 0.0, -3.0), Vec3::Z, segments, true).unwrap();
    for desc in [
        CharacterDesc::child(),
        CharacterDesc::adult(),
        CharacterDesc::tall(),
        CharacterDesc::long_legged(),
        CharacterDesc::short_legged(),
    ] {
        let m = walk(desc, &path, &ground, 600.0, true);
        let max_tilt = m.iter().map(|m| m.tilt.abs()).fold(0.0, f32::max);
        let finite = m.iter().all(|m| {
            m.com.is_finite() && m.tilt.is_finite() && m.feet.iter().all(|f| f.is_finite())
        });
        let (drift, gap) = stance_errors(&m, &ground);
        println!(
            "h={} legs={}: max tilt {:.2} deg, drift {:.4}, gap {:.4}",
            desc.height,
            desc.leg_length_factor,
            max_tilt.to_degrees(),
            drift,
            gap
        );
        assert!(finite, "NaN in a 10 minute walk");
        assert!(max_tilt < 0.35, "tilt reached {max_tilt} rad");
        // The loop's descents leave landing feet briefly above the ground
        // (see `landing_float_limit`).
        assert!(
            drift <= STANCE_LIMIT && gap <= LOOP_FLOAT_LIMIT,
            "drift {drift} m, gap {gap} m"
        );
        let last = m.last().unwrap();
        assert!(last.com.y > 0.3 * desc.height && last.com.y < desc.height);
    }
}
