//! Per-foot state shared by the character (which produces it) and the ground
//! and vegetation systems (which read it).

use glam::Vec3;

/// Which leg.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Side {
    /// The left leg (index 0).
    Left,
    /// The right leg (index 1).
    Right,
}

impl Side {
    /// Both sides, left first.
    pub const BOTH: [Side; 2] = [Side::Left, Side::Right];

    /// 0 for left, 1 for right.
    pub fn index(self) -> usize {
        match self {
            Side::Left => 0,
            Side::Right => 1,
        }
    }
}

/// Where a foot is in its walk cycle.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum FootPhase {
    /// On the ground, carrying weight.
    Stance,
    /// In the air, moving up (first part of the swing).
    SwingUp,
    /// In the air, moving down towards the next foothold.
    SwingDown,
}

/// The sole of a foot in world space: a rounded rectangle from heel to toe.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FootSole {
    /// Bottom of the heel (world).
    pub heel: Vec3,
    /// Bottom of the toe tip (world).
    pub toe: Vec3,
    /// Width of the sole, metres.
    pub width: f32,
}

impl FootSole {
    /// Centre of the sole.
    pub fn center(&self) -> Vec3 {
        (self.heel + self.toe) * 0.5
    }
}

/// Everything the ground and vegetation need to know about one foot this step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FootState {
    /// Which leg.
    pub side: Side,
    /// The sole after IK (world).
    pub sole: FootSole,
    /// Ankle joint position after IK (world).
    pub ankle: Vec3,
    /// Velocity of the ankle (world, m/s).
    pub velocity: Vec3,
    /// Phase of the walk cycle.
    pub phase: FootPhase,
    /// True when the foot bears weight: planted in the stance of its walk
    /// cycle, on ground its ray found.
    pub contact: bool,
    /// True when the sole presses the ground: bearing weight, pushing into
    /// soft ground at the end of its swing, or still rising out of its print
    /// at the start of the swing. Carving reads it (a print is released when
    /// its foot is out).
    pub pressing: bool,
}
