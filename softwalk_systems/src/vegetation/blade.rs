//! One blade of grass: its fixed shape and its bend state.

use glam::Vec3;

use super::recovery::remaining_fraction;

/// The fixed description of a blade, created by the scattering.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Blade {
    /// Where the blade meets the ground (world).
    pub root: Vec3,
    /// Upright height (metres).
    pub height: f32,
    /// Width at the root (metres); the blade tapers to a point.
    pub width: f32,
    /// Relative stiffness around 1: scales the recovery rate and the bend a
    /// blade takes before it breaks.
    pub stiffness: f32,
    /// Colour (linear RGB) of the healthy blade.
    pub colour: [f32; 3],
}

impl Blade {
    /// Tip of the upright blade.
    #[inline]
    pub fn rest_tip(&self) -> Vec3 {
        self.root + Vec3::new(0.0, self.height, 0.0)
    }

    /// Middle of the upright blade.
    #[inline]
    pub fn rest_mid(&self) -> Vec3 {
        self.root + Vec3::new(0.0, 0.5 * self.height, 0.0)
    }

    /// Root, middle and tip of the blade bent by `bend` (kept above the ground
    /// and never longer than the blade: a flattened blade lies on the ground).
    pub fn points(&self, bend: Bend) -> [Vec3; 3] {
        [
            self.root,
            self.place(self.rest_mid() + bend.mid, 0.5 * self.height),
            self.place(self.rest_tip() + bend.tip, self.height),
        ]
    }

    fn place(&self, p: Vec3, max_len: f32) -> Vec3 {
        let p = Vec3::new(p.x, p.y.max(self.root.y), p.z);
        let v = p - self.root;
        let len = v.length();
        if len > max_len {
            self.root + v * (max_len / len)
        } else {
            p
        }
    }
}

/// Displacement of the blade's middle and tip from upright.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Bend {
    /// Displacement of the middle point.
    pub mid: Vec3,
    /// Displacement of the tip.
    pub tip: Vec3,
}

impl Bend {
    /// No displacement.
    pub const ZERO: Bend = Bend {
        mid: Vec3::ZERO,
        tip: Vec3::ZERO,
    };

    /// Size used to compare bends: `|mid| + |tip|`.
    #[inline]
    pub fn size(&self) -> f32 {
        self.mid.length() + self.tip.length()
    }

    /// `self + (other - self) * k`.
    #[inline]
    pub fn lerp(self, other: Bend, k: f32) -> Bend {
        Bend {
            mid: self.mid + (other.mid - self.mid) * k,
            tip: self.tip + (other.tip - self.tip) * k,
        }
    }

    /// The bend scaled by `k`.
    #[inline]
    pub fn scaled(self, k: f32) -> Bend {
        Bend {
            mid: self.mid * k,
            tip: self.tip * k,
        }
    }
}

/// The persistent state of a blade.
///
/// The bend is never integrated step by step: the blade remembers the bend it
/// was *held* at and *when* (`anchor_time`); at any later time its bend is
/// `rest + (held - rest) * (1 + w t) e^{-w t}` (critically damped spring,
/// released at rest), so the shape does not depend on the step size.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BladeState {
    /// Bend at `anchor_time` (the largest push so far that is not yet recovered).
    pub held: Bend,
    /// Permanent bend (plastic): zero for a healthy blade.
    pub rest: Bend,
    /// Time (patch clock, seconds) when `held` was set.
    pub anchor_time: f64,
    /// Time of the latest push, or a negative value if never pushed.
    pub last_push: f64,
    /// Number of separate treads so far.
    pub treads: u16,
    /// True once the blade broke: it only recovers down to `rest`.
    pub broken: bool,
    /// True while the blade is recovering (it is in the patch's active list).
    pub active: bool,
}

impl Default for BladeState {
    fn default() -> Self {
        Self {
            held: Bend::ZERO,
            rest: Bend::ZERO,
            anchor_time: 0.0,
            last_push: -1.0,
            treads: 0,
            broken: false,
            active: false,
        }
    }
}

impl BladeState {
    /// The bend at time `now` for a blade recovering with `omega` (rad/s).
    #[inline]
    pub fn bend_at(&self, now: f64, omega: f32) -> Bend {
        if !self.active {
            return self.rest;
        }
        let k = remaining_fraction(omega, (now - self.anchor_time) as f32);
        self.rest.lerp(self.held, k)
    }

    /// `self.bend_at(now, omega).size()`, without rebuilding the bend of a
    /// healthy blade (whose bend is `held * k`, of size `|held| * k`).
    #[inline]
    pub(crate) fn bend_size_at(&self, now: f64, omega: f32) -> f32 {
        if self.active && !self.broken {
            self.held.size() * remaining_fraction(omega, (now - self.anchor_time) as f32)
        } else {
            self.bend_at(now, omega).size()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn blade() -> Blade {
        Blade {
            root: Vec3::new(1.0, 2.0, 3.0),
            height: 0.5,
            width: 0.01,
            stiffness: 1.0,
            colour: [0.0, 1.0, 0.0],
        }
    }

    #[test]
    fn points_stay_above_ground_and_within_length() {
        let b = blade();
        let bend = Bend {
            mid: Vec3::new(0.4, -0.6, 0.0),
            tip: Vec3::new(0.9, -0.9, 0.0),
        };
        let [root, mid, tip] = b.points(bend);
        assert_eq!(root, b.root);
        assert!(mid.y >= b.root.y && tip.y >= b.root.y);
        assert!((mid - root).length() <= 0.25 + 1e-6);
        assert!((tip - root).length() <= 0.5 + 1e-6);
        assert_eq!(b.points(Bend::ZERO), [b.root, b.rest_mid(), b.rest_tip()]);
    }

    #[test]
    fn recovering_state_goes_from_held_to_rest() {
        let held = Bend {
            mid: Vec3::new(0.1, -0.1, 0.0),
            tip: Vec3::new(0.2, -0.3, 0.0),
        };
        let s = BladeState {
            held,
            rest: held.scaled(0.5),
            anchor_time: 1.0,
            active: true,
            broken: true,
            ..BladeState::default()
        };
        assert_eq!(s.bend_at(1.0, 3.0), held);
        assert_eq!(s.bend_at(100.0, 3.0), held.scaled(0.5));
        let idle = BladeState::default();
        assert_eq!(idle.bend_at(5.0, 3.0), Bend::ZERO);
    }
}
