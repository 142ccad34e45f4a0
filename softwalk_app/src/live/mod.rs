//! The live viewer's logic, free of any window: keys to a desired velocity
//! relative to the camera, the orbiting follow camera, the fixed-step clock
//! and the heads-up line. `softwalk view` (`commands/view.rs`) puts them in
//! a window; everything here is tested without one.

mod clock;
mod controls;
mod hud;
mod orbit;

pub use clock::FixedStepClock;
pub use controls::{
    BRUSH_MATERIALS, Held, RUN_FACTOR, WALK_SPEED_M_S, desired_velocity, next_brush,
};
pub use hud::{Hud, HudFigures};
pub use orbit::{DEFAULT_CAMERA_OFFSET, OrbitCamera};
