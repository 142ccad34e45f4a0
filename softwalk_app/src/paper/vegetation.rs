//! The vegetation claims (paper §3.2, §4): knees rise higher and the body
//! swings less in taller grass, platforms stay below a third of the grass,
//! blades bend only within reach of a foot, and bent grass recovers.

use glam::Vec3;
use softwalk_systems::sim::{Feet, WalkerMetrics};
use softwalk_systems::vegetation::{Bend, GrassPatch};

use super::report::{Check, Claim};
use super::stats::std_dev;
use super::trace::{Trace, trace};
use super::variants::{RIGID, builtin, checked, with_material};
use super::{PaperError, PaperOptions};
use crate::scene::Scene;

/// The walk is measured while the centre of mass is over this X range (inside the grass), metres.
const IN_GRASS_X: (f32, f32) = (3.5, 8.0);
/// The start transient skipped, seconds.
const SETTLE_S: f32 = 1.0;
/// Length of the walk through the grass, seconds.
const WALK_S: f32 = 7.0;
/// Time the grass is left to recover after the walk, seconds.
const RECOVERY_S: f32 = 20.0;

/// A grass scene (`grass-small`, `grass-medium`) on rigid ground, run long
/// enough for the trampled grass to recover; `bare` removes the grass.
pub fn grass_scene(builtin_name: &str, bare: bool) -> Result<Scene, PaperError> {
    let mut scene = with_material(builtin(builtin_name)?, RIGID);
    scene.sim.duration = WALK_S + RECOVERY_S;
    if bare {
        scene.grass.clear();
        scene.sim.duration = WALK_S;
        scene.name = "paper-bare-rigid".into();
        scene.description = "The grass walk without grass, on rigid ground".into();
    } else {
        scene.name = format!("paper-{builtin_name}-rigid");
        scene.description = format!("`{builtin_name}` on rigid ground, then time to recover");
    }
    checked(scene)
}

/// A grass walk, every foot point `p_f` (sole centres) it pushed grass with.
struct GrassWalk {
    scene: Scene,
    trace: Trace,
    foot_points: Vec<Vec3>,
}

impl GrassWalk {
    fn run(name: &str, bare: bool, options: &PaperOptions) -> Result<GrassWalk, PaperError> {
        let scene = grass_scene(name, bare)?;
        options.say(&format!("walking {}", scene.name));
        let mut foot_points = Vec::new();
        let trace = trace(&scene, scene.steps() as usize, |world| {
            for feet in world.query::<&Feet>().iter() {
                foot_points.extend(feet.0.iter().map(|f| f.sole.center()));
            }
        })?;
        Ok(GrassWalk {
            scene,
            trace,
            foot_points,
        })
    }

    /// The walker's steps in the grass (X range) after the start transient.
    fn in_grass(&self) -> Vec<WalkerMetrics> {
        let m = self.trace.walking_from(0, SETTLE_S);
        let inside = |x: f32| x >= IN_GRASS_X.0 && x <= IN_GRASS_X.1;
        m.into_iter()
            .filter(|m| inside(m.character.com.x))
            .collect()
    }

    /// Peak swing clearance over the ground, peak knee flexion, tilt std.
    fn swing(&self) -> (f32, f32, f32) {
        let ground = &self.trace.last;
        let m = self.in_grass();
        let (mut clearance, mut knee) = (0.0f32, 0.0f32);
        for s in &m {
            for k in 0..2 {
                let foot = s.character.feet[k];
                if !s.character.contact[k] {
                    let floor = ground.height_at(foot.x, foot.z).unwrap_or(foot.y);
                    clearance = clearance.max(foot.y - floor);
                }
                knee = knee.max(s.character.knee_flexion[k]);
            }
        }
        let tilts: Vec<f32> = m.iter().map(|s| s.character.tilt).collect();
        (clearance, knee, std_dev(&tilts))
    }

    /// Highest platform top over the ground under its foot, metres.
    fn max_platform(&self) -> f32 {
        let ground = &self.trace.last;
        self.trace.walkers[0]
            .iter()
            .flat_map(|s| (0..2).filter_map(move |k| Some((s.platform_y[k]?, s.character.feet[k]))))
            .map(|(top, foot)| top - ground.height_at(foot.x, foot.z).unwrap_or(top))
            .fold(0.0, f32::max)
    }

    fn patch<T>(&self, read: impl FnOnce(&GrassPatch) -> T) -> T {
        let mut q = self.trace.app.world.query::<&GrassPatch>();
        read(q.iter().next().expect("a grass scene has a patch"))
    }
}

/// Distance from `foot` to blade `i`'s upright segment.
fn segment_distance(patch: &GrassPatch, i: usize, foot: Vec3) -> f32 {
    let b = patch.blades()[i];
    let y = foot.y.clamp(b.root.y, b.root.y + b.height);
    Vec3::new(b.root.x, y, b.root.z).distance(foot)
}

/// Swing, platform, field locality and recovery from three walks.
pub fn vegetation_claims(options: &PaperOptions) -> Result<Vec<Claim>, PaperError> {
    let bare = GrassWalk::run("grass-small", true, options)?;
    let small = GrassWalk::run("grass-small", false, options)?;
    let medium = GrassWalk::run("grass-medium", false, options)?;
    Ok(vec![
        swing_claim(&bare, &small, &medium),
        platform_claim(&[&small, &medium]),
        field_claim(&[&small, &medium]),
        recovery_claim(&[&small, &medium]),
    ])
}

fn swing_claim(bare: &GrassWalk, small: &GrassWalk, medium: &GrassWalk) -> Claim {
    let [b, s, m] = [bare.swing(), small.swing(), medium.swing()];
    Claim {
        title: "Knees rise higher in taller grass; the body swings less".into(),
        statement:
            "Virtual platforms lift the swing foot over the vegetation (higher knees), and beta \
                    falls from 6 (bare) to 4 (0.9 m grass) so the body swings less."
                .into(),
        method: format!(
            "`paper-bare-rigid`, `paper-grass-small-rigid`, `paper-grass-medium-rigid` (rigid ground); \
             peaks while the COM is at x in {IN_GRASS_X:?} m after {SETTLE_S} s."
        ),
        checks: vec![
            Check::new(
                "peak swing clearance bare / 0.5 m / 0.9 m",
                format!("{:.3} / {:.3} / {:.3} m", b.0, s.0, m.0),
                "increasing",
                s.0 > b.0 && m.0 > s.0,
            ),
            Check::new(
                "peak knee flexion bare / 0.5 m / 0.9 m",
                format!(
                    "{:.1}° / {:.1}° / {:.1}°",
                    b.1.to_degrees(),
                    s.1.to_degrees(),
                    m.1.to_degrees()
                ),
                "increasing",
                s.1 > b.1 && m.1 > s.1,
            ),
            Check::new(
                "tilt std bare vs 0.9 m",
                format!("{:.3}° vs {:.3}°", b.2.to_degrees(), m.2.to_degrees()),
                "0.9 m smaller",
                m.2 < b.2,
            ),
        ],
    }
}

fn platform_claim(walks: &[&GrassWalk]) -> Claim {
    let checks = walks
        .iter()
        .map(|w| {
            let spec = &w.scene.grass[0];
            let limit = spec.platform_height();
            let top = w.max_platform();
            Check::new(
                format!("{}: highest platform", w.scene.name),
                format!("{top:.3} m (grass {:.2} m)", spec.settings().height),
                format!("in (0, {limit:.3}] m = height / 3"),
                top > 0.0 && top <= limit + 1e-4,
            )
        })
        .collect();
    Claim {
        title: "Platform height at most a third of the vegetation".into(),
        statement: "A virtual platform rises under the swinging foot, up to vegetation height / 3."
            .into(),
        method: "The two grass walks; platform top minus the ground under the foot, every step."
            .into(),
        checks,
    }
}

fn field_claim(walks: &[&GrassWalk]) -> Claim {
    let checks = walks
        .iter()
        .map(|w| {
            let (touched, beyond, radius) = w.patch(|p| {
                let radius = p.t_max() / p.gamma();
                let touched: Vec<usize> = (0..p.blade_count())
                    .filter(|&i| p.state(i).treads > 0)
                    .collect();
                let beyond = touched
                    .iter()
                    .filter(|&&i| {
                        w.foot_points
                            .iter()
                            .all(|&f| segment_distance(p, i, f) >= radius)
                    })
                    .count();
                (touched.len(), beyond, radius)
            });
            Check::new(
                format!("{}: blades pushed / pushed beyond reach", w.scene.name),
                format!("{touched} / {beyond} (reach t_max/γ = {radius:.3} m)"),
                "some pushed, none beyond reach",
                touched > 0 && beyond == 0,
            )
        })
        .collect();
    Claim {
        title: "Blades bend only within reach of a foot".into(),
        statement: "Eq. 2: t(p) = clamp(t_max − γ|p − p_f|) (p − p_f)_down / |p − p_f|: blades near a foot \
                    are pushed down and away; beyond t_max/γ nothing moves."
            .into(),
        method: "The two grass walks; every sole centre of every step kept; a blade counts as pushed once trodden.".into(),
        checks,
    }
}

fn recovery_claim(walks: &[&GrassWalk]) -> Claim {
    let checks = walks
        .iter()
        .map(|w| {
            let last_feet: Vec<Vec3> = w.foot_points.iter().rev().take(2).copied().collect();
            let (recovered, still_bent, broken, kept) = w.patch(|p| {
                let radius = p.t_max() / p.gamma();
                let away = |i: usize| last_feet.iter().all(|&f| segment_distance(p, i, f) >= radius);
                let trodden = (0..p.blade_count()).filter(|&i| p.state(i).treads > 0 && away(i));
                let (mut recovered, mut still_bent, mut broken, mut kept) = (0, 0, 0, 0);
                for i in trodden {
                    let s = p.state(i);
                    if s.broken {
                        broken += 1;
                        kept += usize::from(p.bend(i) == s.rest && s.rest != Bend::ZERO);
                    } else if p.bend(i) == Bend::ZERO {
                        recovered += 1;
                    } else {
                        still_bent += 1;
                    }
                }
                (recovered, still_bent, broken, kept)
            });
            let m = &w.trace.walkers[0];
            let walked = m.iter().rposition(|s| s.velocity.length() > 0.05).unwrap_or(0);
            let wait = (m.len() - walked) as f32 * w.trace.dt;
            Check::new(
                format!("{}: {wait:.1} s after the walk", w.scene.name),
                format!(
                    "elastic: {recovered} upright, {still_bent} still bent; broken: {kept} of {broken} keep their bend"
                ),
                "all elastic upright, all broken stay down",
                recovered > 0 && still_bent == 0 && kept == broken,
            )
        })
        .collect();
    Claim {
        title: "Trampled grass recovers; broken blades leave a trail".into(),
        statement:
            "Blades keep their state: elastic ones spring back over time, trodden-down ones stay."
                .into(),
        method: format!(
            "The two grass walks continue {RECOVERY_S} s after the walker stops \
             (blades within reach of its standing feet are left out)."
        ),
        checks,
    }
}
