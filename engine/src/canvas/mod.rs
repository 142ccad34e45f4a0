//! Drawing on finished frames: 2D overlays through tiny-skia on the frame's
//! own bytes ([`Overlay`]), text in the embedded DejaVu Sans ([`text`]) and
//! line plots ([`LinePlot`]), robust to any series. Nothing here knows about
//! the 3D renderer: a caller projects world points itself.

#![forbid(unsafe_code)]

pub mod overlay;
pub mod plot;
pub mod text;

pub use overlay::{Overlay, draw_text};
pub use plot::{LinePlot, PixelRect, Series};
pub use text::text_width;
