//! A character's centre of mass and inertia from its skinned mesh: the
//! model posed standing as the driver stands, its volume filled at the
//! uniform density that gives the character's mass.

use engine::anim::{SkinnedVertices, skin_serial};
use engine::geom::SolidMass;
use glam::{Mat3, Vec3};

use super::body::{BodyMass, CharacterBody};
use super::character_rig::CharacterRig;
use super::desc::CharacterDesc;
use super::model_error::ModelError;
use super::pose::Pose;
use super::rig_pose::RigPose;
use super::skeleton::Joint;
use crate::foot::FootState;

impl BodyMass {
    /// The mass properties of `rig` skinned in the driver's standing `pose`
    /// and `feet` (as [`super::Character::new`] poses it), at the uniform
    /// density that gives `body` its mass. The centre of mass height is
    /// measured from the pelvis down, as if the pelvis stood at the body's
    /// rest hip height.
    ///
    /// Fails when the mesh encloses no volume, for example a single sheet.
    pub fn of_rig(
        rig: &CharacterRig,
        body: &CharacterBody,
        pose: &Pose,
        feet: &[FootState; 2],
    ) -> Result<BodyMass, ModelError> {
        let posed = RigPose::drive(rig, body, pose, feet);
        let (mut globals, mut matrices) = (Vec::new(), Vec::new());
        posed.skin_matrices(rig, &mut globals, &mut matrices);
        let mut skinned = SkinnedVertices::default();
        skin_serial(&rig.model().mesh, &matrices, &mut skinned)?;
        // Heights are measured from where the soles would be with the pelvis
        // at the body's rest hip height, as the body's own figures are: the
        // driver stands with its knees slightly bent.
        let pelvis = pose.joint(Joint::Pelvis);
        let origin = pelvis - Vec3::Y * body.hip_height;
        let to_body = body_frame(pose);
        let local: Vec<Vec3> = skinned
            .positions
            .iter()
            .map(|&p| to_body * (p - origin))
            .collect();
        let solid = SolidMass::of_surface(&local, rig.model().mesh.indices()).ok_or_else(|| {
            ModelError::Shape {
                reason: "the skinned mesh encloses no volume, so it has no mass to balance"
                    .to_string(),
            }
        })?;
        if solid.leak > MAX_LEAK {
            return Err(ModelError::Shape {
                reason: format!(
                    "the skinned mesh is not closed (its volume changes by {:.0} % with the \
                     point it is measured from), so its volume is not the body's",
                    100.0 * solid.leak
                ),
            });
        }
        let density = body.desc.mass / solid.volume;
        Ok(BodyMass {
            com_height: solid.centroid.y,
            inertia: solid.inertia * density,
        })
    }
}

/// Mass properties computed once per rig and body description while a
/// scene is set up: a crowd of many characters wearing a few rigs skins
/// each rig once per kind of body, not once per character. The first
/// character of each kind stands for the rest (the figures do not depend on
/// where a character stands).
#[derive(Debug, Default)]
pub struct RigMasses {
    known: Vec<KnownMass>,
}

/// The mass properties of one rig worn by one kind of body, or why its mesh
/// gives none.
#[derive(Debug)]
struct KnownMass {
    rig: CharacterRig,
    desc: CharacterDesc,
    mass: Result<BodyMass, String>,
}

impl RigMasses {
    /// [`BodyMass::of_rig`], computed only for the first character of each
    /// rig and body description asked for.
    pub fn of_rig(
        &mut self,
        rig: &CharacterRig,
        body: &CharacterBody,
        pose: &Pose,
        feet: &[FootState; 2],
    ) -> Result<BodyMass, ModelError> {
        let same = |k: &&KnownMass| k.rig.is_same(rig) && k.desc == body.desc;
        if let Some(known) = self.known.iter().find(same) {
            return known
                .mass
                .clone()
                .map_err(|reason| ModelError::Shape { reason });
        }
        let mass = BodyMass::of_rig(rig, body, pose, feet);
        let kept = match &mass {
            Ok(mass) => Ok(*mass),
            Err(ModelError::Shape { reason }) => Err(reason.clone()),
            Err(_) => return mass,
        };
        self.known.push(KnownMass {
            rig: rig.clone(),
            desc: body.desc,
            mass: kept,
        });
        mass
    }
}

/// Largest [`SolidMass::leak`] of a mesh whose volume is taken as the body's:
/// small openings (eyes, a mouth) change it by far less.
pub const MAX_LEAK: f32 = 0.02;

/// The rotation from world axes to the body frame of `pose`: X right, Y up,
/// Z forward.
fn body_frame(pose: &Pose) -> Mat3 {
    let forward = (pose.forward * Vec3::new(1.0, 0.0, 1.0)).normalize_or(Vec3::Z);
    let right = forward.cross(Vec3::Y);
    Mat3::from_cols(right, Vec3::Y, forward).transpose()
}

/// The built-in human with only the triangles of its front: an open shell.
#[cfg(test)]
pub(crate) fn open_shell() -> CharacterRig {
    let rig = CharacterRig::human().unwrap();
    let model = rig.model();
    let mesh = &model.mesh;
    let front: Vec<u32> = mesh
        .indices()
        .chunks(3)
        .filter(|t| {
            t.iter()
                .map(|&i| mesh.positions()[i as usize].z)
                .sum::<f32>()
                > 0.0
        })
        .flatten()
        .copied()
        .collect();
    let shell = engine::anim::SkinnedMesh::new(
        mesh.positions().to_vec(),
        mesh.normals().to_vec(),
        front,
        mesh.joints().to_vec(),
        mesh.weights().to_vec(),
        mesh.joint_count(),
    )
    .unwrap();
    let open = engine::anim::Model {
        skeleton: model.skeleton.clone(),
        mesh: shell,
        clips: Vec::new(),
    };
    CharacterRig::new("shell", open, rig.bone_map().clone()).unwrap()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::character::{Character, CharacterDesc, WalkPath};
    use crate::ground::FlatGround;

    /// An adult standing away from [`standing`]'s spot, facing another way.
    fn adult_elsewhere() -> Character {
        let path = WalkPath::straight(Vec3::new(-4.0, 0.0, 7.0), Vec3::Z, 5.0).unwrap();
        Character::new(CharacterDesc::adult(), &path, &FlatGround(0.0)).unwrap()
    }

    fn standing(desc: CharacterDesc) -> Character {
        let path = WalkPath::straight(Vec3::new(1.0, 0.3, -2.0), Vec3::X, 5.0).unwrap();
        Character::new(desc, &path, &FlatGround(0.3)).unwrap()
    }

    #[test]
    fn the_human_has_a_human_centre_of_mass_and_inertia() {
        let rig = CharacterRig::human().unwrap();
        let c = standing(CharacterDesc::adult());
        let m = BodyMass::of_rig(&rig, &c.body, &c.pose, &c.feet).unwrap();
        let mesh = &rig.model().mesh;
        let leak = SolidMass::of_surface(mesh.positions(), mesh.indices())
            .unwrap()
            .leak;
        assert!(leak < 0.1 * MAX_LEAK, "the human leaks {leak}");
        // A standing adult's centre of mass is at 53–57 % of the standing height;
        // the rig is scaled by hip height, so compare with the rig's own height.
        let height = rig.height() * c.body.hip_height / rig.hip_height();
        let ratio = m.com_height / height;
        assert!(
            (0.52..0.58).contains(&ratio),
            "COM at {ratio:.3} of the height"
        );
        // Pitch and roll inertia of order 10 kg·m², yaw about a tenth of it.
        let (pitch, yaw, roll) = (m.inertia.x_axis.x, m.inertia.y_axis.y, m.inertia.z_axis.z);
        assert!((7.0..16.0).contains(&pitch), "pitch {pitch}");
        assert!((7.0..16.0).contains(&roll), "roll {roll}");
        assert!((0.5..3.0).contains(&yaw), "yaw {yaw}");
        // Left and right mirror each other: no right-up or right-forward product.
        assert!(m.inertia.x_axis.y.abs() < 0.05 * pitch && m.inertia.x_axis.z.abs() < 0.05 * pitch);
    }

    #[test]
    fn the_mass_properties_do_not_depend_on_where_the_character_stands() {
        let rig = CharacterRig::human().unwrap();
        let (here, there) = (standing(CharacterDesc::adult()), adult_elsewhere());
        let a = BodyMass::of_rig(&rig, &here.body, &here.pose, &here.feet).unwrap();
        let b = BodyMass::of_rig(&rig, &there.body, &there.pose, &there.feet).unwrap();
        assert!((a.com_height - b.com_height).abs() < 1e-3);
        assert!((a.inertia - b.inertia).abs_diff_eq(Mat3::ZERO, 0.05));
    }

    #[test]
    fn an_open_mesh_is_refused_as_a_mass() {
        let rig = open_shell();
        let c = standing(CharacterDesc::adult());
        let e = BodyMass::of_rig(&rig, &c.body, &c.pose, &c.feet).unwrap_err();
        assert!(e.to_string().contains("not closed"), "{e}");
    }

    #[test]
    fn a_rig_and_body_are_weighed_once_and_shared() {
        let rig = CharacterRig::human().unwrap();
        let (adult, elsewhere) = (standing(CharacterDesc::adult()), adult_elsewhere());
        let child = standing(CharacterDesc::child());
        let mut masses = RigMasses::default();
        let first = masses
            .of_rig(&rig, &adult.body, &adult.pose, &adult.feet)
            .unwrap();
        assert_eq!(
            first,
            BodyMass::of_rig(&rig, &adult.body, &adult.pose, &adult.feet).unwrap()
        );
        // The same rig and body elsewhere: the first one's figures.
        let again = masses.of_rig(&rig, &elsewhere.body, &elsewhere.pose, &elsewhere.feet);
        assert_eq!(again.unwrap(), first);
        // Another body, or another rig of the same mesh: weighed on its own.
        let small = masses.of_rig(&rig, &child.body, &child.pose, &child.feet);
        assert!(small.unwrap().com_height < first.com_height);
        let reloaded = CharacterRig::new("copy", rig.model().clone(), rig.bone_map().clone());
        let copy = reloaded.unwrap();
        masses
            .of_rig(&copy, &adult.body, &adult.pose, &adult.feet)
            .unwrap();
        assert_eq!(masses.known.len(), 3);
        // An open mesh is refused each time it is asked for.
        let shell = open_shell();
        for _ in 0..2 {
            let e = masses.of_rig(&shell, &adult.body, &adult.pose, &adult.feet);
            assert!(e.unwrap_err().to_string().contains("not closed"));
        }
        assert_eq!(masses.known.len(), 4);
    }

    #[test]
    fn a_taller_heavier_body_has_more_inertia() {
        let rig = CharacterRig::human().unwrap();
        let small = standing(CharacterDesc::child());
        let tall = standing(CharacterDesc::new(1.9, 85.0));
        let s = BodyMass::of_rig(&rig, &small.body, &small.pose, &small.feet).unwrap();
        let t = BodyMass::of_rig(&rig, &tall.body, &tall.pose, &tall.feet).unwrap();
        assert!(t.com_height > 1.5 * s.com_height);
        assert!(t.inertia.x_axis.x > 10.0 * s.inertia.x_axis.x);
    }
}
