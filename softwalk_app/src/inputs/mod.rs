//! Recorded inputs: what a person (or a script) asked of a steered character,
//! step by step, so a live session replays headless to the same world.
//!
//! An input file is TOML: an optional `character` (the steered one, the
//! scene's first by default) and `[[event]]` tables, each with the `step`
//! it applies before and exactly one action:
//!
//! ```toml
//! character = "walker"
//! [[event]]
//! step = 0
//! velocity = [0.0, 1.2]   # desired planar velocity (x, z), m/s
//! [[event]]
//! step = 60
//! speed = 1.5             # multiplies the desired velocity (Shift)
//! [[event]]
//! step = 120
//! brush = "snow"          # repaints the ground ahead of the character
//! [[event]]
//! step = 300
//! reset = true            # rebuilds the scene
//! ```

mod apply;
mod script;
mod session;

pub use apply::{BRUSH_AHEAD_M, BRUSH_RADIUS_M, InputState, steer_character};
pub use script::{InputAction, InputError, InputEvent, InputScript};
pub use session::{InputSession, SessionError};
