//! The screen a frame is drawn on, and which triangle facings it drops.

/// The size of the image triangles are drawn into, in pixels.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Viewport {
    /// Columns.
    pub width: i32,
    /// Rows.
    pub height: i32,
}

/// Which triangles to drop by their facing.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CullMode {
    /// Draw both sides.
    None,
    /// Drop triangles whose vertices run clockwise seen from the camera
    /// (meshes are counter-clockwise from the front).
    Back,
}
