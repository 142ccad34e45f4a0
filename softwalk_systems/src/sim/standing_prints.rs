//! Walkers start standing in their own prints: before the first step, every
//! character's planted soles press the ground as carving presses it under a
//! foot that bears the body's weight.
//!
//! A character is posed with its feet on the floor of their footholds (the
//! surface less what the ground gives, [`crate::character::FootRays::new`]),
//! the same floor its pelvis height is measured from, so on deep loose
//! ground the legs start straight. Pressing the prints under those soles
//! makes the ground agree with the pose: each foot's [`FootPrint`] holds the
//! untouched surface as its reference, so the first steps read the print as
//! the foot's own (no deeper than a print, its rim laid once), and print
//! depths are measured against the initial surface like any other print.
//!
//! [`FootPrint`]: crate::terrain::FootPrint

use engine::ecs::World;

use super::error::SimError;
use super::run::take_fault;
use super::systems_terrain::{carve_system, refit_system};

/// Presses every character's standing soles into the ground, once, before
/// the first step: the `carve` system over the feet as posed, then `refit`
/// closes the change log (the grid BVH and the renderer see the prints).
/// A foot carving refuses is a [`SimError::System`] naming `carve` at step 0.
pub(crate) fn press_standing_feet(world: &mut World) -> Result<(), SimError> {
    carve_system(world);
    refit_system(world);
    take_fault(world, 0)
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use crate::character::{CharacterDesc, WalkPath};
    use crate::sim::{Feet, FootPrints, GroundState, SimBuilder, SoleGround, sole_ends};
    use crate::terrain::{Heightfield, MaterialTable, generate};

    /// A walker built on 0.3 m of snow over flat ground at height 1.
    fn walker_on_snow() -> engine::schedule::App {
        let table = MaterialTable::with_presets();
        let snow = table.id("snow").unwrap();
        let grid = generate::flat(generate::GridSpec::square(4.0, 201), 1.0).unwrap();
        let mut sim = SimBuilder::new(1.0 / 60.0).unwrap();
        sim.terrain(Heightfield::from_grid(grid, table, snow).unwrap())
            .unwrap();
        let path = WalkPath::straight(Vec3::new(1.0, 0.0, 2.0), Vec3::X, 2.0).unwrap();
        sim.character("walker", CharacterDesc::adult(), path)
            .unwrap();
        sim.build().unwrap()
    }

    #[test]
    fn a_walker_built_on_snow_stands_in_pressed_prints_it_holds_as_its_own() {
        let mut app = walker_on_snow();
        let world = &mut app.world;
        let ground = world.resource::<GroundState>();
        let (hf, volume) = (ground.terrain(), ground.volume());
        let feet = world
            .query::<(&Feet, &FootPrints)>()
            .iter()
            .next()
            .map(|(f, p)| (f.0, p.0.clone()));
        let (feet, prints) = feet.unwrap();
        for (foot, print) in feet.iter().zip(&prints) {
            let sole = foot.sole;
            let lowest = sole.heel.y.min(sole.toe.y);
            assert!((lowest - 0.7).abs() < 0.01, "sole on the floor: {lowest}");
            let under = SoleGround::under(hf.grid(), &sole);
            assert!(under.buried(&sole) < 0.005, "sole in the ground: {under:?}");
            // The lower end of the sole (a leading foot lands heel first)
            // stands on its print's floor, pressed to it.
            let [heel, toe] = sole_ends(&sole);
            let (c, pressed) = match heel.y < toe.y {
                true => (heel, under.heel),
                false => (toe, under.toe),
            };
            assert!((pressed - c.y).abs() < 0.005, "print {pressed} under {c}");
            assert!(print.is_active(), "the print is the foot's own");
            let cell = hf.grid().cell_size();
            let at = (glam::Vec2::new(c.x, c.z) - hf.grid().origin()) / cell;
            let (i, j) = (at.x.round() as usize, at.y.round() as usize);
            assert_eq!(
                print.reference_height(i, j),
                Some(1.0),
                "against the initial surface"
            );
        }
        assert!(volume < hf.initial().volume(), "snow compacts: {volume}");
        assert!(
            (volume - hf.grid().volume()).abs() < 1e-4,
            "the volume is tracked"
        );
    }
}
