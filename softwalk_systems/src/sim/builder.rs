//! Building a simulation: terrain, meshes, grass and characters into an [`App`].

use engine::ecs::Entity;
use engine::geom::{RayScene, TriMesh};
use engine::schedule::App;

use super::components::{
    BaseGains, CharacterName, Feet, FootPrints, Platforms, Props, SystemFault, TerrainDirty,
    TerrainVolume, WalkerMetrics,
};
use super::error::SimError;
use super::ground_view::SceneGround;
use super::pipeline::add_pipeline;
use super::sole_ground::SoleGround;
use super::systems_terrain::TerrainWindows;
use super::timing::SystemTimings;
use crate::character::{Character, CharacterDesc, WalkPath};
use crate::foot::{FootSole, Side};
use crate::terrain::Heightfield;
use crate::vegetation::{GrassPatch, GrassSettings, VegetationFriction, VirtualPlatform, XzRect};

/// Builds a simulation step by step: terrain first, then meshes, grass and characters
/// (which are placed on what is already there), then [`SimBuilder::build`].
pub struct SimBuilder {
    app: App,
    terrain: Option<Entity>,
}

impl SimBuilder {
    /// An empty simulation stepped at `dt` seconds, with the pipeline's resources.
    pub fn new(dt: f32) -> Result<Self, SimError> {
        let mut app = App::new(dt)?;
        let world = &mut app.world;
        world.insert_resource(RayScene::new());
        world.insert_resource(SystemFault::default());
        world.insert_resource(TerrainWindows::default());
        world.insert_resource(TerrainDirty::default());
        world.insert_resource(Props::default());
        world.insert_resource(TerrainVolume(0.0));
        world.insert_resource(SystemTimings::default());
        world.insert_resource(VegetationFriction::default());
        add_pipeline(&mut app.schedule);
        Ok(SimBuilder { app, terrain: None })
    }

    /// Sets the terrain (one per simulation) and builds its BVH.
    pub fn terrain(&mut self, heightfield: Heightfield) -> Result<Entity, SimError> {
        let world = &mut self.app.world;
        if let Some(old) = self.terrain.take() {
            let _ = world.despawn(old);
        }
        world
            .resource_mut::<RayScene>()
            .set_grid(heightfield.grid());
        world.resource_mut::<TerrainVolume>().0 = heightfield.grid().volume();
        let entity = world.spawn((heightfield,));
        self.terrain = Some(entity);
        Ok(entity)
    }

    /// Adds a static mesh (rocks, steps) the feet can stand on.
    pub fn mesh(&mut self, mesh: TriMesh) -> Result<(), SimError> {
        let world = &mut self.app.world;
        world.resource_mut::<RayScene>().add_mesh(mesh.clone())?;
        world.resource_mut::<Props>().0.push(mesh);
        Ok(())
    }

    /// Adds a grass patch over `area`, its blades rooted on the ground.
    pub fn grass(&mut self, area: XzRect, settings: GrassSettings) -> Result<Entity, SimError> {
        let index = self.app.world.query::<&GrassPatch>().iter().count();
        let patch = self
            .with_ground(|ground| GrassPatch::new(area, settings, ground))
            .map_err(|source| SimError::Vegetation { index, source })?;
        Ok(self.app.world.spawn((patch,)))
    }

    /// Adds a character standing at the start of `path`.
    pub fn character(
        &mut self,
        name: &str,
        desc: CharacterDesc,
        path: WalkPath,
    ) -> Result<Entity, SimError> {
        let c = self
            .with_ground(|ground| Character::new(desc, &path, ground))
            .map_err(|source| SimError::Character {
                name: name.to_string(),
                source,
            })?;
        let metrics = WalkerMetrics {
            character: c.metrics,
            platform_y: [None, None],
            grass_height: 0.0,
            ground_y: c.rays.body.point.y,
            velocity: glam::Vec3::ZERO,
            sole_ground: self.ground_under(&c.metrics.soles),
            path_distance: c.gait.distance,
            path_finished: path.is_finished(c.gait.distance),
        };
        let world = &mut self.app.world;
        let entity = world.spawn((
            CharacterName(name.to_string()),
            c.body,
            c.gait,
            c.modifiers,
            c.rays,
            c.balance,
            c.proxy,
            c.ik,
            c.pose,
            Feet(c.feet),
            path,
            BaseGains {
                alpha: desc.alpha,
                beta: desc.beta,
            },
        ));
        world
            .insert(
                entity,
                (
                    Platforms(Side::BOTH.map(VirtualPlatform::new)),
                    FootPrints::default(),
                    metrics,
                ),
            )
            .map_err(|e| SimError::System {
                system: "spawn",
                step: 0,
                message: e.to_string(),
            })?;
        Ok(entity)
    }

    /// Runs `f` with the scene's current ground (terrain and meshes).
    /// The terrain heights under each sole (the soles' own heights without a terrain).
    fn ground_under(&self, soles: &[FootSole; 2]) -> [SoleGround; 2] {
        let mut terrains = self.app.world.query::<&Heightfield>();
        let grid = terrains.iter().next().map(|t| t.grid());
        soles.map(|sole| match grid {
            Some(grid) => SoleGround::under(grid, &sole),
            None => SoleGround::flush(&sole),
        })
    }

    fn with_ground<T>(&self, f: impl FnOnce(&SceneGround<'_>) -> T) -> T {
        let world = &self.app.world;
        let scene = world.resource::<RayScene>();
        let mut terrains = world.query::<&Heightfield>();
        let terrain = terrains.iter().next();
        f(&SceneGround {
            scene: &scene,
            terrain,
        })
    }

    /// The app, its schedule resolved. Fails without a terrain.
    pub fn build(mut self) -> Result<App, SimError> {
        if self.terrain.is_none() {
            return Err(SimError::NoTerrain);
        }
        self.app.schedule.build()?;
        Ok(self.app)
    }
}
