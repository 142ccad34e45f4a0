//! Rendering: image and animation output, 2D overlays, text and plots.
//!
//! Everything here works on opaque [`image::RgbaImage`] frames and pixel
//! coordinates; world-space overlay helpers take a projector closure from the
//! caller's camera.

pub mod output;
pub mod overlay;
pub mod plot;
pub mod text;

pub use output::{
    ApngWriter, GifPalette, GifWriter, OutputError, contact_sheet, encode_png, save_png,
    save_png_gray16,
};
pub use overlay::Overlay;
pub use plot::{LinePlot, PixelRect, Series};
pub use text::{draw_text, text_width};
