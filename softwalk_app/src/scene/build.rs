//! From a validated [`Scene`] to a ready-to-run simulation, through
//! `softwalk_systems::sim::SimBuilder`.

use engine::ecs::Entity;
use engine::geom::TriMesh;
use engine::schedule::App;
use softwalk_systems::character::{Balance, RigMasses};
use softwalk_systems::sim::{MassSource, SimBuilder, SimError, attach_rig_with};
use softwalk_systems::terrain::{Heightfield, MaterialTable};

use super::material::material_table;
use super::{CharacterAssets, Scene, SceneError};

/// Wraps a simulation refusal with the scene part it came from.
fn setup(part: impl Into<String>) -> impl FnOnce(SimError) -> SceneError {
    let part = part.into();
    move |source| SceneError::Setup { part, source }
}

/// Wraps a refusal to set up a spawned character's component with the scene part.
fn spawn_failed<E: std::fmt::Display>(part: String) -> impl FnOnce(E) -> SceneError {
    move |e| SceneError::Setup {
        part,
        source: SimError::System {
            system: "spawn",
            step: 0,
            message: e.to_string(),
        },
    }
}

impl Scene {
    /// The material table: the library presets (sand, soil, mud, snow), then
    /// the scene's `[[materials]]` (one named like a preset replaces it).
    pub fn material_table(&self) -> Result<MaterialTable, SceneError> {
        material_table(&self.materials)
    }

    /// The terrain with its material map, a heightmap resolved against the scene's folder.
    pub fn build_heightfield(&self) -> Result<Heightfield, SceneError> {
        self.terrain
            .build_heightfield(&self.base_dir, self.material_table()?)
    }

    /// The `[[props]]` meshes in world space, each on the ground of `terrain`
    /// under its `at` (errors name the entry and the file).
    pub fn prop_meshes(&self, terrain: &Heightfield) -> Result<Vec<TriMesh>, SceneError> {
        let grid = terrain.grid();
        let (lo, hi) = (grid.origin(), grid.origin() + grid.extent());
        (self.props.iter().enumerate())
            .map(|(k, p)| {
                let at = glam::Vec2::from(p.at).clamp(lo, hi);
                let ground_y = grid.height_at(at.x, at.y).unwrap_or(0.0);
                p.world_mesh(&format!("props[{k}]"), &self.base_dir, ground_y)
            })
            .collect()
    }

    /// The scene as a simulation: terrain, grass patches and characters in a
    /// built [`App`] stepped at `sim.dt`, and the characters' entities in scene
    /// order. Each character's `controller` switch is set on its `Balance`.
    /// Run it with `softwalk_systems::sim::run_steps`.
    ///
    /// ```
    /// use softwalk_app::scene::Scene;
    /// let mut scene = Scene::builtin("sand-flat").unwrap();
    /// scene.terrain.resolution = 101; // keep the doctest quick
    /// let (mut app, walkers) = scene.build_sim().unwrap();
    /// assert_eq!(walkers.len(), 1);
    /// softwalk_systems::sim::run_steps(&mut app, 10).unwrap();
    /// ```
    pub fn build_sim(&self) -> Result<(App, Vec<Entity>), SceneError> {
        let mut builder = SimBuilder::new(self.sim.dt).map_err(setup("sim.dt"))?;
        let heightfield = self.build_heightfield()?;
        let props = self.prop_meshes(&heightfield)?;
        builder.terrain(heightfield).map_err(setup("terrain"))?;
        for (k, mesh) in props.into_iter().enumerate() {
            builder.mesh(mesh).map_err(setup(format!("props[{k}]")))?;
        }
        for (k, patch) in self.grass.iter().enumerate() {
            builder
                .grass(patch.area(), patch.settings())
                .map_err(setup(format!("grass[{k}]")))?;
        }
        let assets = (self.characters.iter().enumerate())
            .map(|(k, c)| (self.rigs).character(&format!("characters[{k}]"), c, &self.base_dir))
            .collect::<Result<Vec<_>, _>>()?;
        let mut walkers = Vec::with_capacity(self.characters.len());
        for (k, c) in self.characters.iter().enumerate() {
            let part = format!("characters[{k}]");
            let path = c.path.walk_path().map_err(|source| SceneError::Setup {
                part: format!("{part}.path"),
                source: SimError::Character {
                    name: c.name.clone(),
                    source,
                },
            })?;
            let entity = builder
                .character(&c.name, c.desc(assets[k].clip.as_deref()), path)
                .map_err(setup(part))?;
            walkers.push(entity);
        }
        let mut app = builder.build().map_err(setup("sim"))?;
        self.attach_rigs(&mut app, &walkers, assets)?;
        for (k, (c, entity)) in self.characters.iter().zip(&walkers).enumerate() {
            let mut balance = app
                .world
                .get_mut::<Balance>(*entity)
                .map_err(spawn_failed(format!("characters[{k}].controller")))?;
            balance.enabled = c.controller;
        }
        Ok((app, walkers))
    }

    /// Gives each character drawn as a model its
    /// [`softwalk_systems::character::CharacterRig`], whose
    /// skinned volume sets its centre of mass and inertia (a mesh that is not
    /// closed keeps the capsules', with a warning), and, with a walk clip,
    /// the [`softwalk_systems::character::ClipWalk`] its upper body plays
    /// (each loaded once, through the scene's [`super::RigCache`], and
    /// weighed once per kind of body).
    fn attach_rigs(
        &self,
        app: &mut App,
        walkers: &[Entity],
        assets: Vec<CharacterAssets>,
    ) -> Result<(), SceneError> {
        let mut masses = RigMasses::default();
        for (k, ((c, &entity), assets)) in
            self.characters.iter().zip(walkers).zip(assets).enumerate()
        {
            let field = format!("characters[{k}]");
            let Some(rig) = assets.rig else { continue };
            if let Some(walk) = assets.walk {
                app.world
                    .insert(entity, (walk,))
                    .map_err(spawn_failed(format!("{field}.clip")))?;
            }
            let mass = attach_rig_with(&mut app.world, entity, rig, &mut masses)
                .map_err(spawn_failed(format!("{field}.model")))?;
            if let MassSource::Capsules { reason } = mass {
                eprintln!(
                    "warning: {field}.model `{}`: {reason}; the body keeps the capsules' \
                     centre of mass and inertia",
                    c.model
                );
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn controller_switch_reaches_the_balance_component() {
        let mut scene = Scene::builtin("controller-compare").unwrap();
        scene.terrain.resolution = 101;
        let (app, walkers) = scene.build_sim().unwrap();
        let enabled: Vec<bool> = walkers
            .iter()
            .map(|e| app.world.get::<Balance>(*e).unwrap().enabled)
            .collect();
        assert_eq!(enabled, [true, false]);
    }

    #[test]
    fn setup_failures_name_the_part() {
        let mut scene = Scene::builtin("sand-flat").unwrap();
        scene.terrain.resolution = 101;
        scene.characters[0].body.beta = 50.0;
        let Err(e) = scene.build_sim() else {
            panic!("a beta above the passive damping should be refused");
        };
        assert_eq!(e.field(), Some("characters[0]"), "{e}");
        assert!(e.to_string().starts_with("characters[0]: "), "{e}");
    }
}
