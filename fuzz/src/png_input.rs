//! Heightmap inputs: small PNGs, valid or with bytes broken, and the
//! pixel count their header declares (checked against the per-input budget).

use crate::rng::Rng;

/// A PNG of random size and depth (gray, one in eight RGB), sometimes with
/// bytes changed, cut short or a header claiming a huge image.
pub fn random_png(rng: &mut Rng) -> Vec<u8> {
    let width = [1, 2, 3, 17, 64][rng.below(5)] as u32;
    let height = [1, 2, 5, 33, 64][rng.below(5)] as u32;
    let sixteen = !rng.one_in(3);
    let mut bytes = Vec::new();
    let complete = {
        let mut encoder = png::Encoder::new(&mut bytes, width, height);
        let rgb = rng.one_in(8);
        encoder.set_color(if rgb {
            png::ColorType::Rgb
        } else {
            png::ColorType::Grayscale
        });
        encoder.set_depth(if sixteen {
            png::BitDepth::Sixteen
        } else {
            png::BitDepth::Eight
        });
        let channels = if rgb { 3 } else { 1 };
        match encoder.write_header() {
            Err(_) => false,
            Ok(mut writer) => {
                let samples = (width * height) as usize * channels * if sixteen { 2 } else { 1 };
                let mut data: Vec<u8> = (0..samples).map(|_| rng.next_u64() as u8).collect();
                if rng.one_in(4) {
                    data.iter_mut().for_each(|b| *b = 0xFF);
                }
                writer.write_image_data(&data).is_ok() && writer.finish().is_ok()
            }
        }
    };
    if complete && rng.one_in(3) {
        break_bytes(&mut bytes, rng);
    }
    bytes
}

/// Flips, truncates, or rewrites the declared size in the header.
fn break_bytes(bytes: &mut Vec<u8>, rng: &mut Rng) {
    match rng.below(3) {
        0 if bytes.len() > 24 => {
            let huge = [65_535u32, 1 << 20, u32::MAX, 0][rng.below(4)];
            let at = 16 + 4 * rng.below(2);
            bytes[at..at + 4].copy_from_slice(&huge.to_be_bytes());
        }
        1 if !bytes.is_empty() => {
            let at = rng.below(bytes.len());
            bytes.truncate(at);
        }
        _ => {
            for _ in 0..1 + rng.below(8) {
                if bytes.is_empty() {
                    break;
                }
                let at = rng.below(bytes.len());
                bytes[at] = rng.next_u64() as u8;
            }
        }
    }
}

/// Width times height from a PNG header, `None` when there is no readable header.
pub fn declared_pixels(bytes: &[u8]) -> Option<u64> {
    if bytes.len() < 24 || &bytes[..8] != b"\x89PNG\r\n\x1a\n" || &bytes[12..16] != b"IHDR" {
        return None;
    }
    let w = u32::from_be_bytes(bytes[16..20].try_into().ok()?);
    let h = u32::from_be_bytes(bytes[20..24].try_into().ok()?);
    Some(u64::from(w) * u64::from(h))
}
