use glam::Vec3;

/// Per-sample surface colour of a height grid, supplied by the caller (the engine
/// knows nothing of materials). Evaluated only for the samples the renderer
/// re-lights: around each rectangle given to
/// [`super::TerrainRenderer::mark_dirty`], within the light's reach, and
/// everywhere when the sun changes.
pub trait TerrainColors {
    /// Linear RGB albedo of sample `(i, j)`.
    fn albedo(&self, i: usize, j: usize) -> Vec3;

    /// How disturbed sample `(i, j)` is, in `[0, 1]` (0 = untouched). Disturbed
    /// samples are darkened by [`super::TerrainStyle::disturbed_darkening`].
    fn disturbance(&self, _i: usize, _j: usize) -> f32 {
        0.0
    }
}

/// One albedo everywhere, nothing disturbed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UniformColor(pub Vec3);

impl TerrainColors for UniformColor {
    fn albedo(&self, _i: usize, _j: usize) -> Vec3 {
        self.0
    }
}

/// Any `Fn(i, j) -> albedo` closure is a colour source with no disturbance.
impl<F: Fn(usize, usize) -> Vec3> TerrainColors for F {
    fn albedo(&self, i: usize, j: usize) -> Vec3 {
        self(i, j)
    }
}

/// Row-major per-sample albedo and disturbance slices (`nx` samples per row).
#[derive(Debug, Clone, Copy)]
pub struct SampleColors<'a> {
    /// Samples per row.
    pub nx: usize,
    /// Linear RGB albedo per sample.
    pub albedo: &'a [Vec3],
    /// Disturbance in `[0, 1]` per sample; empty means none.
    pub disturbed: &'a [f32],
}

impl TerrainColors for SampleColors<'_> {
    fn albedo(&self, i: usize, j: usize) -> Vec3 {
        self.albedo
            .get(j * self.nx + i)
            .copied()
            .unwrap_or(Vec3::ONE)
    }

    fn disturbance(&self, i: usize, j: usize) -> f32 {
        self.disturbed.get(j * self.nx + i).copied().unwrap_or(0.0)
    }
}
