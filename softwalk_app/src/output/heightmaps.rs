//! The terrain before and after the run as 16-bit heightmaps.

use std::path::{Path, PathBuf};

use engine::asset::{HeightmapInfo, save_heightmap_png16};
use engine::geom::HeightGrid;

use crate::runner::{ObserverError, RunObserver, TerrainMoment};

/// Writes `terrain_initial.png` and `terrain_final.png` (16-bit grayscale,
/// normalised to each grid's min..max) and keeps what is needed to read heights back.
pub struct HeightmapWriter {
    dir: PathBuf,
    /// Scale information of the initial and the final heightmap, once written.
    pub written: Vec<(PathBuf, HeightmapInfo)>,
}

impl HeightmapWriter {
    /// Heightmaps go to `dir`.
    pub fn new(dir: &Path) -> Self {
        HeightmapWriter {
            dir: dir.to_path_buf(),
            written: Vec::new(),
        }
    }
}

impl RunObserver for HeightmapWriter {
    fn on_terrain(
        &mut self,
        moment: TerrainMoment,
        grid: &HeightGrid,
    ) -> Result<(), ObserverError> {
        let name = match moment {
            TerrainMoment::Initial => "terrain_initial.png",
            TerrainMoment::Final => "terrain_final.png",
        };
        let path = self.dir.join(name);
        let info = save_heightmap_png16(grid, &path)?;
        self.written.push((path, info));
        Ok(())
    }
}
