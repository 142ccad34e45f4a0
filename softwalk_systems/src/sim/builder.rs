//! Building a simulation: terrain, meshes, grass and characters into an [`App`].

use engine::ecs::Entity;
use engine::geom::TriMesh;
use engine::schedule::App;

use super::components::{
    BaseGains, CharacterName, Feet, FootPrints, Platforms, Props, SystemFault, WalkerMetrics,
};
use super::error::SimError;
use super::ground_state::GroundState;
use super::ground_view::SceneGround;
use super::pipeline::add_pipeline;
use super::sole_ground::under_soles;
use super::standing_prints::press_standing_feet;
use super::timing::SystemTimings;
use crate::character::{Character, CharacterDesc, WalkPath};
use crate::foot::Side;
use crate::terrain::{Heightfield, ScratchPool, SettleScratch, SmoothScratch};
use crate::vegetation::{GrassPatch, GrassSettings, VegetationFriction, VirtualPlatform, XzRect};

/// Builds a simulation step by step: terrain first, then meshes, grass and characters
/// (which are placed on what is already there), then [`SimBuilder::build`].
pub struct SimBuilder {
    app: App,
}

impl SimBuilder {
    /// An empty simulation stepped at `dt` seconds, with the pipeline's resources.
    pub fn new(dt: f32) -> Result<Self, SimError> {
        let mut app = App::new(dt)?;
        let world = &mut app.world;
        world.insert_resource(SystemFault::default());
        world.insert_resource(Props::default());
        world.insert_resource(SystemTimings::default());
        world.insert_resource(ScratchPool::<SmoothScratch>::default());
        world.insert_resource(ScratchPool::<SettleScratch>::default());
        world.insert_resource(VegetationFriction::default());
        add_pipeline(&mut app.schedule);
        Ok(SimBuilder { app })
    }

    /// Sets the terrain (one per simulation, a [`GroundState`] resource) and
    /// builds its BVH; a second call replaces it and keeps the meshes.
    pub fn terrain(&mut self, heightfield: Heightfield) -> Result<(), SimError> {
        let world = &mut self.app.world;
        if let Some(mut ground) = world.get_resource_mut::<GroundState>() {
            ground.set_terrain(heightfield);
            return Ok(());
        }
        world.insert_resource(GroundState::new(heightfield));
        Ok(())
    }

    /// Adds a static mesh (rocks, steps) the feet can stand on; after the terrain.
    pub fn mesh(&mut self, mesh: TriMesh) -> Result<(), SimError> {
        self.app
            .world
            .get_resource_mut::<GroundState>()
            .ok_or(SimError::NoTerrain)?
            .add_mesh(mesh.clone())?;
        self.app.world.resource_mut::<Props>().0.push(mesh);
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
            sole_ground: under_soles(
                self.app.world.get_resource::<GroundState>().as_deref(),
                &c.metrics.soles,
            ),
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
    fn with_ground<T>(&self, f: impl FnOnce(&SceneGround<'_>) -> T) -> T {
        let world = &self.app.world;
        match world.get_resource::<GroundState>() {
            Some(ground) => f(&ground.view()),
            None => f(&SceneGround {
                scene: &engine::geom::RayScene::new(),
                terrain: None,
            }),
        }
    }

    /// The app, its schedule resolved, every character standing in the
    /// prints its soles pressed (`standing_prints::press_standing_feet`). Fails without a
    /// terrain.
    pub fn build(mut self) -> Result<App, SimError> {
        if !self.app.world.contains_resource::<GroundState>() {
            return Err(SimError::NoTerrain);
        }
        self.app.schedule.build()?;
        press_standing_feet(&mut self.app.world)?;
        Ok(self.app)
    }
}
