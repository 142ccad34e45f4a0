//! Bundles: tuples of components spawned, inserted or removed together.

use std::any::{Any, TypeId};

use super::archetype::{Archetype, ComponentType};
use super::entity::Entity;

/// Any value that can be a component: `Send + Sync + 'static`.
pub trait Component: Send + Sync + 'static {}

impl<T: Send + Sync + 'static> Component for T {}

/// A set of components handled together: implemented for tuples of 1 to 12
/// components, e.g. `(Position, Velocity)` or `(Name,)`.
///
/// Each component type may appear once in a bundle.
pub trait Bundle: Send + Sync + 'static {
    /// The component types, in tuple order.
    fn component_types() -> Vec<ComponentType>;
    #[doc(hidden)]
    /// Pushes each component onto its column (one new row; entities are
    /// handled by the caller).
    fn push_into(self, archetype: &mut Archetype);
    #[doc(hidden)]
    /// Pushes every bundle as a new row, with the entity `alloc(row)`; each
    /// column is looked up once for the whole batch.
    fn push_batch(
        bundles: impl Iterator<Item = Self>,
        archetype: &mut Archetype,
        alloc: impl FnMut(u32) -> Entity,
    ) where
        Self: Sized;
    #[doc(hidden)]
    /// Overwrites the components of `row` in place.
    fn overwrite(self, archetype: &mut Archetype, row: usize);
    #[doc(hidden)]
    /// Swap-removes the bundle's components from `row` and returns them.
    /// The archetype must contain every type of the bundle.
    fn take_from(archetype: &mut Archetype, row: usize) -> Self;
}

const COLUMN_EXISTS: &str = "the target archetype has a column for every bundle component";

/// Typed access to a column known to hold `T`.
fn typed_column<T: 'static>(column: &mut super::archetype::ArchetypeColumn) -> &mut Vec<T> {
    let data: &mut dyn Any = &mut **column.data.get_exclusive();
    data.downcast_mut::<Vec<T>>().expect(COLUMN_EXISTS)
}

macro_rules! impl_bundle {
    ($($name:ident $field:tt $var:ident),+) => {
        impl<$($name: Component),+> Bundle for ($($name,)+) {
            fn component_types() -> Vec<ComponentType> {
                vec![$(ComponentType::of::<$name>()),+]
            }

            fn push_into(self, archetype: &mut Archetype) {
                $(archetype.column_mut::<$name>().expect(COLUMN_EXISTS).push(self.$field);)+
            }

            fn push_batch(
                bundles: impl Iterator<Item = Self>,
                archetype: &mut Archetype,
                mut alloc: impl FnMut(u32) -> Entity,
            ) {
                let indices = [$(archetype.column_index(TypeId::of::<$name>()).expect(COLUMN_EXISTS)),+];
                let [$($var),+] = archetype
                    .columns
                    .get_disjoint_mut(indices)
                    .expect("a bundle's component types are distinct");
                $(let $var = typed_column::<$name>($var);)+
                let entities = &mut archetype.entities;
                for bundle in bundles {
                    entities.push(alloc(entities.len() as u32));
                    $($var.push(bundle.$field);)+
                }
            }

            fn overwrite(self, archetype: &mut Archetype, row: usize) {
                $(archetype.column_mut::<$name>().expect(COLUMN_EXISTS)[row] = self.$field;)+
            }

            fn take_from(archetype: &mut Archetype, row: usize) -> Self {
                ($(archetype.column_mut::<$name>().expect(COLUMN_EXISTS).swap_remove(row),)+)
            }
        }
    };
}

impl_bundle!(A 0 a);
impl_bundle!(A 0 a, B 1 b);
impl_bundle!(A 0 a, B 1 b, C 2 c);
impl_bundle!(A 0 a, B 1 b, C 2 c, D 3 d);
impl_bundle!(A 0 a, B 1 b, C 2 c, D 3 d, E 4 e);
impl_bundle!(A 0 a, B 1 b, C 2 c, D 3 d, E 4 e, F 5 f);
impl_bundle!(A 0 a, B 1 b, C 2 c, D 3 d, E 4 e, F 5 f, G 6 g);
impl_bundle!(A 0 a, B 1 b, C 2 c, D 3 d, E 4 e, F 5 f, G 6 g, H 7 h);
impl_bundle!(A 0 a, B 1 b, C 2 c, D 3 d, E 4 e, F 5 f, G 6 g, H 7 h, I 8 i);
impl_bundle!(A 0 a, B 1 b, C 2 c, D 3 d, E 4 e, F 5 f, G 6 g, H 7 h, I 8 i, J 9 j);
impl_bundle!(A 0 a, B 1 b, C 2 c, D 3 d, E 4 e, F 5 f, G 6 g, H 7 h, I 8 i, J 9 j, K 10 k);
impl_bundle!(A 0 a, B 1 b, C 2 c, D 3 d, E 4 e, F 5 f, G 6 g, H 7 h, I 8 i, J 9 j, K 10 k, L 11 l);
