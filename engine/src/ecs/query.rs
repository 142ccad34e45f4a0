//! The `Query` trait: what a query reads and writes, and how it walks one archetype.

use std::any::TypeId;
use std::marker::PhantomData;

use super::archetype::Archetype;
use super::bundle::Component;
use super::entity::Entity;

/// One component access of a query, used for runtime borrow checks.
#[derive(Clone, Copy, Debug)]
pub struct Access {
    pub(crate) type_id: TypeId,
    pub(crate) type_name: &'static str,
    pub(crate) mutable: bool,
}

impl Access {
    fn of<T: 'static>(mutable: bool) -> Self {
        Access {
            type_id: TypeId::of::<T>(),
            type_name: std::any::type_name::<T>(),
            mutable,
        }
    }
}

/// Something a query can yield: `&T`, `&mut T`, `Option<&T>`, `Option<&mut T>`,
/// [`Entity`], or a tuple of up to 12 of those.
pub trait Query {
    /// The value yielded per entity.
    type Item<'q>;
    /// Walks the rows of one archetype.
    type Fetch<'q>: Fetch<Item = Self::Item<'q>>;
    #[doc(hidden)]
    /// Appends this query's component accesses.
    fn access(out: &mut Vec<Access>);
    /// Where the query finds its columns in one archetype (column positions),
    /// found once per archetype; prepared queries keep it between runs.
    type State: Copy + Send + Sync + 'static;
    #[doc(hidden)]
    /// The state for an archetype that has every required component, else `None`.
    fn prepare(archetype: &Archetype) -> Option<Self::State>;
    #[doc(hidden)]
    /// Starts walking a matching archetype.
    ///
    /// # Safety
    /// `state` is what [`Query::prepare`] returned for this archetype, and the
    /// caller holds the borrows listed by [`Query::access`] (or `&mut World`)
    /// for `'q`, with no other fetch of the same archetype alive that writes
    /// what this one touches.
    unsafe fn fetch<'q>(archetype: &'q Archetype, state: Self::State) -> Self::Fetch<'q>;
}

/// Walks the rows of one archetype for a query.
pub trait Fetch: Send + Sized {
    /// The value yielded per row.
    type Item;
    /// The next row. The caller (the query iterator) guarantees a row remains.
    fn next_item(&mut self) -> Self::Item;
    /// Splits into rows `..mid` and `mid..` (for parallel batches).
    fn split_at(self, mid: usize) -> (Self, Self);
    /// Folds the remaining rows; `rows` is their number (the rows the fetch
    /// was made or split for, minus those taken by [`Fetch::next_item`]).
    /// Single-column fetches override it with a plain walk of their slice,
    /// which the compiler can vectorise.
    #[inline]
    fn fold_rows<B>(mut self, rows: usize, init: B, mut g: impl FnMut(B, Self::Item) -> B) -> B {
        let mut acc = init;
        for _ in 0..rows {
            acc = g(acc, self.next_item());
        }
        acc
    }
}

const ROW_COUNT: &str = "the query iterator never asks for more rows than the archetype has";

/// Fetch of `&T`.
pub struct ReadFetch<'q, T>(&'q [T]);

impl<'q, T: Sync> Fetch for ReadFetch<'q, T> {
    type Item = &'q T;
    #[inline]
    fn next_item(&mut self) -> &'q T {
        let (first, rest) = self.0.split_first().expect(ROW_COUNT);
        self.0 = rest;
        first
    }
    fn split_at(self, mid: usize) -> (Self, Self) {
        let (a, b) = self.0.split_at(mid);
        (ReadFetch(a), ReadFetch(b))
    }
    #[inline]
    fn fold_rows<B>(self, rows: usize, init: B, g: impl FnMut(B, &'q T) -> B) -> B {
        debug_assert_eq!(rows, self.0.len(), "{ROW_COUNT}");
        self.0.iter().fold(init, g)
    }
}

/// Fetch of `&mut T`.
pub struct WriteFetch<'q, T>(&'q mut [T]);

impl<'q, T: Send> Fetch for WriteFetch<'q, T> {
    type Item = &'q mut T;
    #[inline]
    fn next_item(&mut self) -> &'q mut T {
        let slice = std::mem::take(&mut self.0);
        let (first, rest) = slice.split_first_mut().expect(ROW_COUNT);
        self.0 = rest;
        first
    }
    fn split_at(self, mid: usize) -> (Self, Self) {
        let (a, b) = self.0.split_at_mut(mid);
        (WriteFetch(a), WriteFetch(b))
    }
    #[inline]
    fn fold_rows<B>(self, rows: usize, init: B, g: impl FnMut(B, &'q mut T) -> B) -> B {
        debug_assert_eq!(rows, self.0.len(), "{ROW_COUNT}");
        self.0.iter_mut().fold(init, g)
    }
}

/// Fetch of [`Entity`].
pub struct EntityFetch<'q>(ReadFetch<'q, Entity>);

impl Fetch for EntityFetch<'_> {
    type Item = Entity;
    #[inline]
    fn next_item(&mut self) -> Entity {
        *self.0.next_item()
    }
    fn split_at(self, mid: usize) -> (Self, Self) {
        let (a, b) = self.0.split_at(mid);
        (EntityFetch(a), EntityFetch(b))
    }
}

/// Fetch of `Option<..>`: `None` when the archetype lacks the component.
impl<F: Fetch> Fetch for Option<F> {
    type Item = Option<F::Item>;
    #[inline]
    fn next_item(&mut self) -> Option<F::Item> {
        self.as_mut().map(Fetch::next_item)
    }
    fn split_at(self, mid: usize) -> (Self, Self) {
        match self {
            Some(fetch) => {
                let (a, b) = fetch.split_at(mid);
                (Some(a), Some(b))
            }
            None => (None, None),
        }
    }
}

impl<T: Component> Query for &T {
    type Item<'q> = &'q T;
    type Fetch<'q> = ReadFetch<'q, T>;
    type State = usize;
    fn access(out: &mut Vec<Access>) {
        out.push(Access::of::<T>(false));
    }
    fn prepare(archetype: &Archetype) -> Option<usize> {
        archetype.column_index(TypeId::of::<T>())
    }
    unsafe fn fetch<'q>(archetype: &'q Archetype, column: usize) -> Self::Fetch<'q> {
        // SAFETY: `column` is `T`'s position (from `prepare`, by the caller's
        // contract), and the caller holds a shared borrow of `T` for `'q`.
        ReadFetch(unsafe { archetype.column_slice_at::<T>(column) })
    }
}

impl<T: Component> Query for &mut T {
    type Item<'q> = &'q mut T;
    type Fetch<'q> = WriteFetch<'q, T>;
    type State = usize;
    fn access(out: &mut Vec<Access>) {
        out.push(Access::of::<T>(true));
    }
    fn prepare(archetype: &Archetype) -> Option<usize> {
        archetype.column_index(TypeId::of::<T>())
    }
    unsafe fn fetch<'q>(archetype: &'q Archetype, column: usize) -> Self::Fetch<'q> {
        // SAFETY: `column` is `T`'s position (from `prepare`, by the caller's
        // contract), and the caller holds the unique borrow of `T` for `'q`.
        WriteFetch(unsafe { archetype.column_slice_mut_at::<T>(column) })
    }
}

impl<T: Component> Query for Option<&T> {
    type Item<'q> = Option<&'q T>;
    type Fetch<'q> = Option<ReadFetch<'q, T>>;
    type State = Option<usize>;
    fn access(out: &mut Vec<Access>) {
        out.push(Access::of::<T>(false));
    }
    fn prepare(archetype: &Archetype) -> Option<Option<usize>> {
        Some(archetype.column_index(TypeId::of::<T>()))
    }
    unsafe fn fetch<'q>(archetype: &'q Archetype, column: Option<usize>) -> Self::Fetch<'q> {
        // SAFETY: as for `&T`.
        column.map(|column| ReadFetch(unsafe { archetype.column_slice_at::<T>(column) }))
    }
}

impl<T: Component> Query for Option<&mut T> {
    type Item<'q> = Option<&'q mut T>;
    type Fetch<'q> = Option<WriteFetch<'q, T>>;
    type State = Option<usize>;
    fn access(out: &mut Vec<Access>) {
        out.push(Access::of::<T>(true));
    }
    fn prepare(archetype: &Archetype) -> Option<Option<usize>> {
        Some(archetype.column_index(TypeId::of::<T>()))
    }
    unsafe fn fetch<'q>(archetype: &'q Archetype, column: Option<usize>) -> Self::Fetch<'q> {
        // SAFETY: as for `&mut T`.
        column.map(|column| WriteFetch(unsafe { archetype.column_slice_mut_at::<T>(column) }))
    }
}

impl Query for Entity {
    type Item<'q> = Entity;
    type Fetch<'q> = EntityFetch<'q>;
    type State = ();
    fn access(_: &mut Vec<Access>) {}
    fn prepare(_: &Archetype) -> Option<()> {
        Some(())
    }
    unsafe fn fetch<'q>(archetype: &'q Archetype, (): ()) -> Self::Fetch<'q> {
        EntityFetch(ReadFetch(archetype.entities()))
    }
}

macro_rules! impl_query_tuple {
    ($($name:ident $field:tt),+) => {
        impl<$($name: Query),+> Query for ($($name,)+) {
            type Item<'q> = ($($name::Item<'q>,)+);
            type Fetch<'q> = ($($name::Fetch<'q>,)+);
            type State = ($($name::State,)+);
            fn access(out: &mut Vec<Access>) {
                $($name::access(out);)+
            }
            fn prepare(archetype: &Archetype) -> Option<Self::State> {
                Some(($($name::prepare(archetype)?,)+))
            }
            unsafe fn fetch<'q>(archetype: &'q Archetype, state: Self::State) -> Self::Fetch<'q> {
                // SAFETY: forwarded: each element's state came from its own
                // `prepare`, and the caller's borrows cover every element.
                unsafe { ($($name::fetch(archetype, state.$field),)+) }
            }
        }

        impl<$($name: Fetch),+> Fetch for ($($name,)+) {
            type Item = ($($name::Item,)+);
            #[inline]
            fn next_item(&mut self) -> Self::Item {
                ($(self.$field.next_item(),)+)
            }
            fn split_at(self, mid: usize) -> (Self, Self) {
                let halves = ($(self.$field.split_at(mid),)+);
                (($(halves.$field.0,)+), ($(halves.$field.1,)+))
            }
        }
    };
}

impl_query_tuple!(A 0);
impl_query_tuple!(A 0, B 1);
impl_query_tuple!(A 0, B 1, C 2);
impl_query_tuple!(A 0, B 1, C 2, D 3);
impl_query_tuple!(A 0, B 1, C 2, D 3, E 4);
impl_query_tuple!(A 0, B 1, C 2, D 3, E 4, F 5);
impl_query_tuple!(A 0, B 1, C 2, D 3, E 4, F 5, G 6);
impl_query_tuple!(A 0, B 1, C 2, D 3, E 4, F 5, G 6, H 7);
impl_query_tuple!(A 0, B 1, C 2, D 3, E 4, F 5, G 6, H 7, I 8);
impl_query_tuple!(A 0, B 1, C 2, D 3, E 4, F 5, G 6, H 7, I 8, J 9);
impl_query_tuple!(A 0, B 1, C 2, D 3, E 4, F 5, G 6, H 7, I 8, J 9, K 10);
impl_query_tuple!(A 0, B 1, C 2, D 3, E 4, F 5, G 6, H 7, I 8, J 9, K 10, L 11);

/// A filter on archetypes: [`With`], [`Without`], `()` (no filter) or a tuple of filters (all must hold).
pub trait QueryFilter {
    #[doc(hidden)]
    /// Whether the archetype passes.
    fn matches(archetype: &Archetype) -> bool;
}

/// Only entities that have component `T` (not fetched).
pub struct With<T>(PhantomData<fn() -> T>);

/// Only entities that lack component `T`.
pub struct Without<T>(PhantomData<fn() -> T>);

impl QueryFilter for () {
    fn matches(_: &Archetype) -> bool {
        true
    }
}

impl<T: Component> QueryFilter for With<T> {
    fn matches(archetype: &Archetype) -> bool {
        archetype.has(TypeId::of::<T>())
    }
}

impl<T: Component> QueryFilter for Without<T> {
    fn matches(archetype: &Archetype) -> bool {
        !archetype.has(TypeId::of::<T>())
    }
}

macro_rules! impl_filter_tuple {
    ($($name:ident),+) => {
        impl<$($name: QueryFilter),+> QueryFilter for ($($name,)+) {
            fn matches(archetype: &Archetype) -> bool {
                $($name::matches(archetype))&&+
            }
        }
    };
}

impl_filter_tuple!(A);
impl_filter_tuple!(A, B);
impl_filter_tuple!(A, B, C);
impl_filter_tuple!(A, B, C, D);
impl_filter_tuple!(A, B, C, D, E);
impl_filter_tuple!(A, B, C, D, E, F);
impl_filter_tuple!(A, B, C, D, E, F, G);
impl_filter_tuple!(A, B, C, D, E, F, G, H);
impl_filter_tuple!(A, B, C, D, E, F, G, H, I);
impl_filter_tuple!(A, B, C, D, E, F, G, H, I, J);
impl_filter_tuple!(A, B, C, D, E, F, G, H, I, J, K);
impl_filter_tuple!(A, B, C, D, E, F, G, H, I, J, K, L);

/// The query's state for an archetype that passes both the query's
/// requirements and the filter, else `None`.
pub(crate) fn prepare_archetype<Q: Query, F: QueryFilter>(
    archetype: &Archetype,
) -> Option<Q::State> {
    if F::matches(archetype) {
        Q::prepare(archetype)
    } else {
        None
    }
}
