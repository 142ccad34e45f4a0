//! What the render tests share: the preview PNGs they write for people.

use image::RgbaImage;

/// Writes `image` to `target/render-previews/{name}.png` (best effort:
/// previews are for people, not for the checks).
pub fn preview(name: &str, image: &RgbaImage) {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../target/render-previews");
    if std::fs::create_dir_all(&dir).is_ok() {
        let _ = image.save(dir.join(format!("{name}.png")));
    }
}
