//! Drawing a world: [`WorldView`] turns a simulated [`engine::ecs::World`]
//! into frames (shaded ground re-lit only where it changed, characters,
//! grass, props, optional debug overlays), as seen by a [`CameraRig`].
//!
//! ```no_run
//! # use softwalk_systems::sim::SimBuilder;
//! # fn demo(app: &engine::schedule::App) -> Result<(), Box<dyn std::error::Error>> {
//! use softwalk_systems::view::{CameraRig, ViewSettings, WorldView};
//!
//! let rig = CameraRig::fixed([2.0, 1.6, -1.5], [2.0, 0.0, 2.0]);
//! let mut view = WorldView::new(&app.world, rig, &ViewSettings::default())?;
//! let image = view.render(&app.world, 0.0)?;
//! image.save("frame.png")?;
//! # Ok(())
//! # }
//! ```

mod camera_rig;
mod overlay_layers;
mod overlays;
mod palette;
mod settings;
mod skinned_figure;
mod world_view;

pub use camera_rig::CameraRig;
pub use overlay_layers::OverlayLayers;
pub use overlays::draw_overlays;
pub use palette::{TerrainPaint, material_albedo};
pub use settings::ViewSettings;
pub use world_view::{ViewError, WorldView};
