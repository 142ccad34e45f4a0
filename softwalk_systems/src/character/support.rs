//! Where each foot stands: the ground under a planted foot is locked when it
//! lands and sinks by the print the material predicts; a swinging foot
//! travels from the print it left to the ground it will land on.
//!
//! This is what keeps the foot IK, the rays and carving from feeding each
//! other: a planted foot does not re-read the cells it is carving (which
//! would lower the foot, which would carve deeper, every step), and a
//! swinging foot does not snap to every print wall and rim it passes over.

use glam::{Vec2, Vec3};

use super::gait::FootPlan;
use crate::foot::FootPhase;
use crate::ground::{Ground, GroundHit};

/// Time a planted foot takes to sink to its full print, seconds: the weight
/// comes onto the leg over the loading response.
pub const SINK_TIME: f32 = 0.2;

/// Least height of a swinging foot over the higher of the print it left and
/// the ground it lands on, metres.
pub const RIM_CLEARANCE: f32 = 0.03;
/// Fraction of the swing over which a foot rises out of a print (and, at
/// the end, settles into a lower landing).
const STEP_OUT_TIME: f32 = 0.3;

fn smoothstep(t: f32) -> f32 {
    let t = t.clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

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

    /// The floor a planted foot sinks to: the surface lowered by the give.
    pub fn floor(&self) -> f32 {
        self.point.y - self.give
    }

    fn from_hit(hit: GroundHit) -> Self {
        SupportPoint {
            point: hit.point,
            normal: hit.normal,
            give: hit.give.max(0.0),
        }
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
    /// Stance: the ground under the sole centre when this contact began,
    /// before it sank. Swing: the ground at the planned foothold.
    pub landing: SupportPoint,
    /// The sole-centre ground point the foot left at lift-off (sunk), and its normal.
    pub left: SupportPoint,
    /// The surface the foot left, before it sank: the top of its print.
    pub left_rim: f32,
    /// Seconds since the foot landed (0 while swinging).
    pub planted_for: f32,
    /// True while the foot is planted.
    pub planted: bool,
    /// False when the last ray for this foot found nothing.
    pub hit: bool,
}

impl FootSupport {
    /// A foot planted (and already sunk) on `point`.
    pub fn planted_on(point: SupportPoint) -> Self {
        FootSupport {
            landing: point,
            left: point,
            left_rim: point.point.y,
            planted_for: 0.0,
            planted: true,
            hit: true,
        }
    }

    /// How far the planted foot has sunk into its print, metres.
    pub fn sink(&self) -> f32 {
        if self.planted {
            // Fastest at touchdown (the foot arrives moving down), easing
            // out as the print reaches its floor.
            let s = (self.planted_for / SINK_TIME).clamp(0.0, 1.0);
            self.landing.give * (1.0 - (1.0 - s) * (1.0 - s))
        } else {
            0.0
        }
    }

    /// The floor this foot stands on, or will once sunk: for a swinging
    /// foot, the floor at its next foothold.
    pub fn floor(&self) -> f32 {
        self.landing.floor()
    }

    /// Advances the support by `dt` for `plan` (whose swing lifts the foot
    /// by up to `clearance`), casting rays from `from_y`; returns the ground
    /// point under the sole centre and its normal (for a swinging foot, the
    /// ground its lift is measured from).
    pub fn advance(
        &mut self,
        plan: &FootPlan,
        ground: &dyn Ground,
        from_y: f32,
        clearance: f32,
        dt: f32,
    ) -> (Vec3, Vec3) {
        let cast = |at: Vec2| ground.cast_down(at.x, at.y, from_y);
        if plan.phase == FootPhase::Stance {
            if self.planted {
                self.planted_for += dt;
            } else {
                self.hit = self.landing.update(plan.foothold, cast(plan.foothold));
                self.planted = true;
                self.planted_for = 0.0;
            }
            return (self.landing.point - Vec3::Y * self.sink(), self.landing.normal);
        }
        if self.planted {
            self.left = SupportPoint {
                point: self.landing.point - Vec3::Y * self.sink(),
                ..self.landing
            };
            self.left_rim = self.landing.point.y;
            self.planted = false;
            self.planted_for = 0.0;
        }
        self.hit = self.landing.update(plan.foothold, cast(plan.foothold));
        let (y, normal) = self.swing_ground(plan.swing, clearance);
        // Ground rising above the path between the two footholds lifts the foot.
        let y = cast(plan.target).map_or(y, |h| y.max(h.point.y - plan.lift));
        (Vec3::new(plan.target.x, y, plan.target.y), normal)
    }

    /// The ground a swinging foot travels over at swing progress `u`, with
    /// the swing's own lift `clearance` to come on top: from the print it
    /// left to its landing. Between two footholds of different heights (out
    /// of a deep print, or down into one) the foot rises early and clears
    /// the higher of its landing and the print's rim by at least
    /// [`RIM_CLEARANCE`], the way a leg steps
    /// out of deep snow with the hip, not by dragging the foot.
    fn swing_ground(&self, u: f32, clearance: f32) -> (f32, Vec3) {
        let u = u.clamp(0.0, 1.0);
        let eased = smoothstep(u);
        let (from, to) = (self.left.point.y, self.landing.point.y);
        let base = from + (to - from) * eased;
        let apex = (from.min(to) + clearance).max(self.left_rim.max(to) + RIM_CLEARANCE);
        let top = apex - clearance;
        let held = smoothstep(u.min(1.0 - u) / STEP_OUT_TIME);
        let y = base + (top - base).max(0.0) * held;
        let normal = self
            .left
            .normal
            .lerp(self.landing.normal, eased)
            .try_normalize()
            .unwrap_or(Vec3::Y);
        (y, normal)
    }
}
