//! The size a PNG file declares in its header, read without decoding the image.

use std::io::Read;
use std::path::Path;

/// `(width, height)` from the PNG's `IHDR` chunk; `None` when the file cannot be
/// read or does not start like a PNG.
pub fn png_size(path: &Path) -> Option<(u32, u32)> {
    let mut header = [0u8; 24];
    std::fs::File::open(path)
        .ok()?
        .read_exact(&mut header)
        .ok()?;
    if &header[..8] != b"\x89PNG\r\n\x1a\n" || &header[12..16] != b"IHDR" {
        return None;
    }
    let w = u32::from_be_bytes(header[16..20].try_into().ok()?);
    let h = u32::from_be_bytes(header[20..24].try_into().ok()?);
    Some((w, h))
}
