//! Stage 4, balance: the rigid proxy carrying the body's global tilt and the
//! PD controller of the paper's eq. 1 acting on it.
//!
//! Model (forward lean `theta` > 0 when leaning towards the walking direction):
//!
//! ```text
//! I * theta'' = alpha * e + beta * theta' - k * (theta - theta_lean) - c * theta'
//! e = (p_com - p_target) . u
//! theta_lean = alpha * e_slow / k_lean      (controller on; 0 when off)
//! ```
//!
//! - the motion plane passes through the COM and is spanned by gravity and the
//!   horizontal velocity; its normal is the character's right `r = v × y`;
//! - `p_target` is the midpoint of the two foot keys projected into that plane;
//! - `u` is the unit vector along the terrain slope in that plane (walking direction);
//! - `p_com` is the animated (untilted) centre of mass projected onto the
//!   terrain line through `p_target` along the ground normal, so `e` is
//!   `(com - p_target) . u`: on an uphill slope the COM projects ahead of the
//!   feet by about `h sin(slope)`, on a downhill slope behind;
//! - written about `r` (positive = backward), this is eq. 1 verbatim:
//!   `tau_r = alpha (p_target - p_com) . u + beta theta_r'`;
//! - `k` (posture stiffness) and `c` (passive damping, larger than any allowed
//!   beta) are the body's own passive terms: `beta` feeds the swing, the net
//!   damping `c - beta` stays positive and falls as beta rises;
//! - `theta_lean` is the sustained lean the controller asks of the posture:
//!   `e_slow` is `e` low-passed over about a step (time constant
//!   `lean_time_constant`), so the step-frequency swing of `e` barely reaches
//!   it while a slope's steady offset does. The steady lean is
//!   `alpha e (1/k + 1/k_lean)`: a soft stiffness for the slow lean, the stiff
//!   `k` (natural frequency above the step frequency) for the swing;
//! - `I` is the proxy's pitch inertia about the ground: the body's inertia
//!   scaled to the proxy mass plus `m_proxy * h_com²`, so a higher COM gives a
//!   larger inertia, a lower natural frequency and a lower damping ratio.
//!
//! A second PD axis (beyond the paper, its limitation 3) leans the body into
//! turns, about the walking direction (`phi` > 0 leaning left):
//!
//! ```text
//! I_roll * phi'' = k_lat * (phi_turn - phi) - c_lat * phi'
//! phi_turn = atan(v * omega / g)            (controller on; 0 when off)
//! ```
//!
//! with `v` the pelvis speed and `omega` the rate of its heading (positive
//! turning left): the lean that puts the resultant of gravity and the
//! centripetal force through the feet. On a straight path `omega` is 0 and
//! so is the lean; in a turn of radius `r` it is `atan(v² / (g r))`.
//!
//! Its sagittal counterpart leans the body back while the walk brakes for
//! a stop: the posture's target lean falls by [`brake_lean`] of the
//! deceleration `a` the gait is asked for, `atan(a / g)` up to
//! [`MAX_BRAKE_LEAN`] (controller on; nothing at a steady speed).

use glam::{Mat3, Quat, Vec2, Vec3};

use super::body::CharacterBody;
use super::desc::DEFAULT_PASSIVE_DAMPING;
use super::error::{CharacterError, check_range};
use super::gait::{Gait, clamp_dt};
use super::gravity::GRAVITY;
use super::path::turn_angle;
use super::rays::FootRays;

/// The balance controller's settings (paper eq. 1), settable at run time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Balance {
    /// Stiffness on the COM offset, N·m per metre (30 in the paper).
    pub alpha: f32,
    /// Swing gain on the tilt rate, N·m·s/rad (6 in the paper; 4 in medium grass).
    pub beta: f32,
    /// Controller on (the paper's blue character) or off (red).
    pub enabled: bool,
    /// Passive posture stiffness k, N·m/rad.
    pub posture_stiffness: f32,
    /// Passive damping c, N·m·s/rad; beta must stay below it.
    pub passive_damping: f32,
    /// Stiffness k_lean of the sustained lean, N·m/rad: the posture leans by
    /// `alpha * e_slow / k_lean` on top of the fast response (0: no sustained lean).
    pub lean_stiffness: f32,
    /// Time constant of the low-pass giving `e_slow`, seconds.
    pub lean_time_constant: f32,
    /// Stiffness k_lat of the lateral axis, N·m/rad.
    pub lateral_stiffness: f32,
    /// Damping c_lat of the lateral axis, N·m·s/rad.
    pub lateral_damping: f32,
}

/// Default posture stiffness, N·m/rad: keeps every morphology's natural
/// frequency above its step frequency.
pub const DEFAULT_POSTURE_STIFFNESS: f32 = 300.0;
/// Default stiffness of the sustained lean, N·m/rad (a visible 7–8° at a 20° slope).
pub const DEFAULT_LEAN_STIFFNESS: f32 = 100.0;
/// Default time constant of the slow COM offset, seconds (about one step).
pub const DEFAULT_LEAN_TIME_CONSTANT: f32 = 0.5;
/// Default stiffness of the lateral axis, N·m/rad: settles a turn's lean in
/// about half a second for an adult's proxy.
pub const DEFAULT_LATERAL_STIFFNESS: f32 = 60.0;
/// Default damping of the lateral axis, N·m·s/rad (about critical).
pub const DEFAULT_LATERAL_DAMPING: f32 = 15.0;
/// The largest lean into a turn, radians (30°).
pub const MAX_TURN_LEAN: f32 = 0.52;
/// The largest lean back while braking, radians (3°): the legs do most of
/// the braking, the trunk leans back slightly.
pub const MAX_BRAKE_LEAN: f32 = 0.052;

impl Balance {
    /// The controller with the given gains, enabled, and default passive terms.
    pub fn new(alpha: f32, beta: f32) -> Result<Self, CharacterError> {
        let mut b = Balance {
            alpha: 30.0,
            beta: 6.0,
            enabled: true,
            posture_stiffness: DEFAULT_POSTURE_STIFFNESS,
            passive_damping: DEFAULT_PASSIVE_DAMPING,
            lean_stiffness: DEFAULT_LEAN_STIFFNESS,
            lean_time_constant: DEFAULT_LEAN_TIME_CONSTANT,
            lateral_stiffness: DEFAULT_LATERAL_STIFFNESS,
            lateral_damping: DEFAULT_LATERAL_DAMPING,
        };
        b.set_gains(alpha, beta)?;
        Ok(b)
    }

    /// Changes alpha and beta, refusing non-finite or negative values and a
    /// beta at or above the passive damping (the swing would grow without bound).
    pub fn set_gains(&mut self, alpha: f32, beta: f32) -> Result<(), CharacterError> {
        check_range("alpha", alpha, 0.0, 1.0e4)?;
        check_range("beta", beta, 0.0, self.passive_damping)?;
        if beta >= self.passive_damping {
            return Err(CharacterError::InvalidField {
                field: "beta",
                reason: format!(
                    "{beta} must stay below the passive damping {}",
                    self.passive_damping
                ),
            });
        }
        self.alpha = alpha;
        self.beta = beta;
        Ok(())
    }
}

/// The single rigid body carrying the character's global tilt.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RigidProxy {
    /// Proxy mass, kg.
    pub mass: f32,
    /// Inertia about the COM in the body frame (X right, Y up, Z forward), kg·m²:
    /// the body's inertia scaled to the proxy mass.
    pub inertia: Mat3,
    /// Pitch inertia about the ground under the COM, kg·m².
    pub pitch_inertia: f32,
    /// Animated (untilted) centre of mass this step (world).
    pub com: Vec3,
    /// Rotation of the body by the tilt (about `axis`).
    pub orientation: Quat,
    /// Angular velocity (world, rad/s).
    pub angular_velocity: Vec3,
    /// Normal of the motion plane: the character's right.
    pub axis: Vec3,
    /// Forward lean, radians (positive towards the walking direction).
    pub tilt: f32,
    /// Rate of the forward lean, rad/s.
    pub tilt_rate: f32,
    /// Controller torque of eq. 1 this step, forward positive, N·m.
    pub torque: f32,
    /// Terrain slope along the walking direction under the pelvis, radians (uphill positive).
    pub slope: f32,
    /// The COM offset `e` low-passed (`e_slow`), metres.
    pub slow_offset: f32,
    /// Roll inertia about the ground under the COM (about the walking direction), kg·m².
    pub roll_inertia: f32,
    /// Lean into a turn, radians (positive leaning left).
    pub lean: f32,
    /// Rate of the lean, rad/s.
    pub lean_rate: f32,
    /// The lean the lateral axis is driving towards, `atan(v ω / g)`, radians.
    pub turn_lean: f32,
    /// Pelvis heading (x, z) at the last step (zero before the first).
    pub last_heading: Vec2,
    /// Debug collider: capsule radius, m.
    pub capsule_radius: f32,
    /// Debug collider: capsule half height (centre to cap centre), m.
    pub capsule_half_height: f32,
}

impl RigidProxy {
    /// An upright, resting proxy for a body.
    pub fn new(body: &CharacterBody) -> Self {
        let mut proxy = RigidProxy {
            mass: body.desc.proxy_mass,
            inertia: Mat3::ZERO,
            pitch_inertia: 0.0,
            com: Vec3::Y * body.com_height,
            orientation: Quat::IDENTITY,
            angular_velocity: Vec3::ZERO,
            axis: Vec3::X,
            tilt: 0.0,
            tilt_rate: 0.0,
            torque: 0.0,
            slope: 0.0,
            slow_offset: 0.0,
            roll_inertia: 0.0,
            lean: 0.0,
            lean_rate: 0.0,
            turn_lean: 0.0,
            last_heading: Vec2::ZERO,
            capsule_radius: 0.15 * body.desc.height,
            capsule_half_height: 0.35 * body.desc.height,
        };
        proxy.take_body_mass(body);
        proxy
    }

    /// Takes the inertia and centre of mass height of `body` (after
    /// [`CharacterBody::set_mass_properties`]), keeping the tilt and lean state.
    pub fn take_body_mass(&mut self, body: &CharacterBody) {
        self.inertia = body.inertia * (self.mass / body.desc.mass);
        self.pitch_inertia = about_ground(self.inertia.x_axis.x, self.mass, body.com_height);
        self.roll_inertia = about_ground(self.inertia.z_axis.z, self.mass, body.com_height);
    }
}

/// An inertia about the centre of mass moved to the ground below it, `com_height`
/// lower (the parallel-axis theorem).
fn about_ground(about_com: f32, mass: f32, com_height: f32) -> f32 {
    about_com + mass * com_height * com_height
}

/// The animated centre of mass: the upper body above the walking pelvis and
/// each leg's mass halfway between its hip and its foot target.
pub fn animated_com(body: &CharacterBody, gait: &Gait, rays: &FootRays) -> Vec3 {
    let right = gait.pelvis.right3();
    let pelvis_xz = gait.pelvis.position + Vec2::new(right.x, right.z) * gait.sway;
    let hip_y = rays.body.point.y + gait.params.walking_hip_height(body) + gait.bob;
    let pelvis = Vec3::new(pelvis_xz.x, hip_y, pelvis_xz.y);
    let leg_share = body.leg_mass() / body.desc.mass;
    let mut com = pelvis + Vec3::Y * (body.com_height - body.hip_height);
    for plan in &gait.feet {
        let offset = plan.target - pelvis_xz;
        com += Vec3::new(offset.x, 0.0, offset.y) * (0.5 * leg_share);
    }
    com
}

/// Stage 4: computes the eq. 1 torque and integrates the proxy's tilt by `dt`
/// (clamped by [`clamp_dt`]), semi-implicit Euler with the damping taken implicitly.
pub fn balance_stage(
    proxy: &mut RigidProxy,
    balance: &Balance,
    body: &CharacterBody,
    gait: &Gait,
    rays: &FootRays,
    dt: f32,
) {
    let dt = clamp_dt(dt);
    let com = animated_com(body, gait, rays);
    let velocity = Vec3::new(gait.velocity.x, 0.0, gait.velocity.y);
    let forward = velocity
        .try_normalize()
        .unwrap_or_else(|| gait.pelvis.heading3());
    let right = forward.cross(Vec3::Y);
    let n = rays.body.normal;
    let slope = (-n.dot(forward)).atan2(n.dot(Vec3::Y).max(1.0e-3));
    let u = forward * slope.cos() + Vec3::Y * slope.sin();
    let in_plane = |p: Vec3| p - right * (p - com).dot(right);
    let target = (in_plane(rays.feet[0].point) + in_plane(rays.feet[1].point)) * 0.5;
    let offset = (com - target).dot(u);
    let torque = if balance.enabled {
        balance.alpha * offset + balance.beta * proxy.tilt_rate
    } else {
        0.0
    };
    proxy.com = com;
    proxy.axis = right;
    proxy.slope = slope;
    proxy.torque = torque;
    if dt > 0.0 {
        let follow = 1.0 - (-dt / balance.lean_time_constant.max(dt)).exp();
        proxy.slow_offset += (offset - proxy.slow_offset) * follow;
        let mut lean = if balance.enabled && balance.lean_stiffness > 0.0 {
            balance.alpha * proxy.slow_offset / balance.lean_stiffness
        } else {
            0.0
        };
        if balance.enabled && gait.params.braking > 0.0 {
            lean -= brake_lean(gait.params.braking);
        }
        let inertia = proxy.pitch_inertia;
        let drive = torque - balance.posture_stiffness * (proxy.tilt - lean);
        proxy.tilt_rate = (proxy.tilt_rate + dt * drive / inertia)
            / (1.0 + dt * balance.passive_damping / inertia);
        proxy.tilt += dt * proxy.tilt_rate;
    }
    lateral_stage(proxy, balance, gait, dt);
    proxy.orientation = proxy.body_rotation(forward);
    proxy.angular_velocity = right * -proxy.tilt_rate;
}

impl RigidProxy {
    /// The body's rotation for walking along `forward`: the forward tilt
    /// about the right axis, then the lean into the turn about `forward`
    /// (none on a straight path).
    pub fn body_rotation(&self, forward: Vec3) -> Quat {
        let pitch = Quat::from_axis_angle(forward.cross(Vec3::Y), -self.tilt);
        if self.lean == 0.0 {
            pitch
        } else {
            Quat::from_axis_angle(forward, -self.lean) * pitch
        }
    }
}

/// How far the body leans back braking at `deceleration` m/s²:
/// `atan(a / g)`, within [0, [`MAX_BRAKE_LEAN`]].
pub fn brake_lean(deceleration: f32) -> f32 {
    (deceleration.max(0.0) / GRAVITY).atan().min(MAX_BRAKE_LEAN)
}

/// The lean that balances a turn at `speed` (m/s) turning at `rate` (rad/s,
/// positive left): `atan(v ω / g)`, within ±[`MAX_TURN_LEAN`].
pub fn turn_lean(speed: f32, rate: f32) -> f32 {
    (speed * rate / GRAVITY)
        .atan()
        .clamp(-MAX_TURN_LEAN, MAX_TURN_LEAN)
}

/// The lateral axis: drives the lean towards [`turn_lean`] of the pelvis's
/// speed and heading rate (semi-implicit Euler, damping implicit).
fn lateral_stage(proxy: &mut RigidProxy, balance: &Balance, gait: &Gait, dt: f32) {
    let heading = gait.pelvis.heading;
    if dt <= 0.0 {
        return;
    }
    let previous = proxy.last_heading;
    proxy.last_heading = heading;
    let rate = if previous == Vec2::ZERO {
        0.0
    } else {
        turn_angle(previous, heading) / dt
    };
    proxy.turn_lean = if balance.enabled {
        turn_lean(gait.velocity.length(), rate)
    } else {
        0.0
    };
    if proxy.turn_lean == 0.0 && proxy.lean == 0.0 && proxy.lean_rate == 0.0 {
        return;
    }
    let inertia = proxy.roll_inertia.max(1.0e-6);
    let drive = balance.lateral_stiffness * (proxy.turn_lean - proxy.lean);
    proxy.lean_rate =
        (proxy.lean_rate + dt * drive / inertia) / (1.0 + dt * balance.lateral_damping / inertia);
    proxy.lean += dt * proxy.lean_rate;
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gains_are_validated_by_name() {
        let e = Balance::new(f32::NAN, 6.0).unwrap_err();
        assert!(matches!(
            e,
            CharacterError::InvalidField { field: "alpha", .. }
        ));
        let e = Balance::new(30.0, DEFAULT_PASSIVE_DAMPING).unwrap_err();
        assert!(matches!(
            e,
            CharacterError::InvalidField { field: "beta", .. }
        ));
        let mut b = Balance::new(30.0, 6.0).unwrap();
        b.set_gains(10.0, 4.0).unwrap();
        assert_eq!((b.alpha, b.beta), (10.0, 4.0));
    }
}
