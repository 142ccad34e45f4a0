//! The skinned sole on the ground: a scene walked with its first character's
//! rig skinned every step, the sole's gap to the driver's sole plane and its
//! slide during stance measured from the skinned mesh's foot vertices, with
//! the walk's gait quality.

use engine::anim::{SkinnedVertices, skin};
use engine::ecs::Entity;
use engine::schedule::App;
use glam::{Affine3A, Mat4, Vec3};
use softwalk_app::paper::gait_quality::GaitQuality;
use softwalk_app::scene::Scene;
use softwalk_systems::character::{CharacterBody, CharacterRig, Pose, RigPose};
use softwalk_systems::foot::FootPhase;
use softwalk_systems::sim::{Feet, WalkerMetrics, run_steps};

/// Most accepted gap between the skinned sole and the ground during stance, metres.
pub const SOLE_GAP_GOAL_M: f32 = 0.01;
/// Most accepted slide of a touching skinned sole vertex over one stance,
/// metres (the driver's own sole is held to the same figure).
pub const SOLE_SLIDE_GOAL_M: f32 = 0.01;
/// A sole vertex this close above the sole's lowest vertex touches the ground, metres.
const TOUCH_M: f32 = 0.01;

/// The skinned mesh of a rig as the world poses its character now.
pub struct Skinner {
    rig: CharacterRig,
    globals: Vec<Mat4>,
    matrices: Vec<Affine3A>,
    /// The skinned vertices of the last [`Skinner::pose`].
    pub out: SkinnedVertices,
}

impl Skinner {
    /// A skinner of `rig`.
    pub fn new(rig: CharacterRig) -> Skinner {
        Skinner {
            rig,
            globals: Vec::new(),
            matrices: Vec::new(),
            out: SkinnedVertices::default(),
        }
    }

    /// Poses the rig after `entity`'s driver and skins it into `out`.
    pub fn pose(&mut self, app: &App, entity: Entity) -> RigPose {
        let body = app.world.get::<CharacterBody>(entity).unwrap();
        let pose = app.world.get::<Pose>(entity).unwrap();
        let feet = app.world.get::<Feet>(entity).unwrap();
        let rig_pose = RigPose::drive(&self.rig, &body, &pose, &feet.0);
        rig_pose.skin_matrices(&self.rig, &mut self.globals, &mut self.matrices);
        skin(&self.rig.model().mesh, &self.matrices, &mut self.out).unwrap();
        rig_pose
    }
}

/// Worst sole gap and slide over a stance in one walk.
#[derive(Debug, Default)]
pub struct SoleFigures {
    /// Largest distance of the skinned sole's lowest vertex from the driver's sole plane.
    pub gap: f32,
    /// Largest slide of a touching skinned sole vertex over one stance (see [`StanceSlide`]).
    pub slide: f32,
    /// The same slide of the driver's own sole (heel, centre, toe).
    pub driver_slide: f32,
    /// Steps measured in stance.
    pub stance_steps: usize,
}

impl SoleFigures {
    /// Whether the gap and both slides are within their goals.
    pub fn met(&self) -> bool {
        self.gap <= SOLE_GAP_GOAL_M
            && self.slide <= SOLE_SLIDE_GOAL_M
            && self.driver_slide <= SOLE_SLIDE_GOAL_M
    }
}

/// Slide of one stance so far: how far any point of the sole has moved
/// horizontally, while it touches the ground (within a touch distance,
/// [`TOUCH_M`] by default, above the floor), from where it first touched it
/// in this stance. A foot that rolls from heel to toe touches with other
/// points in turn and does not slide; a point that touches and moves does.
pub struct StanceSlide {
    touch: f32,
    first_touch: Vec<Option<Vec3>>,
    worst: f32,
}

impl Default for StanceSlide {
    fn default() -> Self {
        StanceSlide::new(TOUCH_M)
    }
}

impl StanceSlide {
    /// A stance whose points touch within `touch` metres of the floor.
    pub fn new(touch: f32) -> Self {
        StanceSlide {
            touch,
            first_touch: Vec::new(),
            worst: 0.0,
        }
    }

    /// Adds this step's sole points, the floor at the lowest of them;
    /// returns the worst slide so far.
    pub fn add(&mut self, points: &[Vec3]) -> f32 {
        let floor = points.iter().map(|p| p.y).fold(f32::INFINITY, f32::min);
        self.add_over(points, floor)
    }

    /// Adds this step's sole points over a floor at height `floor`; returns
    /// the worst slide so far.
    pub fn add_over(&mut self, points: &[Vec3], floor: f32) -> f32 {
        self.first_touch.resize(points.len(), None);
        for (first, p) in self.first_touch.iter_mut().zip(points) {
            if p.y < floor + self.touch {
                let at = *first.get_or_insert(*p);
                self.worst = self
                    .worst
                    .max(((*p - at) * Vec3::new(1.0, 0.0, 1.0)).length());
            }
        }
        self.worst
    }
}

/// A walk's sole figures and gait quality.
pub struct SoleWalk {
    /// The skinned sole's gap and slide.
    pub soles: SoleFigures,
    /// The gait goals, measured on the driver.
    pub quality: GaitQuality,
}

/// Walks `scene`'s first character alone for `seconds`, skinning its rig
/// every step, and measures its soles and its gait.
pub fn walk_soles(scene: &Scene, seconds: f64) -> SoleWalk {
    let mut scene = scene.clone();
    scene.characters.truncate(1);
    let (mut app, walkers) = scene.build_sim().unwrap();
    let entity = walkers[0];
    let rig = app.world.get::<CharacterRig>(entity).unwrap().clone();
    let mut skinner = Skinner::new(rig.clone());
    let mut figures = SoleFigures::default();
    let mut slides: [[StanceSlide; 2]; 2] = Default::default();
    let mut series = Vec::new();
    for _ in 0..scene.sim.steps_for(seconds) {
        run_steps(&mut app, 1).unwrap();
        series.push(*app.world.get::<WalkerMetrics>(entity).unwrap());
        skinner.pose(&app, entity);
        let feet = app.world.get::<Feet>(entity).unwrap().0;
        let right = app.world.get::<Pose>(entity).unwrap().right;
        for (k, foot) in feet.iter().enumerate() {
            if !(foot.contact && foot.phase == FootPhase::Stance) {
                slides[k] = Default::default();
                continue;
            }
            figures.stance_steps += 1;
            let sole: Vec<Vec3> = (rig.sole_vertices()[k].iter())
                .map(|&v| skinner.out.positions[v as usize])
                .collect();
            let along = (foot.sole.toe - foot.sole.heel).normalize();
            let normal = right.cross(along).normalize();
            let above = |p: &Vec3| (*p - foot.sole.heel).dot(normal);
            let lowest = sole.iter().map(above).fold(f32::INFINITY, f32::min);
            figures.gap = figures.gap.max(lowest.abs());
            figures.slide = figures.slide.max(slides[k][0].add(&sole));
            let driver = [foot.sole.heel, foot.sole.center(), foot.sole.toe];
            figures.driver_slide = figures.driver_slide.max(slides[k][1].add(&driver));
        }
    }
    SoleWalk {
        soles: figures,
        quality: GaitQuality::measure(&series, scene.sim.dt),
    }
}
