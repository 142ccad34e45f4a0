//! Giving a simulated character a rigged model: the model is drawn in its
//! place, and its skinned mesh's volume gives the body its centre of mass and
//! inertia, so the balance of eq. 1 acts on the body the user sees.

use engine::ecs::{Entity, World};

use super::components::{CharacterName, Feet};
use super::error::SimError;
use crate::character::{BodyMass, CharacterBody, CharacterRig, Pose, RigidProxy};

/// Attaches `rig` to the character `entity` and gives its body and rigid
/// proxy the mass properties of the rig's skinned mesh, posed as the
/// character stands now (see [`BodyMass::of_rig`]).
///
/// Call it before the first step: the proxy's tilt state is kept, but the
/// body's centre of mass moves.
pub fn attach_rig(world: &mut World, entity: Entity, rig: CharacterRig) -> Result<(), SimError> {
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
        BodyMass::of_rig(&rig, &body, &pose, &feet.0).map_err(|source| {
            let name = world
                .get::<CharacterName>(entity)
                .map(|n| n.0.clone())
                .unwrap_or_default();
            SimError::Model {
                name,
                source: Box::new(source),
            }
        })?
    };
    {
        let mut body = world
            .get_mut::<CharacterBody>(entity)
            .map_err(|e| failed(e.to_string()))?;
        body.set_mass_properties(mass);
        let mut proxy = world
            .get_mut::<RigidProxy>(entity)
            .map_err(|e| failed(e.to_string()))?;
        proxy.take_body_mass(&body);
    }
    world
        .insert(entity, (rig,))
        .map_err(|e| failed(e.to_string()))
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::*;
    use crate::character::{CharacterDesc, WalkPath};
    use crate::sim::SimBuilder;
    use crate::terrain::generate::{GridSpec, flat};
    use crate::terrain::{Heightfield, MaterialTable};

    #[test]
    fn the_rig_sets_the_body_and_proxy_mass_properties() {
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
        let mut app = builder.build().unwrap();
        let capsules = app.world.get::<CharacterBody>(walker).unwrap().com_height;
        let rig = CharacterRig::human().unwrap();
        attach_rig(&mut app.world, walker, rig).unwrap();
        let body = app.world.get::<CharacterBody>(walker).unwrap();
        let proxy = app.world.get::<RigidProxy>(walker).unwrap();
        assert_ne!(body.com_height, capsules);
        let expect = proxy.inertia.x_axis.x + proxy.mass * body.com_height * body.com_height;
        assert!((proxy.pitch_inertia - expect).abs() < 1e-3);
        assert!(app.world.get::<CharacterRig>(walker).is_ok());
    }
}
