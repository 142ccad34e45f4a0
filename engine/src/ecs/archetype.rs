//! Archetypes: tables holding every entity with exactly one set of component types.

use std::any::{Any, TypeId};

use super::borrow::SharedCell;
use super::column::Column;
use super::entity::Entity;

/// Identity of a component type, as listed by a bundle.
#[derive(Clone, Copy, Debug)]
pub struct ComponentType {
    pub(crate) type_id: TypeId,
    pub(crate) type_name: &'static str,
    pub(crate) new_column: fn() -> Box<dyn Column>,
}

impl ComponentType {
    /// The identity of component type `T`.
    pub fn of<T: Send + Sync + 'static>() -> Self {
        ComponentType {
            type_id: TypeId::of::<T>(),
            type_name: std::any::type_name::<T>(),
            new_column: || Box::new(Vec::<T>::new()),
        }
    }
}

pub(crate) struct ArchetypeColumn {
    pub ty: ComponentType,
    /// Index of the component type's borrow flag in the world.
    pub component_id: usize,
    pub data: SharedCell<Box<dyn Column>>,
}

/// A cached structural transition: adding or removing one bundle type.
#[derive(Clone, Copy)]
pub(crate) struct Edge {
    pub bundle: TypeId,
    pub target: u32,
    /// Adding: the source already has some of the bundle's types.
    pub overlaps: bool,
}

/// A table of entities that share exactly one set of component types: one
/// column per type, one row per entity. Rows are dense; despawning or moving
/// an entity swaps the last row into the hole.
pub struct Archetype {
    /// Sorted by `TypeId`.
    pub(crate) columns: Vec<ArchetypeColumn>,
    pub(crate) entities: Vec<Entity>,
    pub(crate) add_edges: Vec<Edge>,
    pub(crate) remove_edges: Vec<Edge>,
}

impl Archetype {
    /// `columns` must be sorted by type id without duplicates.
    pub(crate) fn new(columns: Vec<ArchetypeColumn>) -> Self {
        Archetype {
            columns,
            entities: Vec::new(),
            add_edges: Vec::new(),
            remove_edges: Vec::new(),
        }
    }

    /// Number of rows (entities).
    pub fn len(&self) -> usize {
        self.entities.len()
    }

    /// Whether the archetype has no rows.
    pub fn is_empty(&self) -> bool {
        self.entities.is_empty()
    }

    /// Whether the archetype stores component `type_id`.
    pub fn has(&self, type_id: TypeId) -> bool {
        self.column_index(type_id).is_some()
    }

    /// The entities, in row order.
    pub fn entities(&self) -> &[Entity] {
        &self.entities
    }

    pub(crate) fn column_index(&self, type_id: TypeId) -> Option<usize> {
        // Archetypes hold a handful of columns: a linear scan beats a binary search.
        self.columns.iter().position(|c| c.ty.type_id == type_id)
    }

    pub(crate) fn type_ids(&self) -> impl Iterator<Item = TypeId> + '_ {
        self.columns.iter().map(|c| c.ty.type_id)
    }

    /// Typed exclusive access to the column of `T`.
    pub(crate) fn column_mut<T: 'static>(&mut self) -> Option<&mut Vec<T>> {
        let index = self.column_index(TypeId::of::<T>())?;
        let column: &mut dyn Any = &mut **self.columns[index].data.get_exclusive();
        column.downcast_mut::<Vec<T>>()
    }

    /// The column at `index`, which must store `T` (checked in debug builds).
    ///
    /// # Safety
    /// `index` is the position of `T`'s column in this archetype.
    #[inline]
    unsafe fn column_of<T: 'static>(&self, index: usize) -> &ArchetypeColumn {
        debug_assert!(
            self.columns[index].ty.type_id == TypeId::of::<T>(),
            "column {index} stores `{}`, not `{}`",
            self.columns[index].ty.type_name,
            std::any::type_name::<T>()
        );
        // SAFETY: by the caller's contract `index` is a column position.
        unsafe { self.columns.get_unchecked(index) }
    }

    /// Typed shared access to the column of `T`.
    ///
    /// # Safety
    /// The caller holds a shared borrow of `T`'s flag (or `&World` with no
    /// mutable borrow possible) for the returned lifetime.
    pub(crate) unsafe fn column_slice<T: 'static>(&self) -> Option<&[T]> {
        let index = self.column_index(TypeId::of::<T>())?;
        // SAFETY: `index` is `T`'s column (just looked up); the borrow is
        // forwarded to the caller.
        Some(unsafe { self.column_slice_at(index) })
    }

    /// Typed mutable access to the column of `T` through `&self`.
    ///
    /// # Safety
    /// The caller holds the unique borrow of `T`'s flag (or `&mut World`) for
    /// the returned lifetime, and takes no other reference to this column.
    #[allow(clippy::mut_from_ref)] // guarded by the runtime borrow flag, see `# Safety`
    pub(crate) unsafe fn column_slice_mut<T: 'static>(&self) -> Option<&mut [T]> {
        let index = self.column_index(TypeId::of::<T>())?;
        // SAFETY: `index` is `T`'s column (just looked up); the borrow is
        // forwarded to the caller.
        Some(unsafe { self.column_slice_mut_at(index) })
    }

    /// Typed shared access to column `index`, without looking the type up:
    /// what cached queries use.
    ///
    /// # Safety
    /// `index` is the position of `T`'s column in this archetype (what
    /// [`Archetype::column_index`] returned for `T`; debug builds check it),
    /// and the borrow contract of [`Archetype::column_slice`] holds.
    pub(crate) unsafe fn column_slice_at<T: 'static>(&self, index: usize) -> &[T] {
        // SAFETY: forwarded to the caller: `index` is `T`'s column.
        let column = unsafe { self.column_of::<T>(index) };
        // SAFETY: forwarded to the caller: a shared borrow of `T` is held.
        let data: &dyn Column = unsafe { &**column.data.get() };
        // SAFETY: by the caller's contract the column's `ComponentType` is
        // `T`'s. `ComponentType::of::<T>` is its only constructor, and the
        // world creates every column with that type's `new_column`, which
        // boxes a `Vec<T>`; a column is never replaced. So the trait object
        // points at a `Vec<T>` (the unchecked form of `downcast_ref`).
        let vec = unsafe { &*(data as *const dyn Column).cast::<Vec<T>>() };
        vec.as_slice()
    }

    /// Typed mutable access to column `index` through `&self`.
    ///
    /// # Safety
    /// `index` is the position of `T`'s column in this archetype (debug
    /// builds check it), and the borrow contract of
    /// [`Archetype::column_slice_mut`] holds.
    #[allow(clippy::mut_from_ref)] // guarded by the runtime borrow flag, see `# Safety`
    pub(crate) unsafe fn column_slice_mut_at<T: 'static>(&self, index: usize) -> &mut [T] {
        // SAFETY: forwarded to the caller: `index` is `T`'s column.
        let column = unsafe { self.column_of::<T>(index) };
        // SAFETY: forwarded to the caller: the unique borrow of `T` is held.
        let data: &mut dyn Column = unsafe { &mut **column.data.get_mut() };
        // SAFETY: as in `column_slice_at`: the column holds a `Vec<T>`.
        let vec = unsafe { &mut *(data as *mut dyn Column).cast::<Vec<T>>() };
        vec.as_mut_slice()
    }

    pub(crate) fn reserve(&mut self, additional: usize) {
        self.entities.reserve(additional);
        for column in &mut self.columns {
            column.data.get_exclusive().reserve(additional);
        }
    }

    /// Drops every component of `row`; returns the entity moved into `row`, if any.
    pub(crate) fn swap_remove_drop(&mut self, row: usize) -> Option<Entity> {
        for column in &mut self.columns {
            column.data.get_exclusive().swap_remove_drop(row);
        }
        self.swap_remove_entity(row)
    }

    /// Removes `row` from the entity list; returns the entity moved into `row`, if any.
    pub(crate) fn swap_remove_entity(&mut self, row: usize) -> Option<Entity> {
        self.entities.swap_remove(row);
        self.entities.get(row).copied()
    }
}

/// The column check exists in debug builds only.
#[cfg(all(test, debug_assertions))]
mod tests {
    use super::super::world::World;

    #[test]
    fn a_column_position_is_checked_against_the_requested_type_in_debug_builds() {
        let mut world = World::new();
        world.spawn((1u32, 2.0f64));
        let archetype = &world.archetypes()[1];
        let position = archetype
            .column_index(std::any::TypeId::of::<f64>())
            .unwrap();
        // SAFETY: `world` is borrowed shared and nothing writes to it.
        assert_eq!(
            unsafe { archetype.column_slice_at::<f64>(position) },
            &[2.0]
        );
        let wrong = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            // SAFETY: as above; the debug check panics before the data is touched.
            unsafe { archetype.column_slice_at::<u32>(position).len() }
        }));
        let message = *wrong.unwrap_err().downcast::<String>().unwrap();
        assert!(message.contains("stores `f64`, not `u32`"), "{message}");
    }
}
