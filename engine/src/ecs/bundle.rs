//! Bundles: tuples of components spawned, inserted or removed together.

use super::archetype::{Archetype, ComponentType};

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
    /// Overwrites the components of `row` in place.
    fn overwrite(self, archetype: &mut Archetype, row: usize);
    #[doc(hidden)]
    /// Swap-removes the bundle's components from `row` and returns them.
    /// The archetype must contain every type of the bundle.
    fn take_from(archetype: &mut Archetype, row: usize) -> Self;
}

const COLUMN_EXISTS: &str = "the target archetype has a column for every bundle component";

macro_rules! impl_bundle {
    ($($name:ident $field:tt),+) => {
        impl<$($name: Component),+> Bundle for ($($name,)+) {
            fn component_types() -> Vec<ComponentType> {
                vec![$(ComponentType::of::<$name>()),+]
            }

            fn push_into(self, archetype: &mut Archetype) {
                $(archetype.column_mut::<$name>().expect(COLUMN_EXISTS).push(self.$field);)+
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

impl_bundle!(A 0);
impl_bundle!(A 0, B 1);
impl_bundle!(A 0, B 1, C 2);
impl_bundle!(A 0, B 1, C 2, D 3);
impl_bundle!(A 0, B 1, C 2, D 3, E 4);
impl_bundle!(A 0, B 1, C 2, D 3, E 4, F 5);
impl_bundle!(A 0, B 1, C 2, D 3, E 4, F 5, G 6);
impl_bundle!(A 0, B 1, C 2, D 3, E 4, F 5, G 6, H 7);
impl_bundle!(A 0, B 1, C 2, D 3, E 4, F 5, G 6, H 7, I 8);
impl_bundle!(A 0, B 1, C 2, D 3, E 4, F 5, G 6, H 7, I 8, J 9);
impl_bundle!(A 0, B 1, C 2, D 3, E 4, F 5, G 6, H 7, I 8, J 9, K 10);
impl_bundle!(A 0, B 1, C 2, D 3, E 4, F 5, G 6, H 7, I 8, J 9, K 10, L 11);
