//! An observer that keeps only the last rendered frame.

use image::RgbaImage;

use crate::runner::{Frame, ObserverError, RunObserver};

/// Keeps the last frame a run renders (for a gallery image or a snapshot test).
///
/// ```no_run
/// use softwalk_app::output::LastFrame;
/// use softwalk_app::scene::Scene;
/// use softwalk_app::runner::{RunOptions, run};
///
/// # fn main() -> Result<(), Box<dyn std::error::Error>> {
/// let scene = Scene::builtin("default")?;
/// let mut last = LastFrame::default();
/// run(&scene, &RunOptions::from_scene(&scene), &mut last)?;
/// let image = last.into_image().expect("the run rendered");
/// # let _ = image;
/// # Ok(())
/// # }
/// ```
#[derive(Debug, Default)]
pub struct LastFrame(Option<RgbaImage>);

impl LastFrame {
    /// The last frame, or `None` when the run rendered none.
    pub fn into_image(self) -> Option<RgbaImage> {
        self.0
    }
}

impl RunObserver for LastFrame {
    fn on_frame(&mut self, frame: &Frame<'_>) -> Result<(), ObserverError> {
        self.0 = Some(frame.image.clone());
        Ok(())
    }
}
