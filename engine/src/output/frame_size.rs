//! The one size every frame of an animation must have.

use std::path::Path;

use super::error::OutputError;

/// Remembers the first frame's size and refuses frames of another size (or
/// sizes no encoder accepts), naming the animation file and the frame.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct FrameSize(Option<(u32, u32)>);

impl FrameSize {
    /// Checks frame number `index` of the animation written to `path`.
    pub(super) fn check(
        &mut self,
        path: &Path,
        index: usize,
        width: u32,
        height: u32,
    ) -> Result<(), OutputError> {
        super::png::check_size(path, width, height)?;
        let (expected_width, expected_height) = *self.0.get_or_insert((width, height));
        if (width, height) != (expected_width, expected_height) {
            return Err(OutputError::FrameSize {
                path: path.to_path_buf(),
                index,
                expected_width,
                expected_height,
                found_width: width,
                found_height: height,
            });
        }
        Ok(())
    }
}
