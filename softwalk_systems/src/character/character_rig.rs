//! [`CharacterRig`]: a rigged, skinned model (glTF) prepared to be driven by
//! the walking character: its legs, spine and arms found through a bone map,
//! its rest pose, its soles and the height of its hips.

use std::path::Path;
use std::sync::{Arc, OnceLock};

use engine::anim::gltf::load_gltf_from_slice;
use engine::anim::{
    BoneMap, BoneRole, LegChain, Model, RigChains, SkinnedMesh, SkinnedVertices, skin_matrices,
    skin_serial,
};
use engine::geom::Aabb;
use glam::{Mat3, Mat4, Quat, Vec3};

use super::model_error::ModelError;
use super::model_units::ModelUnits;

/// The default character, a CC0 MakeHuman body with a game-engine rig
/// (`assets/characters/human.glb`; see the README beside it), built in.
const HUMAN_GLB: &[u8] = include_bytes!("../../../assets/characters/human.glb");
/// The cubes of [`CharacterRig::coarse_mesh`], as a fraction of the
/// model's largest extent.
pub const COARSE_MESH_CELL: f32 = 1.0 / 40.0;
/// How far above the lowest rest-pose foot vertex a foot vertex still counts as sole, metres.
const SOLE_BAND: f32 = 0.012;
/// Smallest share of a vertex's weight on a foot's bones for it to be part of that sole.
const SOLE_WEIGHT: f32 = 0.5;
/// Widest rest pose, as a multiple of its height, still taken as standing
/// (a T-pose's arm span is about its height; a lying figure is several times it).
const MAX_WIDTH_PER_HEIGHT: f32 = 1.5;

/// An arm's joints the driver aims: shoulder (upper arm bone) and elbow
/// (forearm bone). An arm is driven only when its hand is mapped too.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ArmChain {
    /// The upper arm's joint.
    pub shoulder: usize,
    /// The forearm's joint.
    pub elbow: usize,
}

/// A loaded model with everything the driver needs, shared (cloning is cheap).
///
/// Rest-pose figures are in the model's bind space after its rest transforms,
/// in metres (a model in centimetres or millimetres is converted): Y up, the
/// soles on the lowest foot vertex.
#[derive(Debug, Clone)]
pub struct CharacterRig {
    data: Arc<RigData>,
}

#[derive(Debug)]
struct RigData {
    name: String,
    model: Model,
    units: ModelUnits,
    map: BoneMap,
    chains: RigChains,
    arms: [Option<ArmChain>; 2],
    rest_globals: Vec<Mat4>,
    rest_positions: Vec<Vec3>,
    ground: f32,
    hip_height: f32,
    height: f32,
    frame: Mat3,
    soles: [Vec<u32>; 2],
    sole_centres: [Vec3; 2],
    sole_lengths: [f32; 2],
    /// The mesh clustered for figures seen small, built on first use.
    coarse: OnceLock<SkinnedMesh>,
}

impl CharacterRig {
    /// The built-in human (parsed once, then shared).
    pub fn human() -> Result<CharacterRig, ModelError> {
        static HUMAN: OnceLock<CharacterRig> = OnceLock::new();
        if let Some(rig) = HUMAN.get() {
            return Ok(rig.clone());
        }
        let model = CharacterRig::parse_human()?;
        let map = BoneMap::detect(&model.skeleton);
        let rig = CharacterRig::new("human", model, map)?;
        Ok(HUMAN.get_or_init(|| rig).clone())
    }

    /// Loads a `.glb` or `.gltf` file, its bones named by `map` (or by the
    /// preset that matches most of them when `None`).
    pub fn load(path: &Path, map: Option<BoneMap>) -> Result<CharacterRig, ModelError> {
        let model = engine::anim::gltf::load_gltf(path).map_err(|source| ModelError::Load {
            path: path.to_path_buf(),
            source: Box::new(source),
        })?;
        let map = map.unwrap_or_else(|| BoneMap::detect(&model.skeleton));
        CharacterRig::new(&path.display().to_string(), model, map)
    }

    /// Parses the built-in human's bytes afresh (for load-time benchmarks).
    pub fn parse_human() -> Result<Model, ModelError> {
        let path = Path::new("assets/characters/human.glb");
        load_gltf_from_slice(HUMAN_GLB, path).map_err(|source| ModelError::Load {
            path: path.to_path_buf(),
            source: Box::new(source),
        })
    }

    /// Prepares `model`, its bones named by `map`: the legs, spine and
    /// head must be mapped (arms and toes are optional), the rest pose must
    /// stand (Y up, 0.5 to 3 m tall in metres, centimetres or millimetres;
    /// other units are converted to metres), each foot must have sole
    /// vertices, and the hips must stand above the soles.
    pub fn new(name: &str, model: Model, map: BoneMap) -> Result<CharacterRig, ModelError> {
        let chains = RigChains::find(&model.skeleton, &map)?;
        let RestModel {
            model,
            units,
            globals: rest_globals,
            vertices: rest_vertices,
        } = in_metres(model)?;
        let rest_positions: Vec<Vec3> = rest_globals.iter().map(|m| m.w_axis.truncate()).collect();
        let (soles, ground) = soles(&model, &chains, &rest_vertices.positions)?;
        let at = |j: usize| rest_positions[j];
        let hip_mid = 0.5 * (at(chains.left.hip) + at(chains.right.hip));
        let hip_height = hip_mid.y - ground;
        if hip_height.is_nan() || hip_height <= 1e-3 {
            return Err(ModelError::Shape {
                reason: format!(
                    "the hips stand {hip_height:.3} m above the soles; they must be above them"
                ),
            });
        }
        let height = (rest_vertices.positions.iter())
            .map(|p| p.y)
            .fold(f32::NEG_INFINITY, f32::max)
            - ground;
        let sole_centres = [0, 1].map(|k| sole_centre(&rest_vertices.positions, &soles[k]));
        let legs = [&chains.left, &chains.right];
        let feet = [0, 1].map(|k| FootRest {
            leg: legs[k],
            centre: sole_centres[k],
            sole: &soles[k],
        });
        let frame = rest_frame(&chains, &rest_positions, &rest_vertices.positions, &feet)?;
        let sole_lengths = [0, 1].map(|k| sole_length(&rest_vertices.positions, &soles[k], frame));
        let arm = |upper, lower, hand| {
            map.joint(hand)?;
            Some(ArmChain {
                shoulder: map.joint(upper)?,
                elbow: map.joint(lower)?,
            })
        };
        use BoneRole::*;
        let arms = [
            arm(UpperArmL, LowerArmL, HandL),
            arm(UpperArmR, LowerArmR, HandR),
        ];
        Ok(CharacterRig {
            data: Arc::new(RigData {
                name: name.to_string(),
                model,
                units,
                map,
                chains,
                arms,
                rest_globals,
                rest_positions,
                ground,
                hip_height,
                height,
                frame,
                soles,
                sole_centres,
                sole_lengths,
                coarse: OnceLock::new(),
            }),
        })
    }

    /// The model's mesh with its vertices clustered into cubes of
    /// [`COARSE_MESH_CELL`] of its largest extent (about a fifth of the
    /// default human's triangles), for a figure seen small: built on first
    /// use and shared by every clone of the rig.
    pub fn coarse_mesh(&self) -> &SkinnedMesh {
        self.data.coarse.get_or_init(|| {
            let full = &self.data.model.mesh;
            let bounds = Aabb::from_points(full.positions());
            full.clustered((bounds.max - bounds.min).max_element() * COARSE_MESH_CELL)
                .unwrap_or_else(|_| full.clone())
        })
    }

    /// Whether `other` is this same loaded rig (a clone of it).
    pub(crate) fn is_same(&self, other: &CharacterRig) -> bool {
        Arc::ptr_eq(&self.data, &other.data)
    }

    /// The name it was given (`human`, or the model's file).
    pub fn name(&self) -> &str {
        &self.data.name
    }

    /// The model: skeleton, skinned mesh and clips.
    pub fn model(&self) -> &Model {
        &self.data.model
    }

    /// The length unit the model's file uses (its figures here are in metres).
    pub fn units(&self) -> ModelUnits {
        self.data.units
    }

    /// The bone map its chains were found through.
    pub fn bone_map(&self) -> &BoneMap {
        &self.data.map
    }

    /// Its legs and spine.
    pub fn chains(&self) -> &RigChains {
        &self.data.chains
    }

    /// Its arms (left first), where the bone map names them.
    pub fn arms(&self) -> &[Option<ArmChain>; 2] {
        &self.data.arms
    }

    /// Each joint's global matrix in the rest pose.
    pub fn rest_globals(&self) -> &[Mat4] {
        &self.data.rest_globals
    }

    /// Each joint's position in the rest pose.
    pub fn rest_positions(&self) -> &[Vec3] {
        &self.data.rest_positions
    }

    /// Height of the lowest rest-pose foot vertex (the soles).
    pub fn ground(&self) -> f32 {
        self.data.ground
    }

    /// Height of the midpoint between the hip joints above the soles, rest pose.
    pub fn hip_height(&self) -> f32 {
        self.data.hip_height
    }

    /// Height of the highest rest-pose vertex above the soles.
    pub fn height(&self) -> f32 {
        self.data.height
    }

    /// The rest pose's facing frame: columns right, up (+Y), forward.
    pub fn rest_frame(&self) -> Mat3 {
        self.data.frame
    }

    /// The vertices of each sole (left first): foot vertices near the lowest foot vertex.
    pub fn sole_vertices(&self) -> &[Vec<u32>; 2] {
        &self.data.soles
    }

    /// The centre of each sole in the rest pose (left first), on the ground.
    pub fn sole_centres(&self) -> &[Vec3; 2] {
        &self.data.sole_centres
    }

    /// The length of each sole (left first) from heel to toe, rest pose.
    pub fn sole_lengths(&self) -> &[f32; 2] {
        &self.data.sole_lengths
    }
}

/// A model in metres with its rest pose: the joints' global matrices and
/// the mesh skinned by them.
struct RestModel {
    model: Model,
    units: ModelUnits,
    globals: Vec<Mat4>,
    vertices: SkinnedVertices,
}

impl RestModel {
    /// `model` (in `units`) in its rest pose.
    fn of(model: Model, units: ModelUnits) -> Result<RestModel, ModelError> {
        let globals = model.skeleton.rest_globals();
        let mut matrices = Vec::new();
        skin_matrices(&model.skeleton, &globals, &mut matrices);
        let mut vertices = SkinnedVertices::default();
        skin_serial(&model.mesh, &matrices, &mut vertices)?;
        Ok(RestModel {
            model,
            units,
            globals,
            vertices,
        })
    }
}

/// A model converted to metres, and the unit its file uses: told from the
/// rest pose's standing height, once it is known to stand rather than lie.
/// A model already in metres is skinned once; a converted one again, scaled.
fn in_metres(model: Model) -> Result<RestModel, ModelError> {
    let rest = RestModel::of(model, ModelUnits::Metres)?;
    let bounds = Aabb::from_points(&rest.vertices.positions);
    let extent = bounds.max - bounds.min;
    let (width, height) = (extent.x.max(extent.z), extent.y);
    if width > MAX_WIDTH_PER_HEIGHT * height {
        return Err(ModelError::LyingDown { width, height });
    }
    let units = ModelUnits::of_standing_height(height)?;
    match units {
        ModelUnits::Metres => Ok(rest),
        _ => RestModel::of(rest.model.scaled(units.metres())?, units),
    }
}

/// One foot in the rest pose: its leg, the centre of its sole and the sole's vertices.
struct FootRest<'a> {
    leg: &'a LegChain,
    centre: Vec3,
    sole: &'a [u32],
}

/// Right, up and forward of the rest pose: forward along the feet (see
/// [`foot_direction`]), right across it and the vertical.
fn rest_frame(
    chains: &RigChains,
    rest: &[Vec3],
    positions: &[Vec3],
    feet: &[FootRest; 2],
) -> Result<Mat3, ModelError> {
    let forward = feet
        .iter()
        .map(|foot| foot_direction(foot, rest, positions))
        .sum::<Vec3>()
        * Vec3::new(1.0, 0.0, 1.0);
    let Some(forward) = forward.try_normalize() else {
        return Err(ModelError::Shape {
            reason: "the toes are straight above or below the ankles; the feet point nowhere"
                .to_string(),
        });
    };
    let right = forward.cross(Vec3::Y);
    let left_side = (rest[chains.left.hip] - rest[chains.right.hip]).dot(right);
    if left_side >= 0.0 {
        return Err(ModelError::Shape {
            reason: "the left hip is on the right of the body (the bone map swaps the sides)"
                .to_string(),
        });
    }
    Ok(Mat3::from_cols(right, Vec3::Y, forward))
}

/// Where a foot points in the rest pose: from the ankle to the toe joint;
/// without a toe joint, along the sole's longest horizontal axis, towards
/// the side of the ankle the sole reaches further (the toes).
fn foot_direction(foot: &FootRest, rest: &[Vec3], positions: &[Vec3]) -> Vec3 {
    let ankle = rest[foot.leg.ankle];
    if let Some(toe) = foot.leg.toe {
        return rest[toe] - ankle;
    }
    let flat = |p: Vec3| glam::Vec2::new(p.x, p.z);
    let centre = flat(foot.centre);
    let (mut xx, mut xz, mut zz) = (0.0, 0.0, 0.0);
    for &v in foot.sole {
        let d = flat(positions[v as usize]) - centre;
        (xx, xz, zz) = (xx + d.x * d.x, xz + d.x * d.y, zz + d.y * d.y);
    }
    // The major eigenvector of the 2x2 covariance [[xx, xz], [xz, zz]].
    let angle = 0.5 * (2.0 * xz).atan2(xx - zz);
    let axis = glam::Vec2::from_angle(angle);
    let reach = |sign: f32| {
        (foot.sole.iter())
            .map(|&v| sign * (flat(positions[v as usize]) - flat(ankle)).dot(axis))
            .fold(0.0, f32::max)
    };
    let axis = if reach(1.0) >= reach(-1.0) {
        axis
    } else {
        -axis
    };
    Vec3::new(axis.x, 0.0, axis.y)
}

/// Each sole's vertices (left first) and the height of the lowest: the
/// foot vertices within [`SOLE_BAND`] of the lowest foot vertex. Refused
/// when a foot has no vertex there.
fn soles(
    model: &Model,
    chains: &RigChains,
    positions: &[Vec3],
) -> Result<([Vec<u32>; 2], f32), ModelError> {
    let side = |k: usize| ["left", "right"][k];
    let feet = [&chains.left, &chains.right].map(|leg| foot_vertices(model, leg));
    if let Some(k) = feet.iter().position(Vec::is_empty) {
        return Err(ModelError::Shape {
            reason: format!(
                "no vertex is weighted mostly to the {} foot (its ankle joint and below)",
                side(k)
            ),
        });
    }
    let ground = (feet.iter().flatten())
        .map(|&v| positions[v as usize].y)
        .fold(f32::INFINITY, f32::min);
    let soles = feet.map(|foot| {
        (foot.into_iter())
            .filter(|&v| positions[v as usize].y <= ground + SOLE_BAND)
            .collect::<Vec<u32>>()
    });
    if let Some(k) = soles.iter().position(Vec::is_empty) {
        return Err(ModelError::Shape {
            reason: format!(
                "no vertex of the {} foot lies within {SOLE_BAND} m of the soles",
                side(k)
            ),
        });
    }
    Ok((soles, ground))
}

/// The vertices weighted mostly to `leg`'s foot: its ankle joint and every
/// joint below it (toes).
fn foot_vertices(model: &Model, leg: &LegChain) -> Vec<u32> {
    let mesh = &model.mesh;
    let skeleton = &model.skeleton;
    let foot: Vec<bool> = (0..skeleton.len())
        .map(|j| skeleton.is_ancestor(leg.ankle, j))
        .collect();
    (mesh.joints().iter().zip(mesh.weights()))
        .enumerate()
        .filter(|(_, (js, ws))| {
            let on_foot: f32 = (js.iter().zip(ws.iter()))
                .filter(|(j, _)| foot.get(**j as usize).copied().unwrap_or(false))
                .map(|(_, w)| w)
                .sum();
            on_foot >= SOLE_WEIGHT
        })
        .map(|(k, _)| k as u32)
        .collect()
}

/// The middle of a sole's vertices' extent, at their lowest height.
fn sole_centre(positions: &[Vec3], sole: &[u32]) -> Vec3 {
    let bounds = (sole.iter()).fold(Aabb::EMPTY, |b, &v| b.grown_to(positions[v as usize]));
    let mid = 0.5 * (bounds.min + bounds.max);
    Vec3::new(mid.x, bounds.min.y, mid.z)
}

/// A sole's extent from heel to toe along the rest frame's forward.
fn sole_length(positions: &[Vec3], sole: &[u32], frame: Mat3) -> f32 {
    let along = sole
        .iter()
        .map(|&v| positions[v as usize].dot(frame.z_axis));
    let (lo, hi) = along.fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), x| {
        (lo.min(x), hi.max(x))
    });
    hi - lo
}

/// The rotation turning `from` (orthonormal columns) onto `to`.
pub(crate) fn frame_rotation(from: Mat3, to: Mat3) -> Quat {
    Quat::from_mat3(&(to * from.transpose())).normalize()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_built_in_human_stands_facing_forward_on_two_soles() {
        let rig = CharacterRig::human().unwrap();
        assert!((1.5..1.9).contains(&rig.height()), "{}", rig.height());
        assert!(rig.ground().abs() < 0.01);
        assert!(rig.rest_frame().z_axis.z > 0.99, "faces +Z");
        for (k, sole) in rig.sole_vertices().iter().enumerate() {
            assert!(sole.len() > 10, "sole {k} has {} vertices", sole.len());
            assert!((0.15..0.35).contains(&rig.sole_lengths()[k]));
        }
        // The left sole is on the character's left (+X when facing +Z).
        assert!(rig.sole_centres()[0].x > rig.sole_centres()[1].x);
        assert!(rig.arms().iter().all(Option::is_some));
    }

    #[test]
    fn a_rig_whose_map_swaps_the_legs_is_refused() {
        let model = CharacterRig::parse_human().unwrap();
        let s = &model.skeleton;
        let mut names: Vec<(BoneRole, String)> = BoneMap::detect(s)
            .pairs()
            .iter()
            .map(|&(r, j)| (r, s.joints()[j].name.clone()))
            .collect();
        for (_, name) in &mut names {
            *name = match name.strip_suffix("_l") {
                Some(stem) => format!("{stem}_r"),
                None => match name.strip_suffix("_r") {
                    Some(stem) => format!("{stem}_l"),
                    None => continue,
                },
            };
        }
        let map = BoneMap::from_names(s, &names);
        let e = CharacterRig::new("swapped", model, map).unwrap_err();
        assert!(e.to_string().contains("swaps the sides"), "{e}");
    }
}
