//! Scene files: a TOML description of terrain, materials, grass, characters,
//! camera, simulation and rendering settings, checked field by field, and
//! turned into a simulation by [`Scene::build_sim`].
//!
//! The scene format builds on the library's types: `[[materials]]` entries are
//! `softwalk_systems::terrain::TerrainMaterial`s, `[characters.body]` is a
//! `softwalk_systems::character::CharacterDesc`, `[[grass]]` starts from a
//! `softwalk_systems::vegetation::GrassSettings` preset. The terrain spans
//! `x` in `[0, size_x]` and `z` in `[0, size_z]`, heights in `[0, max_height]`.
//!
//! ```
//! use softwalk_app::scene::Scene;
//! let scene = Scene::builtin("sand-flat").unwrap();
//! let text = scene.to_toml_string().unwrap();
//! let again = Scene::from_toml_str(&text, std::path::Path::new("")).unwrap();
//! assert_eq!(scene, again);
//! ```

mod build;
mod builtin;
mod camera;
mod character;
mod character_clip;
mod character_model;
mod check;
mod crowd;
mod crowding;
mod error;
mod field_line;
mod grass;
mod ignored_keys;
mod material;
mod png_header;
mod prop;
mod render_settings;
mod rig_cache;
mod sim_settings;
mod syntax;
mod terrain;
mod terrain_build;

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};
use softwalk_systems::terrain::{MaterialTable, TerrainMaterial};
use softwalk_systems::vegetation::MAX_BLADES;

pub use builtin::{BuiltinScene, builtin_scenes};
pub use camera::{CameraMode, CameraSpec, MAX_CAMERA_COORDINATE};
pub use character::{CharacterSpec, DEFAULT_CORNER_RADIUS, MAX_TURN_DEG, MAX_WAYPOINTS, PathSpec};
pub use character_clip::{LoadedClip, load_clip};
pub use character_model::{HUMAN_MODEL, MANNEQUIN_MODEL, role_key};
pub use crowd::{CrowdLayout, CrowdSpec};
pub use crowding::{MAX_CHARACTERS, SPAWN_CLEARANCE_M};
pub use error::SceneError;
pub use grass::{
    GrassPatchSpec, GrassPreset, MAX_BLADE_WIDTH, MAX_BREAK_BEND, MAX_GAMMA, MAX_GRASS_DENSITY,
    MAX_GRASS_HEIGHT, MAX_RECOVERY_OMEGA, MAX_T_MAX,
};
pub use png_header::png_size;
pub use prop::{MAX_PROP_FILE_BYTES, MAX_PROP_SCALE, MAX_PROP_SINK, MAX_PROPS, PropSpec};
pub use render_settings::{
    APNG_DELAY_MS, GIF_DELAY_MS, MAX_FRAME_SIDE, RenderSettings, frame_delay_ms,
};
pub use rig_cache::{CharacterAssets, RigCache};
pub use sim_settings::{MAX_DT, MAX_STEPS, MIN_DT, SimSettings};
pub use terrain::{
    FEATURE_SIZE_RANGE, MAX_REGIONS, MAX_RESOLUTION, MAX_SINUOSITY, MAX_TERRAIN_SIZE,
    MaterialRegion, Slope, TerrainShape, TerrainSpec,
};

/// Largest scene file read, bytes: far above any hand-written or generated
/// scene (a 20,000-walker crowd is about 4 MB).
pub const MAX_SCENE_FILE_BYTES: u64 = 64 << 20;
/// Most accepted `[[grass]]` patches.
pub const MAX_GRASS_PATCHES: usize = 256;
/// Most accepted `[[materials]]` entries.
pub const MAX_MATERIALS: usize = 256;

/// A whole scene. Build one with [`Scene::from_toml_str`], [`Scene::load`] or
/// [`Scene::builtin`]; all three validate it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scene {
    /// Short name, used in outputs.
    pub name: String,
    /// One-line description.
    #[serde(default)]
    pub description: String,
    /// The ground.
    pub terrain: TerrainSpec,
    /// Time span and step.
    pub sim: SimSettings,
    /// Camera; defaults to following the first character.
    #[serde(default)]
    pub camera: CameraSpec,
    /// Frame settings; defaults to 960 x 540 every 2nd step.
    #[serde(default)]
    pub render: RenderSettings,
    /// User-defined materials; one named like a preset replaces it.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub materials: Vec<TerrainMaterial>,
    /// Grass patches.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub grass: Vec<GrassPatchSpec>,
    /// Static meshes on the terrain (rocks, logs, bridges) the feet stand on.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub props: Vec<PropSpec>,
    /// The walkers (at least one).
    pub characters: Vec<CharacterSpec>,
    /// Folder relative paths are resolved against (the scene file's folder).
    #[serde(skip)]
    pub base_dir: PathBuf,
    /// The characters' models and clips, loaded once by validation and
    /// shared with the build (no part of the scene's content).
    #[serde(skip)]
    pub rigs: RigCache,
}

impl Scene {
    /// Parses and validates TOML text; relative paths resolve against `base_dir`.
    pub fn from_toml_str(text: &str, base_dir: &Path) -> Result<Scene, SceneError> {
        let mut scene: Scene = toml::from_str(text).map_err(|e| syntax::syntax_error(text, &e))?;
        scene.base_dir = base_dir.to_path_buf();
        if let Ok(kept) = toml::Table::try_from(&scene) {
            ignored_keys::check_no_ignored_keys(text, &kept)?;
        }
        scene.validate().map_err(|error| {
            match error.field().and_then(|f| field_line::field_line(text, f)) {
                Some(line) => SceneError::AtLine {
                    line,
                    error: Box::new(error),
                },
                None => error,
            }
        })?;
        Ok(scene)
    }

    /// Reads, parses and validates a scene file; errors name the file. Only a
    /// regular file of at most [`MAX_SCENE_FILE_BYTES`] is read (a FIFO or a
    /// device would block or never end).
    pub fn load(path: &Path) -> Result<Scene, SceneError> {
        let read_error = |source| SceneError::Read {
            path: path.to_path_buf(),
            source,
        };
        let meta = std::fs::metadata(path).map_err(read_error)?;
        if !meta.is_file() {
            return Err(SceneError::NotAFile {
                path: path.to_path_buf(),
            });
        }
        if meta.len() > MAX_SCENE_FILE_BYTES {
            return Err(SceneError::FileTooLarge {
                path: path.to_path_buf(),
                bytes: meta.len(),
            });
        }
        let text = std::fs::read_to_string(path).map_err(read_error)?;
        let base = path.parent().unwrap_or(Path::new(""));
        Scene::from_toml_str(&text, base).map_err(|e| SceneError::InFile {
            path: path.to_path_buf(),
            error: Box::new(e),
        })
    }

    /// The built-in scene with this name, parsed and validated.
    pub fn builtin(name: &str) -> Result<Scene, SceneError> {
        let b = BuiltinScene::find(name)?;
        Scene::from_toml_str(&b.toml, Path::new(""))
    }

    /// The scene as TOML text that [`Scene::from_toml_str`] reads back to an equal scene.
    pub fn to_toml_string(&self) -> Result<String, SceneError> {
        toml::to_string(self).map_err(|e| SceneError::Serialize(e.to_string()))
    }

    /// A path from the scene resolved against its folder.
    pub fn resolve(&self, path: &Path) -> PathBuf {
        self.base_dir.join(path)
    }

    /// The resolved heightmap file, when the terrain shape is a heightmap.
    pub fn heightmap_path(&self) -> Option<PathBuf> {
        match &self.terrain.shape {
            TerrainShape::Heightmap { path, .. } => Some(self.resolve(path)),
            _ => None,
        }
    }

    /// The terrain's height grid (see [`TerrainSpec::build_height_grid`]), heightmap resolved against the scene's folder.
    pub fn build_height_grid(&self) -> Result<engine::geom::HeightGrid, SceneError> {
        self.terrain.build_height_grid(&self.base_dir)
    }

    /// The material with this name: a user definition first, then a library preset.
    pub fn material(&self, name: &str) -> Option<TerrainMaterial> {
        match self.materials.iter().find(|m| m.name == name) {
            Some(m) => Some(m.clone()),
            None => MaterialTable::with_presets().by_name(name).ok().cloned(),
        }
    }

    /// Every material name the scene may use, presets first.
    pub fn material_names(&self) -> Vec<String> {
        let mut names: Vec<String> = MaterialTable::with_presets()
            .materials()
            .iter()
            .map(|m| m.name.clone())
            .collect();
        for m in &self.materials {
            if !names.contains(&m.name) {
                names.push(m.name.clone());
            }
        }
        names
    }

    /// The material at `(x, z)` on the terrain.
    pub fn material_at(&self, x: f32, z: f32) -> Option<TerrainMaterial> {
        self.material(self.terrain.material_at(x, z))
    }

    /// Number of steps the scene runs for.
    pub fn steps(&self) -> u64 {
        self.sim.steps()
    }

    /// Checks every field; the first problem found is returned.
    pub fn validate(&self) -> Result<(), SceneError> {
        check::identifier("name", &self.name)?;
        check::count_at_most("materials", self.materials.len(), MAX_MATERIALS)?;
        check::count_at_most("grass", self.grass.len(), MAX_GRASS_PATCHES)?;
        self.terrain.validate()?;
        for (k, m) in self.materials.iter().enumerate() {
            let field = format!("materials[{k}]");
            material::validate_material(&field, m)?;
            if self.materials[..k].iter().any(|o| o.name == m.name) {
                return Err(SceneError::invalid(
                    format!("{field}.name"),
                    format!("material \"{}\" is defined twice", m.name),
                ));
            }
        }
        self.check_material("terrain.material", &self.terrain.material)?;
        for (k, r) in self.terrain.regions.iter().enumerate() {
            self.check_material(&format!("terrain.regions[{k}].material"), &r.material)?;
        }
        self.check_heightmap()?;
        // Grass and paths must lie on the sampled grid, which may stop short of
        // `size_x`/`size_z` by less than a cell.
        let size = self.terrain.extent();
        let mut blades = 0.0;
        for (k, g) in self.grass.iter().enumerate() {
            let field = format!("grass[{k}]");
            g.validate(&field, size)?;
            blades += g.blade_count();
            if blades > MAX_BLADES as f64 {
                return Err(SceneError::invalid(
                    format!("{field}.density"),
                    format!(
                        "the patches up to this one hold {blades:.0} blades, more than the limit {MAX_BLADES} over all patches"
                    ),
                ));
            }
        }
        check::count_at_most("props", self.props.len(), MAX_PROPS)?;
        for (k, p) in self.props.iter().enumerate() {
            let field = format!("props[{k}]");
            p.validate(&field, size)?;
            p.check_file(&field, &self.base_dir)?;
        }
        crowding::check_count(&self.characters)?;
        if self.characters.is_empty() {
            return Err(SceneError::invalid(
                "characters",
                "a scene needs at least one [[characters]] entry",
            ));
        }
        let mut seen = std::collections::HashSet::with_capacity(self.characters.len());
        for (k, c) in self.characters.iter().enumerate() {
            let field = format!("characters[{k}]");
            c.validate(&field, size, &self.base_dir, &self.rigs)?;
            if !seen.insert(c.name.as_str()) {
                return Err(SceneError::invalid(
                    format!("{field}.name"),
                    format!("character \"{}\" is defined twice", c.name),
                ));
            }
        }
        let names: Vec<&str> = self.characters.iter().map(|c| c.name.as_str()).collect();
        self.camera.validate(&names)?;
        self.sim.validate()?;
        self.render.validate()?;
        self.render.validate_delay(self.sim.dt)?;
        Ok(())
    }

    /// Problems that do not stop a run: characters whose spawn points
    /// overlap (closer than [`SPAWN_CLEARANCE_M`]), one line per pair.
    pub fn warnings(&self) -> Vec<String> {
        crowding::overlapping_spawns(&self.characters)
    }

    fn check_material(&self, field: &str, name: &str) -> Result<(), SceneError> {
        if self.material(name).is_some() {
            Ok(())
        } else {
            Err(SceneError::UnknownMaterial {
                field: field.to_owned(),
                name: name.to_owned(),
                known: self.material_names().join(", "),
            })
        }
    }

    fn check_heightmap(&self) -> Result<(), SceneError> {
        let Some(path) = self.heightmap_path() else {
            return Ok(());
        };
        let field = "terrain.shape.path".to_owned();
        if !path.exists() {
            return Err(SceneError::MissingFile { field, path });
        }
        if !path.is_file() {
            return Err(SceneError::BadFile {
                field,
                path,
                reason: "not a regular file".into(),
            });
        }
        // The size first, from the header: a huge image is refused before it is decoded.
        let bad = |reason: String| SceneError::BadFile {
            field: field.clone(),
            path: path.clone(),
            reason,
        };
        match png_header::png_size(&path) {
            None => return Err(bad("not a PNG file".into())),
            Some((w, h)) if w < 2 || h < 2 => {
                return Err(bad(format!(
                    "the heightmap is {w} x {h} pixels; at least 2 x 2 are needed"
                )));
            }
            Some((w, h)) if u64::from(w) * u64::from(h) > engine::geom::MAX_GRID_SAMPLES as u64 => {
                return Err(bad(format!(
                    "the heightmap is {w} x {h} pixels, more than the limit of {} pixels",
                    engine::geom::MAX_GRID_SAMPLES
                )));
            }
            Some(_) => {}
        }
        // Then the pixels: a corrupt or unsupported PNG is refused now, not when the run sets up.
        engine::asset::load_heightmap(&path, 1.0, 1.0).map_err(|e| bad(e.to_string()))?;
        Ok(())
    }
}
