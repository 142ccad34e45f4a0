//! How a scene file's camera and settings become a
//! [`softwalk_systems::view::WorldView`].

mod scene_view;

pub use scene_view::scene_view;
