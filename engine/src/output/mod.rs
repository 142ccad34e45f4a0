//! Writing frames and animations to files: PNG (RGBA8 and 16-bit gray),
//! animated GIF, APNG, and contact sheets of many frames.
//!
//! Every file is written whole or not at all: single images go through
//! [`crate::io::write_atomic`]; the streaming animation writers write into a
//! [`crate::io::AtomicFile`] (`.NAME.partial` beside the target) and rename it
//! in `finish()`. A writer dropped without `finish()` leaves no file behind.

#![forbid(unsafe_code)]

mod apng;
mod contact_sheet;
mod error;
mod frame_size;
mod gif;
mod png;

pub use apng::ApngWriter;
pub use contact_sheet::contact_sheet;
pub use error::OutputError;
pub use gif::{GifPalette, GifWriter};
pub use png::{encode_png, save_png, save_png_gray16};
