//! [`WorldView`]: draws a world into frames.

use engine::ecs::{Entity, World};
use engine::geom::TriMesh;
use engine::render::{
    Camera, CameraFollow, FrameScene, GrassBlade, MeshInstance, RenderError, Renderer,
    SampleColors, TerrainRenderer,
};
use glam::{Mat4, Vec3};
use image::RgbaImage;
use thiserror::Error;

use super::camera_rig::CameraRig;
use super::overlay_layers::OverlayLayers;
use super::overlays::draw_overlays;
use super::palette::TerrainPaint;
use super::settings::ViewSettings;
use super::skinned_figure::{Detail, SkinnedFigure};
use crate::character::{
    Balance, CharacterBody, CharacterRig, ClipWalk, Gait, Pose, character_mesh,
};
use crate::sim::{Feet, GroundState, Props, WalkerMetrics};
use crate::terrain::Heightfield;
use crate::vegetation::GrassPatch;

/// Blue for a character with the balance controller, red without (the paper's Fig. 2).
const WITH_CONTROLLER: Vec3 = Vec3::new(0.16, 0.30, 0.75);
/// See [`WITH_CONTROLLER`].
const WITHOUT_CONTROLLER: Vec3 = Vec3::new(0.75, 0.16, 0.12);
/// Albedo of props (rocks, steps).
const PROP: Vec3 = Vec3::new(0.5, 0.48, 0.45);
/// Near and far planes of the camera, metres.
const NEAR_FAR: (f32, f32) = (0.05, 200.0);
/// Smoothing of the follow camera.
const FOLLOW_SMOOTHING: f32 = 0.4;
/// A skinned figure standing less tall than this on screen, in pixels, is
/// drawn with its coarse mesh (whose cubes then span at most 1.5 pixels).
const COARSE_BELOW_PX: f32 = 60.0;

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

/// One character as drawn: its mesh and colour, and whether the last
/// frame found its pose.
struct Figure {
    entity: Entity,
    body: FigureBody,
    color: Vec3,
    posed: bool,
}

/// What a character is drawn as.
enum FigureBody {
    /// The capsule mannequin: one capsule per bone, placed by the pose's
    /// part transforms (kept from frame to frame).
    Mannequin(TriMesh, Vec<Mat4>),
    /// A skinned model, re-skinned each frame from its rig's pose.
    Skinned(Box<SkinnedFigure>),
}

/// Draws a world as a [`CameraRig`] sees it: shaded terrain (re-meshed and
/// re-lit only where the ground changed), characters, props, grass, their
/// sun shadows, and optional overlays.
pub struct WorldView {
    renderer: Renderer,
    camera: Camera,
    follow: Option<(CameraFollow, Entity)>,
    terrain: TerrainRenderer,
    paint: TerrainPaint,
    figures: Vec<Figure>,
    props: Vec<TriMesh>,
    blades: Vec<GrassBlade>,
    settings: ViewSettings,
    layers: OverlayLayers,
}

impl WorldView {
    /// A view of `world` (its terrain, every character, prop and grass
    /// patch) through `rig`, drawing frames as `settings` say.
    pub fn new(
        world: &World,
        rig: CameraRig,
        settings: &ViewSettings,
    ) -> Result<WorldView, ViewError> {
        let (terrain, paint) = {
            let ground = world
                .get_resource::<GroundState>()
                .ok_or(ViewError::NoTerrain)?;
            let hf = ground.terrain();
            let paint = TerrainPaint::of(hf);
            let mut terrain = TerrainRenderer::new(hf.grid(), settings.terrain)?;
            terrain.update(hf.grid(), &colors(&paint, hf), &settings.lighting)?;
            (terrain, paint)
        };
        let camera = Camera::perspective(
            settings.fov_deg.to_radians(),
            settings.width,
            settings.height,
            NEAR_FAR.0,
            NEAR_FAR.1,
        )?;
        let (camera, follow) = match rig {
            CameraRig::Fixed { eye, target } => (camera.look_at(eye, target, Vec3::Y), None),
            CameraRig::Follow { character, offset } => {
                let follow = CameraFollow {
                    offset,
                    smoothing: FOLLOW_SMOOTHING,
                };
                (camera, Some((follow, character)))
            }
        };
        let mut view = WorldView {
            renderer: Renderer::new(settings.width, settings.height)?
                .with_threads(settings.threads)?,
            camera,
            follow,
            terrain,
            paint,
            figures: figures(world),
            props: world
                .get_resource::<Props>()
                .map(|p| p.0.clone())
                .unwrap_or_default(),
            blades: Vec::new(),
            settings: *settings,
            layers: OverlayLayers::ALL,
        };
        if let Some((follow, entity)) = view.follow
            && let Some(target) = followed_point(world, entity)
        {
            follow.snap(&mut view.camera, target);
        }
        Ok(view)
    }

    /// Draws the world now; `dt` is the simulated time since the last frame
    /// (for the follow camera).
    pub fn render(&mut self, world: &World, dt: f32) -> Result<RgbaImage, ViewError> {
        if let Some((follow, entity)) = self.follow
            && let Some(target) = followed_point(world, entity)
        {
            follow.update(&mut self.camera, target, dt);
        }
        self.update_terrain(world)?;
        self.collect_blades(world);
        for figure in &mut self.figures {
            figure.posed = figure.pose(world, &self.camera);
        }
        let figures = self.figures.iter().filter(|f| f.posed).map(|f| {
            let (mesh, parts): (&TriMesh, &[Mat4]) = match &f.body {
                FigureBody::Mannequin(mesh, parts) => (mesh, parts),
                FigureBody::Skinned(skinned) => (skinned.mesh(), &[]),
            };
            MeshInstance::new(mesh, Mat4::IDENTITY, f.color).with_parts(parts)
        });
        let props = (self.props.iter()).map(|m| MeshInstance::new(m, Mat4::IDENTITY, PROP));
        let meshes: Vec<MeshInstance<'_>> = figures.chain(props).collect();
        let scene = FrameScene {
            terrain: Some(&self.terrain),
            meshes: &meshes,
            blades: &self.blades,
            lighting: self.settings.lighting,
            shadows: self.settings.shadows,
        };
        let mut image = self.renderer.render(&scene, &self.camera);
        if self.settings.overlays {
            draw_overlays(world, &self.camera, &mut image, self.layers);
        }
        Ok(image)
    }

    /// The camera of the last frame.
    pub fn camera(&self) -> &Camera {
        &self.camera
    }

    /// Places the camera at `eye` looking at `target` from the next frame
    /// on (a following rig stops following): for cameras driven from outside,
    /// such as the live viewer's orbit.
    pub fn look_at(&mut self, eye: Vec3, target: Vec3) {
        self.follow = None;
        self.camera = self.camera.look_at(eye, target, Vec3::Y);
    }

    /// Turns the overlays (proxy, centre of mass, support, IK keys,
    /// platforms) on or off from the next frame on.
    pub fn set_overlays(&mut self, on: bool) {
        self.settings.overlays = on;
    }

    /// Chooses which overlay layers are drawn while overlays are on (all
    /// of them unless set), from the next frame on.
    pub fn set_overlay_layers(&mut self, layers: OverlayLayers) {
        self.layers = layers;
    }

    /// Re-meshes and re-lights only the terrain patches the simulation
    /// changed since the last frame.
    fn update_terrain(&mut self, world: &World) -> Result<(), ViewError> {
        let Some(mut ground) = world.get_resource_mut::<GroundState>() else {
            return Err(ViewError::NoTerrain);
        };
        let changed = ground.take_unseen();
        if changed.is_empty() {
            return Ok(());
        }
        let hf = ground.terrain();
        self.paint.refresh(hf, &changed);
        for &rect in &changed {
            self.terrain.mark_dirty(rect);
        }
        let colors = colors(&self.paint, hf);
        self.terrain
            .update(hf.grid(), &colors, &self.settings.lighting)?;
        Ok(())
    }

    /// The blades of every grass patch, as they are bent now.
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

/// The colour source of the terrain renderer: the paint over `hf`'s samples.
fn colors<'a>(paint: &'a TerrainPaint, hf: &Heightfield) -> SampleColors<'a> {
    SampleColors {
        nx: hf.grid().nx(),
        albedo: &paint.albedo,
        disturbed: &paint.disturbed,
    }
}

impl Figure {
    /// Poses the figure as the world has it now: the mannequin's part
    /// transforms, or the skinned model's mesh re-skinned in world space
    /// (coarse when `camera` sees it small). False when the entity has no
    /// pose.
    fn pose(&mut self, world: &World, camera: &Camera) -> bool {
        let Ok(pose) = world.get::<Pose>(self.entity) else {
            return false;
        };
        match &mut self.body {
            FigureBody::Mannequin(_, parts) => {
                pose.write_part_transforms(parts);
                true
            }
            FigureBody::Skinned(skinned) => {
                let (Ok(body), Ok(feet)) = (
                    world.get::<CharacterBody>(self.entity),
                    world.get::<Feet>(self.entity),
                ) else {
                    return false;
                };
                let clip = world.get::<ClipWalk>(self.entity).ok();
                let gait = world.get::<Gait>(self.entity).ok();
                let playing = clip.as_deref().zip(gait.as_deref());
                let detail = detail_seen(world, self.entity, body.desc.height, camera);
                skinned.update(&body, &pose, &feet.0, playing, detail);
                true
            }
        }
    }
}

/// Every character of the world, in entity order, with its mesh and colour:
/// skinned when it has a [`CharacterRig`], else the capsule mannequin.
fn figures(world: &World) -> Vec<Figure> {
    let mut figures: Vec<Figure> = world
        .query::<(
            Entity,
            &CharacterBody,
            Option<&Balance>,
            Option<&CharacterRig>,
        )>()
        .iter()
        .map(|(entity, body, balance, rig)| Figure {
            entity,
            body: match rig {
                Some(rig) => FigureBody::Skinned(Box::new(SkinnedFigure::new(rig.clone()))),
                None => FigureBody::Mannequin(character_mesh(body), Vec::new()),
            },
            posed: false,
            color: match balance.is_none_or(|b| b.enabled) {
                true => WITH_CONTROLLER,
                false => WITHOUT_CONTROLLER,
            },
        })
        .collect();
    figures.sort_by_key(|f| f.entity);
    figures
}

/// How much of the figure of `entity`, `height` metres tall, to draw as
/// `camera` sees it: coarse below [`COARSE_BELOW_PX`] on screen.
fn detail_seen(world: &World, entity: Entity, height: f32, camera: &Camera) -> Detail {
    let Some(centre) = followed_point(world, entity) else {
        return Detail::Full;
    };
    let distance = centre.distance(camera.eye).max(1e-3);
    match camera.focal_px() * height / distance < COARSE_BELOW_PX {
        true => Detail::Coarse,
        false => Detail::Full,
    }
}

/// The point a follow camera aims at: the character's centre of mass.
fn followed_point(world: &World, entity: Entity) -> Option<Vec3> {
    world
        .get::<WalkerMetrics>(entity)
        .ok()
        .map(|m| m.character.com)
}
