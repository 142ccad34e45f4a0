//! Where each foot stands: the floor under a planted foot is locked when it
//! lands (the surface lowered by the print the material predicts), and a
//! swinging foot travels from the print it left to the floor of the print it
//! will make, pushing into the ground at the end of the swing.
//!
//! This keeps the foot IK, the rays and carving from feeding each other: a
//! planted foot does not re-read the cells it is carving (which would lower
//! the foot, which would carve deeper, every step), and a swinging foot does
//! not snap to every print wall and rim it passes over. The foot pushes into
//! the ground over the ground's own [`SINK_TIME_S`], so it goes down as fast
//! as carving presses the ground, never through it.
//!
//! Where the leg falls behind its swing (a knee at its top speed), the
//! support reads the ground where the leg really has the foot
//! ([`FootSupport::reached`]): a foot still low in a deep print waits before
//! firmer ground ahead ([`FootSupport::trail`]), and a foot short of a
//! softer landing pushes no lower than the firmer floor under it.

use std::f32::consts::PI;

use glam::{Vec2, Vec3};

use super::body::CharacterBody;
use super::gait::{FootPlan, GaitParams, smoothstep};
use super::ground_cross::{GroundCross, SOLE_RAYS};
use crate::foot::FootPhase;
use crate::ground::{Ground, GroundHit, rise_along};
use crate::terrain::SINK_TIME_S;

/// Least height of a swinging foot over the higher of the print's rim it
/// leaves and the ground it lands on, metres.
pub const RIM_CLEARANCE: f32 = 0.02;
/// Fraction of the swing over which a foot rises out of a print (and, at
/// the end, comes down into a lower landing).
const STEP_OUT_TIME: f32 = 0.3;
/// Give of a landing (metres) from which a foot pushes into it for the
/// ground's whole [`SINK_TIME_S`]; a landing that gives less takes less.
pub const FULL_PUSH_GIVE: f32 = 0.02;
/// How far (metres) the sole a leg really reached may be below the floor
/// of the ground its swing moves it over before the swing waits for it
/// (see [`FootSupport::trail`]).
const WAIT_BELOW_FLOOR: f32 = 0.01;

/// A ground point under a sole centre, with its normal and how far it gives.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SupportPoint {
    /// The surface point (world).
    pub point: Vec3,
    /// Unit surface normal.
    pub normal: Vec3,
    /// How far a planted foot presses the surface here, metres.
    pub give: f32,
}

impl SupportPoint {
    /// A point of flat rigid ground at `point`.
    pub fn rigid(point: Vec3) -> Self {
        SupportPoint {
            point,
            normal: Vec3::Y,
            give: 0.0,
        }
    }

    /// What a ray found.
    pub fn from_hit(hit: GroundHit) -> Self {
        SupportPoint {
            point: hit.point,
            normal: hit.normal,
            give: hit.give.max(0.0),
        }
    }

    /// The floor a planted foot stands on: the surface lowered by the give.
    pub fn floor(&self) -> Vec3 {
        self.point - Vec3::Y * self.give
    }

    /// Moves to `at` (x, z) with what a ray found there; a miss keeps the
    /// last height, normal and give. Returns whether the ray hit.
    fn update(&mut self, at: Vec2, found: Option<GroundHit>) -> bool {
        match found {
            Some(hit) => {
                *self = Self::from_hit(hit);
                true
            }
            None => {
                (self.point.x, self.point.z) = (at.x, at.y);
                false
            }
        }
    }
}

/// One foot's support: locked while planted, interpolated while swinging.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FootSupport {
    /// The ground at the foothold, aimed during the swing and locked once
    /// the foot starts pressing it or ploughs towards it (see
    /// [`Self::landing_held`]).
    pub landing: SupportPoint,
    /// The floor the foot left at lift-off, and its normal.
    pub left: SupportPoint,
    /// The surface the foot left, before it was pressed: the top of its print.
    pub left_rim: f32,
    /// True while the foot is planted.
    pub planted: bool,
    /// False when the last ray for this foot found nothing.
    pub hit: bool,
    /// True once the swinging foot has ploughed towards its landing (set by
    /// the foot IK): the landing is no longer re-aimed, so the ground the
    /// foot pressed on its way is not read back as a shallower landing, and
    /// the knee is bound to straighten in time for it.
    pub landing_held: bool,
    /// True once the foot has lifted off: its landing is one it stepped
    /// onto, not the foothold the walker started standing on.
    pub stepped: bool,
    /// The sole centre the leg really reached last step (world; set by the
    /// foot IK, `None` before it has placed the foot).
    pub reached: Option<Vec3>,
    /// How far (x, z) the swinging foot's key trails its swing's target,
    /// metres. In the rising half of the swing, a foot its leg leaves below
    /// the floor of the ground the swing would move it over waits where it
    /// is: a leg that cannot lift the foot out of a deep print in time does
    /// not push it into the firmer ground ahead (a sand edge after snow).
    /// The trail closes evenly by the time the foot pushes into its landing.
    trail: Vec2,
    /// Swing progress at the last step, for closing [`Self::trail`].
    last_swing: f32,
    /// Where (x, z) the swinging foot's key was last step.
    key_at: Vec2,
}

impl FootSupport {
    /// A foot planted on `point`.
    pub fn planted_on(point: SupportPoint) -> Self {
        FootSupport {
            landing: point,
            left: point,
            left_rim: point.point.y,
            planted: true,
            hit: true,
            landing_held: false,
            stepped: false,
            reached: None,
            trail: Vec2::ZERO,
            last_swing: 0.0,
            key_at: Vec2::new(point.point.x, point.point.z),
        }
    }

    /// Advances the support for `plan` under `params` (the swing lift, the
    /// swing's duration) for a foot of `body`, casting rays from `from_y`.
    pub fn advance(
        &mut self,
        plan: &FootPlan,
        params: &GaitParams,
        body: &CharacterBody,
        ground: &dyn Ground,
        from_y: f32,
    ) -> SupportKey {
        let cast = |at: Vec2| ground.cast_down(at.x, at.y, from_y);
        if plan.phase == FootPhase::Stance {
            // The landing was aimed (and locked) during the swing.
            self.planted = true;
            self.landing_held = false;
            let floor = self.landing.floor();
            return SupportKey::pressing(floor, self.landing.normal);
        }
        if self.planted {
            self.left = SupportPoint {
                point: self.landing.floor(),
                ..self.landing
            };
            self.left_rim = self.landing.point.y;
            self.planted = false;
            self.stepped = true;
            self.restart_trail(plan.target);
        }
        let swing_time = params.swing_time();
        let u = plan.swing.clamp(0.0, 1.0);
        let pushing_from = 1.0 - self.push_time() / swing_time.max(f32::EPSILON);
        // The landing is aimed until the foot starts pushing into it, or
        // ploughs towards it; from then on it is carved, and must not be
        // read back.
        if u <= pushing_from && !self.landing_held {
            self.aim(plan, body, &cast);
        }
        let normal = self
            .left
            .normal
            .lerp(self.landing.normal, smoothstep(u))
            .try_normalize()
            .unwrap_or(Vec3::Y);
        let (plan, onward_clear) = self.follow(plan, body, &cast, normal, pushing_from);
        let plan = &plan;
        let at = |y: f32| Vec3::new(plan.target.x, y - plan.lift, plan.target.y);
        if u > pushing_from {
            // The sole goes into its landing no lower than the floor under
            // it where the leg really has it: a foot still over firmer
            // ground short of a softer landing stops on that ground.
            let stop = self
                .landing
                .floor()
                .y
                .max(self.floor_under_reached(plan, body, &cast, normal));
            let pushed = (u - pushing_from) / (1.0 - pushing_from);
            let sole = (self.landing.point.y - self.landing.give * pushed).max(stop);
            return SupportKey {
                centre: at(sole),
                normal,
                pressing: true,
                floor: stop.min(sole),
                surface: (sole - plan.lift).max(stop),
            };
        }
        let height = self.swing_height(u / pushing_from.max(f32::EPSILON), params.clearance);
        // Ground rising above the path between the two footholds, under any
        // part of the sole, lifts the foot.
        let clear = onward_clear.unwrap_or_else(|| lowest_clear_centre(&cast, plan, body, normal));
        let height = clear.map_or(height, |c| height.max(c.surface));
        // A foot ploughing towards its landing goes no lower than the floors
        // it will pass over on its way: it ploughs through loose ground, but
        // is not pushed into a rigid edge ahead.
        let floor = clear.map_or(f32::MIN, |c| c.floor);
        let floor = if self.landing_held {
            floor.max(highest_floor_ahead(&cast, plan, body, normal))
        } else {
            floor
        };
        // Until the sole is out of its print, the print stays held: its walls
        // do not slump onto the rising foot.
        let in_print = self.left.give > 0.0 && u < 0.5 && height < self.left_rim;
        SupportKey {
            centre: at(height),
            normal,
            pressing: in_print,
            floor: floor.min(height),
            surface: clear.map_or(f32::MIN, |c| c.surface.min(height)),
        }
    }

    /// `plan` with its target moved back by the swing's trail, after
    /// updating the trail (see [`Self::trail`]): it closes evenly until
    /// `pushing_from`, unless, in the rising half of the swing, the sole
    /// centre the leg reached last step is more than [`WAIT_BELOW_FLOOR`]
    /// below the floor under the sole (lying in the plane of `normal`) where
    /// the closed trail would put it; then the key stays where it was.
    /// Also returns, when it was read and the key goes on, the clear centre
    /// at the key (see [`lowest_clear_centre`]), so it is not read twice.
    fn follow(
        &mut self,
        plan: &FootPlan,
        body: &CharacterBody,
        cast: &dyn Fn(Vec2) -> Option<GroundHit>,
        normal: Vec3,
        pushing_from: f32,
    ) -> (FootPlan, Option<Option<ClearCentre>>) {
        let u = plan.swing.clamp(0.0, 1.0);
        let left = pushing_from - self.last_swing;
        let keep = if left > 0.0 {
            ((pushing_from - u) / left).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let at = |target: Vec2| FootPlan { target, ..*plan };
        let onward = plan.target - self.trail * keep;
        let clear = (u < 0.5 && u < pushing_from && self.reached.is_some())
            .then(|| lowest_clear_centre(cast, &at(onward), body, normal));
        let floor = clear.flatten().map_or(f32::MIN, |c| c.floor);
        let waits = clear.is_some() && self.reached.is_some_and(|r| r.y < floor - WAIT_BELOW_FLOOR);
        let key = if waits { self.key_at } else { onward };
        self.trail = plan.target - key;
        self.key_at = key;
        self.last_swing = u;
        (at(key), clear.filter(|_| !waits))
    }

    /// The floor under a flat sole (lying in the plane of `normal`, facing
    /// `plan`'s heading) centred where the leg really had the sole last step:
    /// the lowest height of its centre over the floors under five points
    /// from heel to toe (see [`lowest_clear_centre`]); `f32::MIN` when that
    /// is unknown or no ray hits.
    fn floor_under_reached(
        &self,
        plan: &FootPlan,
        body: &CharacterBody,
        cast: &dyn Fn(Vec2) -> Option<GroundHit>,
        normal: Vec3,
    ) -> f32 {
        self.reached.map_or(f32::MIN, |r| {
            let there = FootPlan {
                target: Vec2::new(r.x, r.z),
                ..*plan
            };
            lowest_clear_centre(cast, &there, body, normal).map_or(f32::MIN, |c| c.floor)
        })
    }

    /// Aims the landing at `plan`'s foothold: the surface under the sole
    /// centre, with the slope and give read over the patch the sole will
    /// cover (a single ray reads a print's wall, or the softer of two
    /// grounds where the sole spans both).
    fn aim(
        &mut self,
        plan: &FootPlan,
        body: &CharacterBody,
        cast: &dyn Fn(Vec2) -> Option<GroundHit>,
    ) {
        let (along, across) = (0.5 * body.foot_length, 0.5 * body.foot_width);
        let heading = plan.foothold_heading;
        let patch = GroundCross::sample(cast, plan.foothold, heading, [along, across], SOLE_RAYS);
        self.hit = self
            .landing
            .update(plan.foothold, patch.and_then(|p| p.centre));
        if let Some(patch) = patch {
            // The sole meets the highest ground under it and stops on the
            // highest floor: half over an old print it lands on the print's
            // edge and presses it, not through it.
            self.landing.normal = patch.normal;
            self.landing.point.y = patch.rest_top;
            self.landing.give = patch.rest_top - patch.rest_floor;
        }
    }

    /// Starts a new swing's trail from a key at `at` (x, z), closed.
    fn restart_trail(&mut self, at: Vec2) {
        self.trail = Vec2::ZERO;
        self.last_swing = 0.0;
        self.key_at = at;
    }

    /// Time the foot takes to push into its landing, seconds: as long as
    /// the ground takes to give ([`SINK_TIME_S`]), shorter for a landing
    /// that gives less than [`FULL_PUSH_GIVE`], none on rigid ground.
    fn push_time(&self) -> f32 {
        SINK_TIME_S * (self.landing.give / FULL_PUSH_GIVE).min(1.0)
    }

    /// Height of the sole's lowest point over the swing to the landing
    /// surface, at progress `u` of that part, for a lift of `clearance`:
    /// from the floor it left to the surface it lands on. Out of a print, or
    /// into one, the foot rises early and clears the higher of the print's
    /// rim and the landing surface by at least [`RIM_CLEARANCE`] (the way a
    /// leg steps out of deep snow: with the hip, not by dragging the foot).
    /// A landing below the rim (down a slope) lowers the rim to clear as the
    /// foot travels towards it, so the foot goes down with the ground rather
    /// than being held at the height it left and dropped at the end, faster
    /// than a knee straightens.
    fn swing_height(&self, u: f32, clearance: f32) -> f32 {
        let u = u.clamp(0.0, 1.0);
        let (from, to) = (self.left.point.y, self.landing.point.y);
        let eased = smoothstep(u);
        // A landing below the print's rim is cleared from above as the foot
        // goes down to it; a landing above it, all the way.
        let rim = (self.left_rim + (to - self.left_rim).min(0.0) * eased).max(to);
        let base = from + (to - from) * eased;
        let apex = (from.min(to) + clearance).max(rim + RIM_CLEARANCE);
        let top = apex - clearance;
        let held = smoothstep(u.min(1.0 - u) / STEP_OUT_TIME);
        base + (top - base).max(0.0) * held + clearance * (PI * u).sin()
    }
}

/// What one foot's support gives its ground key this step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SupportKey {
    /// The ground point under the sole centre that the swing's lift is
    /// measured from.
    pub centre: Vec3,
    /// Its unit normal.
    pub normal: Vec3,
    /// Whether the foot presses the ground: planted, pushing in at the end
    /// of its swing, or still rising out of its print.
    pub pressing: bool,
    /// The lowest the sole's lowest point may go, metres: the floor of the
    /// ground under it (its surface less what it gives), never above where
    /// the key puts the sole; `f32::MIN` where no ray found ground.
    pub floor: f32,
    /// The highest surface under five points from the sole's heel to its toe, metres
    /// (for a foot pushing into its landing, how far it has pushed less the
    /// lift its swing still has, never below the landing's floor; the floor
    /// of a planted foot; `f32::MIN` where no ray found ground): a foot goes
    /// below it only as fast as the ground gives.
    pub surface: f32,
}

impl SupportKey {
    /// A foot pressing the ground at `centre`, on its floor.
    fn pressing(centre: Vec3, normal: Vec3) -> Self {
        SupportKey {
            centre,
            normal,
            pressing: true,
            floor: centre.y,
            surface: centre.y,
        }
    }
}

/// Heights of the centre of a flat sole at which five points from its heel to its toe
/// are all on or above the ground under them.
#[derive(Debug, Clone, Copy, PartialEq)]
struct ClearCentre {
    /// Above the surface.
    surface: f32,
    /// Above the floor: the surface less what the ground gives there.
    floor: f32,
}

/// The lowest heights of the centre of a flat sole at `plan`'s target,
/// facing its heading and lying in the plane of `normal`, at which five
/// points from its heel to its toe (the ends, the centre and half-way) are
/// all on or above the surface, and the floor, under them (a rim a quarter of a sole
/// wide or wider is always seen); `None` when every ray misses. A sole centred over an old
/// print can still have its heel or toe over the fresh ground beside it.
fn lowest_clear_centre(
    cast: &dyn Fn(Vec2) -> Option<GroundHit>,
    plan: &FootPlan,
    body: &CharacterBody,
    normal: Vec3,
) -> Option<ClearCentre> {
    let half = plan.heading * (0.5 * body.foot_length);
    [-1.0, -0.5, 0.0, 0.5, 1.0]
        .into_iter()
        .map(|f| half * f)
        .filter_map(|offset| {
            cast(plan.target + offset).map(|hit| {
                let surface = hit.point.y - rise_along(normal, offset);
                ClearCentre {
                    surface,
                    floor: surface - hit.give.max(0.0),
                }
            })
        })
        .reduce(|a, b| ClearCentre {
            surface: a.surface.max(b.surface),
            floor: a.floor.max(b.floor),
        })
}

/// The most rays [`highest_floor_ahead`] casts.
const MOST_RAYS_AHEAD: usize = 8;

/// The highest floor (surface less give) under the toe of a flat sole
/// lying in the plane of `normal` as it travels from `plan`'s target to its
/// foothold, as a height of the sole's centre at the target, metres;
/// `f32::MIN` where every ray misses. The toe is read at most half a foot
/// apart (up to [`MOST_RAYS_AHEAD`] rays), so no edge a sole could catch
/// on falls between two rays.
fn highest_floor_ahead(
    cast: &dyn Fn(Vec2) -> Option<GroundHit>,
    plan: &FootPlan,
    body: &CharacterBody,
    normal: Vec3,
) -> f32 {
    let toe = plan.heading * (0.5 * body.foot_length);
    let way = plan.foothold - plan.target;
    let spacing = (0.5 * body.foot_length).max(1e-3);
    let rays = ((way.length() / spacing).ceil() as usize).clamp(1, MOST_RAYS_AHEAD);
    (1..=rays)
        .filter_map(|i| {
            let offset = way * (i as f32 / rays as f32) + toe;
            let hit = cast(plan.target + offset)?;
            Some(hit.point.y - hit.give.max(0.0) - rise_along(normal, offset))
        })
        .fold(f32::MIN, f32::max)
}

/// Unit heel-to-toe direction of a sole facing `heading` (x, z) on ground of
/// unit `normal`: the heading projected into the ground's tangent plane.
pub(crate) fn sole_direction(heading: Vec2, normal: Vec3) -> Vec3 {
    let heading = Vec3::new(heading.x, 0.0, heading.y);
    (heading - normal * heading.dot(normal))
        .try_normalize()
        .unwrap_or(heading)
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;

    fn support(left_floor: f32, left_rim: f32, landing: f32) -> FootSupport {
        let mut s = FootSupport::planted_on(SupportPoint::rigid(Vec3::Y * landing));
        s.left = SupportPoint::rigid(Vec3::Y * left_floor);
        s.left_rim = left_rim;
        s
    }

    #[test]
    fn a_lower_landing_is_approached_going_down_not_held_at_the_start() {
        // Down a rigid slope: left at 0.2 m, landing at 0 m, clearance 7 cm.
        let s = support(0.2, 0.2, 0.0);
        let c = 0.07;
        let heights: Vec<f32> = (0..=20)
            .map(|i| s.swing_height(i as f32 / 20.0, c))
            .collect();
        // Never above the start plus the lift, and no steep drop at the end:
        // the last fifth of the swing goes down no more than the first fifth
        // of the way up plus the slope's share.
        assert!(heights.iter().all(|&h| h <= 0.2 + c + 1e-6), "{heights:?}");
        let end_drop = heights[16] - heights[20];
        assert!(
            end_drop < 0.12,
            "drops {end_drop} m in the last fifth: {heights:?}"
        );
        assert!((heights[20] - 0.0).abs() < 1e-6);
    }

    /// A swinging plan at `target` (x, z) facing +X.
    pub(in crate::character) fn swinging_at(target: Vec2) -> FootPlan {
        FootPlan {
            side: crate::foot::Side::Left,
            phase: FootPhase::SwingDown,
            from: target,
            foothold: target,
            swing: 0.6,
            target,
            lift: 0.0,
            pitch: 0.0,
            from_heading: Vec2::X,
            foothold_heading: Vec2::X,
            heading: Vec2::X,
            contact_along: 0.0,
            contact: target,
        }
    }

    fn hit_at(p: Vec2, y: f32) -> Option<GroundHit> {
        Some(GroundHit {
            point: Vec3::new(p.x, y, p.y),
            normal: Vec3::Y,
            give: 0.0,
        })
    }

    #[test]
    fn a_sole_over_an_old_print_clears_the_ground_under_its_heel() {
        let body = CharacterBody::new(crate::character::CharacterDesc::adult()).unwrap();
        let plan = swinging_at(Vec2::ZERO);
        // An old print 0.3 m deep under the centre and the toe; fresh
        // snow at 0 behind x = -0.1, under the heel.
        let print = |p: Vec2| hit_at(p, if p.x > -0.1 { -0.3 } else { 0.0 });
        let centre = lowest_clear_centre(&print, &plan, &body, Vec3::Y)
            .unwrap()
            .surface;
        assert!(
            centre.abs() < 1e-6,
            "the flat sole clears the heel's snow: {centre}"
        );
        // On a plane the sole lies along the slope: its centre is on the
        // surface under it, not raised to the surface under the heel.
        let slope = 20f32.to_radians().tan();
        let normal = Vec3::new(slope, 1.0, 0.0).normalize();
        let plane = |p: Vec2| hit_at(p, -slope * p.x);
        let centre = lowest_clear_centre(&plane, &plan, &body, normal)
            .unwrap()
            .surface;
        assert!(centre.abs() < 1e-5, "down 20°: {centre}");
        assert!(lowest_clear_centre(&|_| None, &plan, &body, Vec3::Y).is_none());
    }

    #[test]
    fn a_rim_between_the_heel_and_the_centre_lifts_the_swinging_sole() {
        let body = CharacterBody::new(crate::character::CharacterDesc::adult()).unwrap();
        let plan = swinging_at(Vec2::ZERO);
        // A neighbour's rim 3 cm high and 4 cm wide, a quarter of a sole
        // behind the centre; level ground at 0 elsewhere.
        let quarter = 0.25 * body.foot_length;
        let rim = |p: Vec2| {
            hit_at(
                p,
                if (p.x + quarter).abs() < 0.02 {
                    0.03
                } else {
                    0.0
                },
            )
        };
        let centre = lowest_clear_centre(&rim, &plan, &body, Vec3::Y)
            .unwrap()
            .surface;
        assert!(
            (centre - 0.03).abs() < 1e-6,
            "the sole rests on the rim: {centre}"
        );
    }

    /// Level loose ground: its surface at `top`, giving `give` under a foot.
    struct Loose {
        top: f32,
        give: f32,
    }

    impl Ground for Loose {
        fn cast_down(&self, x: f32, z: f32, _from_y: f32) -> Option<GroundHit> {
            Some(GroundHit {
                point: Vec3::new(x, self.top, z),
                normal: Vec3::Y,
                give: self.give,
            })
        }
    }

    #[test]
    fn a_held_landing_is_not_re_aimed_and_a_swinging_sole_reads_its_floor() {
        let body = CharacterBody::new(crate::character::CharacterDesc::adult()).unwrap();
        let params = GaitParams::new(&body, &crate::character::GaitModifiers::default());
        let mut s = FootSupport::planted_on(SupportPoint::rigid(Vec3::ZERO));
        let fresh = Loose {
            top: 0.0,
            give: 0.3,
        };
        let mut plan = swinging_at(Vec2::new(0.5, 0.0));
        plan.swing = 0.3;
        let key = s.advance(&plan, &params, &body, &fresh, 2.0);
        assert!((s.landing.give - 0.3).abs() < 1e-6);
        assert!((key.floor + 0.3).abs() < 1e-5, "{}", key.floor);
        assert!(key.floor <= key.centre.y);
        assert!(key.surface.abs() < 1e-5, "{}", key.surface);
        // Pressed by other feet: re-aimed.
        let pressed = Loose {
            top: -0.1,
            give: 0.1,
        };
        plan.swing = 0.4;
        s.advance(&plan, &params, &body, &pressed, 2.0);
        assert!((s.landing.point.y + 0.1).abs() < 1e-6);
        // Pressed by the foot ploughing towards it: the landing is held.
        s.landing_held = true;
        plan.swing = 0.5;
        s.advance(&plan, &params, &body, &fresh, 2.0);
        assert!((s.landing.point.y + 0.1).abs() < 1e-6);
        assert!((s.landing.give - 0.1).abs() < 1e-6);
        // Planted, the next swing aims again.
        plan.phase = FootPhase::Stance;
        s.advance(&plan, &params, &body, &fresh, 2.0);
        assert!(!s.landing_held);
    }

    /// Level snow (surface 0, giving 0.3 m) before x = 0.3 and, beyond,
    /// ground at the same height giving the held metres (0: rigid).
    struct SnowThen(f32);

    impl Ground for SnowThen {
        fn cast_down(&self, x: f32, z: f32, _from_y: f32) -> Option<GroundHit> {
            Some(GroundHit {
                point: Vec3::new(x, 0.0, z),
                normal: Vec3::Y,
                give: if x < 0.3 { 0.3 } else { self.0 },
            })
        }
    }

    #[test]
    fn a_ploughing_foot_reads_the_rigid_floor_ahead_on_its_way_to_the_landing() {
        let body = CharacterBody::new(crate::character::CharacterDesc::adult()).unwrap();
        let params = GaitParams::new(&body, &crate::character::GaitModifiers::default());
        let mut plan = swinging_at(Vec2::ZERO);
        plan.foothold = Vec2::new(0.6, 0.0);
        plan.swing = 0.5;
        let floor = |held: bool| {
            let mut s = FootSupport::planted_on(SupportPoint::rigid(Vec3::Y * -0.3));
            s.advance(
                &swinging_at(Vec2::ZERO),
                &params,
                &body,
                &SnowThen(0.0),
                2.0,
            );
            s.landing = SupportPoint::rigid(Vec3::new(0.6, 0.0, 0.0));
            s.landing_held = held;
            s.advance(&plan, &params, &body, &SnowThen(0.0), 2.0).floor
        };
        // Over snow the sole may plough to the snow's floor; once it
        // ploughs towards a landing on rigid ground, the rigid edge ahead
        // holds it up.
        assert!((floor(false) + 0.3).abs() < 1e-5, "{}", floor(false));
        assert!(floor(true).abs() < 1e-5, "{}", floor(true));
    }

    #[test]
    fn a_foot_the_leg_leaves_below_the_floor_ahead_waits_then_catches_up_by_the_landing() {
        let body = CharacterBody::new(crate::character::CharacterDesc::adult()).unwrap();
        let params = GaitParams::new(&body, &crate::character::GaitModifiers::default());
        let half = 0.5 * body.foot_length;
        let mut s = FootSupport::planted_on(SupportPoint::rigid(Vec3::Y * -0.3));
        let mut plan = swinging_at(Vec2::ZERO);
        plan.foothold = Vec2::new(0.8, 0.0);
        let mut key_x = |s: &mut FootSupport, x: f32, swing: f32| {
            plan.target = Vec2::new(x, 0.0);
            plan.swing = swing;
            // Sand beyond the snow, giving 5 cm.
            let sand = SnowThen(0.05);
            s.advance(&plan, &params, &body, &sand, 2.0).centre.x
        };
        // Lifting off in a print 0.25 m deep in the snow: over snow it goes on.
        key_x(&mut s, 0.0, 0.05);
        s.reached = Some(Vec3::new(0.0, -0.25, 0.0));
        let over_snow = 0.29 - half;
        assert!((key_x(&mut s, over_snow, 0.2) - over_snow).abs() < 1e-6);
        // Its toe would go over the sand, whose floor is 5 cm down: it waits.
        assert!((key_x(&mut s, over_snow + 0.05, 0.3) - over_snow).abs() < 1e-6);
        assert!((key_x(&mut s, over_snow + 0.1, 0.4) - over_snow).abs() < 1e-6);
        // Lifted clear, it goes on, and is on its target by the landing.
        s.reached = Some(Vec3::new(over_snow, -0.03, 0.0));
        let on = key_x(&mut s, over_snow + 0.15, 0.5);
        assert!(on > over_snow && on < over_snow + 0.15, "{on}");
        assert!((key_x(&mut s, 0.8, 0.99) - 0.8).abs() < 1e-6);
    }

    #[test]
    fn a_foot_short_of_a_soft_landing_pushes_no_lower_than_the_firm_floor_under_it() {
        let body = CharacterBody::new(crate::character::CharacterDesc::adult()).unwrap();
        let params = GaitParams::new(&body, &crate::character::GaitModifiers::default());
        // Landing in the snow at x = 0 (before x = 0.3); rigid ground beyond.
        let ground = SnowThen(0.0);
        let sole_pushed = |reached_x: f32| {
            let mut s = FootSupport::planted_on(SupportPoint::rigid(Vec3::X * 0.8));
            let mut plan = swinging_at(Vec2::ZERO);
            plan.swing = 0.3;
            s.advance(&plan, &params, &body, &ground, 2.0);
            s.reached = Some(Vec3::new(reached_x, 0.0, 0.0));
            plan.swing = 0.97;
            let key = s.advance(&plan, &params, &body, &ground, 2.0);
            (key.centre.y + plan.lift, key.floor)
        };
        // Over the snow it pushes in; still over the rigid ground it stops on it.
        let (in_snow, snow_floor) = sole_pushed(0.0);
        assert!(
            in_snow < -0.1 && (snow_floor + 0.3).abs() < 1e-5,
            "{in_snow} {snow_floor}"
        );
        let (on_rigid, rigid_floor) = sole_pushed(0.6);
        assert!(
            on_rigid.abs() < 1e-5 && rigid_floor.abs() < 1e-5,
            "{on_rigid} {rigid_floor}"
        );
    }

    #[test]
    fn a_foot_pushing_into_its_landing_stops_on_the_landing_floor_whatever_its_lift() {
        let body = CharacterBody::new(crate::character::CharacterDesc::adult()).unwrap();
        let params = GaitParams::new(&body, &crate::character::GaitModifiers::default());
        // Sand 5 cm deep at 0: a landing held while the foot ploughs
        // towards it, late in the swing while the gait still lifts the foot.
        let sand = Loose {
            top: 0.0,
            give: 0.05,
        };
        let mut s = FootSupport::planted_on(SupportPoint::rigid(Vec3::Y * -0.3));
        let mut plan = swinging_at(Vec2::new(0.5, 0.0));
        plan.swing = 0.1;
        s.advance(&plan, &params, &body, &sand, 2.0);
        s.landing_held = true;
        plan.swing = 0.9;
        plan.lift = 0.07;
        let key = s.advance(&plan, &params, &body, &sand, 2.0);
        let sole = key.centre.y + plan.lift;
        assert!(sole < 0.0 && sole > -0.05, "pushing in: {sole}");
        assert!((key.floor + 0.05).abs() < 1e-6, "floor {}", key.floor);
        assert!((key.surface + 0.05).abs() < 1e-6, "surface {}", key.surface);
    }

    #[test]
    fn a_print_rim_and_a_higher_landing_are_still_cleared() {
        let c = 0.07;
        // Out of a 0.2 m print onto level snow: the foot is above the rim
        // by mid-swing, having risen early (more than half-way at 0.3).
        let s = support(-0.2, 0.0, 0.0);
        assert!(s.swing_height(0.5, c) >= RIM_CLEARANCE - 1e-6);
        assert!(s.swing_height(0.3, c) > -0.1);
        // Up onto a 0.15 m step: mid-swing the foot is above the step.
        let s = support(0.0, 0.0, 0.15);
        assert!(s.swing_height(0.5, c) >= 0.15 + RIM_CLEARANCE - 1e-6);
    }
}
