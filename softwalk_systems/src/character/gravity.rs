//! Standard gravity, shared by the walk model (Froude numbers) and the
//! balance (leaning into turns and braking).

/// Standard gravity, m/s².
pub const GRAVITY: f32 = 9.81;
