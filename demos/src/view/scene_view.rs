//! [`SceneView`]: turns the world into frames.

use engine::ecs::{Entity, World};
use engine::geom::{GridRect, TriMesh};
use engine::render::{
    Camera, CameraFollow, FrameScene, GrassBlade, Lighting, MeshInstance, RenderError, Renderer,
    SampleColors, TerrainRenderer, TerrainStyle,
};
use glam::{Mat4, Vec3};
use image::RgbaImage;
use softwalk_systems::character::{Balance, CharacterBody, Pose, character_mesh};
use softwalk_systems::sim::{TerrainDirty, WalkerMetrics};
use softwalk_systems::terrain::Heightfield;
use softwalk_systems::vegetation::GrassPatch;
use thiserror::Error;

use super::overlays::draw_overlays;
use super::palette::TerrainPaint;
use crate::scene::{CameraMode, Scene};

/// Blue for a character with the balance controller, red without (the paper's Fig. 2).
const WITH_CONTROLLER: Vec3 = Vec3::new(0.16, 0.30, 0.75);
const WITHOUT_CONTROLLER: Vec3 = Vec3::new(0.75, 0.16, 0.12);

/// A frame could not be set up or drawn.
#[derive(Debug, Error)]
pub enum ViewError {
    /// The renderer refused a setting.
    #[error("renderer: {0}")]
    Render(#[from] RenderError),
    /// The world has no terrain to draw.
    #[error("the world has no terrain")]
    NoTerrain,
}

/// One character as drawn: its capsule mesh and colour.
struct Figure {
    entity: Entity,
    mesh: TriMesh,
    color: Vec3,
}

/// Draws a world as the scene's camera sees it: shaded terrain (re-meshed only
/// where the ground changed), characters, grass, and optional overlays.
pub struct SceneView {
    renderer: Renderer,
    camera: Camera,
    follow: Option<(CameraFollow, Entity)>,
    terrain: TerrainRenderer,
    paint: TerrainPaint,
    nx: usize,
    figures: Vec<Figure>,
    blades: Vec<GrassBlade>,
    lighting: Lighting,
    overlays: bool,
}

impl SceneView {
    /// A view of `world` (built from `scene`; `walkers` in scene order) drawing
    /// `width` x `height` frames with `threads` worker threads.
    pub fn new(
        scene: &Scene,
        world: &World,
        walkers: &[Entity],
        width: u32,
        height: u32,
        threads: usize,
    ) -> Result<SceneView, ViewError> {
        let mut terrains = world.query::<&Heightfield>();
        let hf = terrains.iter().next().ok_or(ViewError::NoTerrain)?;
        let grid = hf.grid();
        let paint = TerrainPaint::of(hf);
        let lighting = Lighting::default();
        let mut terrain = TerrainRenderer::new(grid, TerrainStyle::default())?;
        let camera = Camera::perspective(
            scene.camera.fov_deg.to_radians(),
            width,
            height,
            0.05,
            200.0,
        )?;
        let (camera, follow) = match &scene.camera.mode {
            CameraMode::Fixed { eye, target } => (
                camera.look_at(Vec3::from(*eye), Vec3::from(*target), Vec3::Y),
                None,
            ),
            CameraMode::Follow { character, offset } => {
                let index = character
                    .as_ref()
                    .and_then(|name| scene.characters.iter().position(|c| &c.name == name))
                    .unwrap_or(0);
                let follow = walkers.get(index).map(|&e| {
                    (
                        CameraFollow {
                            offset: Vec3::from(*offset),
                            smoothing: 0.4,
                        },
                        e,
                    )
                });
                (camera, follow)
            }
        };
        let figures = walkers
            .iter()
            .filter_map(|&entity| {
                let body = world.get::<CharacterBody>(entity).ok()?;
                let enabled = world
                    .get::<Balance>(entity)
                    .map(|b| b.enabled)
                    .unwrap_or(true);
                Some(Figure {
                    entity,
                    mesh: character_mesh(&body),
                    color: if enabled {
                        WITH_CONTROLLER
                    } else {
                        WITHOUT_CONTROLLER
                    },
                })
            })
            .collect();
        let colors = SampleColors {
            nx: grid.nx(),
            albedo: &paint.albedo,
            disturbed: &paint.disturbed,
        };
        terrain.update(grid, &colors, &lighting)?;
        let mut view = SceneView {
            renderer: Renderer::new(width, height)?.with_threads(threads)?,
            camera,
            follow,
            terrain,
            paint,
            nx: grid.nx(),
            figures,
            blades: Vec::new(),
            lighting,
            overlays: scene.render.overlays,
        };
        drop(terrains);
        if let Some((follow, entity)) = view.follow
            && let Some(target) = followed_point(world, entity)
        {
            follow.snap(&mut view.camera, target);
        }
        Ok(view)
    }

    /// Draws the world now; `dt` is the simulated time since the last frame (for the follow camera).
    pub fn render(&mut self, world: &World, dt: f32) -> Result<RgbaImage, ViewError> {
        if let Some((follow, entity)) = self.follow
            && let Some(target) = followed_point(world, entity)
        {
            follow.update(&mut self.camera, target, dt);
        }
        self.update_terrain(world)?;
        self.collect_blades(world);
        let poses: Vec<(usize, Vec<Mat4>)> = self
            .figures
            .iter()
            .enumerate()
            .filter_map(|(k, f)| {
                world
                    .get::<Pose>(f.entity)
                    .ok()
                    .map(|p| (k, p.part_transforms()))
            })
            .collect();
        let meshes: Vec<MeshInstance<'_>> = poses
            .iter()
            .map(|(k, parts)| {
                let f = &self.figures[*k];
                MeshInstance::new(&f.mesh, Mat4::IDENTITY, f.color).with_parts(parts)
            })
            .collect();
        let scene = FrameScene {
            terrain: Some(&self.terrain),
            meshes: &meshes,
            blades: &self.blades,
            lighting: self.lighting,
            shadows: true,
        };
        let mut image = self.renderer.render(&scene, &self.camera);
        if self.overlays {
            draw_overlays(world, &self.camera, &mut image);
        }
        Ok(image)
    }

    /// The camera of the last frame.
    pub fn camera(&self) -> &Camera {
        &self.camera
    }

    /// Re-meshes and re-lights only the terrain patches the simulation changed since the last frame.
    fn update_terrain(&mut self, world: &World) -> Result<(), ViewError> {
        let rect: GridRect = world
            .get_resource_mut::<TerrainDirty>()
            .map(|mut d| d.take())
            .unwrap_or_default();
        if rect.is_empty() {
            return Ok(());
        }
        let mut terrains = world.query::<&Heightfield>();
        let hf = terrains.iter().next().ok_or(ViewError::NoTerrain)?;
        self.paint.refresh(hf, rect);
        self.terrain.mark_dirty(rect);
        let colors = SampleColors {
            nx: self.nx,
            albedo: &self.paint.albedo,
            disturbed: &self.paint.disturbed,
        };
        self.terrain.update(hf.grid(), &colors, &self.lighting)?;
        Ok(())
    }

    fn collect_blades(&mut self, world: &World) {
        self.blades.clear();
        for patch in world.query::<&GrassPatch>().iter() {
            self.blades
                .extend(patch.blade_polylines().map(|b| GrassBlade {
                    root: b.points[0],
                    mid: b.points[1],
                    tip: b.points[2],
                    width: b.width,
                    color: Vec3::from(b.colour),
                }));
        }
    }
}

/// The point a follow camera aims at: the character's centre of mass.
fn followed_point(world: &World, entity: Entity) -> Option<Vec3> {
    world
        .get::<WalkerMetrics>(entity)
        .ok()
        .map(|m| m.character.com)
}
