//! Giving a simulated character a rigged model: the model is drawn in its
//! place, and its skinned mesh's volume gives the body its centre of mass and
//! inertia, so the balance of eq. 1 acts on the body the user sees.

use engine::ecs::{Entity, World};

use super::components::{CharacterName, Feet};
use super::error::SimError;
use crate::character::{CharacterBody, CharacterRig, ModelError, Pose, RigMasses, RigidProxy};

/// Where an attached character's mass properties come from.
#[derive(Debug, Clone, PartialEq)]
pub enum MassSource {
    /// The skinned mesh's volume.
    Mesh,
    /// The capsule segments, because the mesh's volume is not a body's
    /// (for example an open mesh); the reason says why.
    Capsules {
        /// Why the mesh was not used.
        reason: String,
    },
}

/// Attaches `rig` to the character `entity` and gives its body and rigid
/// proxy the mass properties of the rig's skinned mesh, posed as the
/// character stands now (see [`crate::character::BodyMass::of_rig`]). A mesh that encloses no
/// body (open, or flat) keeps the capsules' mass properties, and the returned
/// [`MassSource`] says so.
///
/// Call it before the first step: the proxy's tilt state is kept, but the
/// body's centre of mass moves.
pub fn attach_rig(
    world: &mut World,
    entity: Entity,
    rig: CharacterRig,
) -> Result<MassSource, SimError> {
    attach_rig_with(world, entity, rig, &mut RigMasses::default())
}

/// [`attach_rig`] taking the mass properties from `masses` when a character
/// with the same rig and body description was weighed before: attaching a
/// crowd's rigs through one [`RigMasses`] skins each rig once per kind of body.
pub fn attach_rig_with(
    world: &mut World,
    entity: Entity,
    rig: CharacterRig,
    masses: &mut RigMasses,
) -> Result<MassSource, SimError> {
    let failed = |message: String| SimError::System {
        system: "attach_rig",
        step: 0,
        message,
    };
    let mass = {
        let body = world
            .get::<CharacterBody>(entity)
            .map_err(|e| failed(e.to_string()))?;
        let pose = world
            .get::<Pose>(entity)
            .map_err(|e| failed(e.to_string()))?;
        let feet = world
            .get::<Feet>(entity)
            .map_err(|e| failed(e.to_string()))?;
        masses.of_rig(&rig, &body, &pose, &feet.0)
    };
    let source = match mass {
        Ok(mass) => {
            let mut body = world
                .get_mut::<CharacterBody>(entity)
                .map_err(|e| failed(e.to_string()))?;
            body.set_mass_properties(mass);
            let mut proxy = world
                .get_mut::<RigidProxy>(entity)
                .map_err(|e| failed(e.to_string()))?;
            proxy.take_body_mass(&body);
            MassSource::Mesh
        }
        Err(ModelError::Shape { reason }) => MassSource::Capsules { reason },
        Err(source) => {
            let name = world
                .get::<CharacterName>(entity)
                .map(|n| n.0.clone())
                .unwrap_or_default();
            return Err(SimError::Model {
                name,
                source: Box::new(source),
            });
        }
    };
    world
        .insert(entity, (rig,))
        .map_err(|e| failed(e.to_string()))?;
    Ok(source)
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::*;
    use crate::character::rig_mass::open_shell;
    use crate::character::{CharacterDesc, WalkPath};
    use crate::sim::SimBuilder;
    use crate::terrain::generate::{GridSpec, flat};
    use crate::terrain::{Heightfield, MaterialTable};

    /// A sand field with one adult walker, built.
    fn one_walker() -> (engine::schedule::App, Entity) {
        let table = MaterialTable::with_presets();
        let sand = table.id("sand").unwrap();
        let grid = flat(GridSpec::square(4.0, 81), 0.0).unwrap();
        let mut builder = SimBuilder::new(1.0 / 60.0).unwrap();
        builder
            .terrain(Heightfield::from_grid(grid, table, sand).unwrap())
            .unwrap();
        let path = WalkPath::straight(Vec3::new(1.0, 0.0, 1.0), Vec3::Z, 3.0).unwrap();
        let walker = builder
            .character("w", CharacterDesc::adult(), path)
            .unwrap();
        (builder.build().unwrap(), walker)
    }

    #[test]
    fn the_rig_sets_the_body_and_proxy_mass_properties() {
        let (mut app, walker) = one_walker();
        let capsules = app.world.get::<CharacterBody>(walker).unwrap().com_height;
        let rig = CharacterRig::human().unwrap();
        assert_eq!(
            attach_rig(&mut app.world, walker, rig).unwrap(),
            MassSource::Mesh
        );
        let body = app.world.get::<CharacterBody>(walker).unwrap();
        let proxy = app.world.get::<RigidProxy>(walker).unwrap();
        assert_ne!(body.com_height, capsules);
        let expect = proxy.inertia.x_axis.x + proxy.mass * body.com_height * body.com_height;
        assert!((proxy.pitch_inertia - expect).abs() < 1e-3);
        assert!(app.world.get::<CharacterRig>(walker).is_ok());
    }

    #[test]
    fn an_open_mesh_keeps_the_capsules_mass() {
        let (mut app, walker) = one_walker();
        let before = app.world.get::<CharacterBody>(walker).unwrap().com_height;
        let source = attach_rig(&mut app.world, walker, open_shell()).unwrap();
        assert!(matches!(source, MassSource::Capsules { .. }), "{source:?}");
        assert_eq!(
            app.world.get::<CharacterBody>(walker).unwrap().com_height,
            before
        );
        assert!(app.world.get::<CharacterRig>(walker).is_ok());
    }
}
