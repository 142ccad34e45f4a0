//! Resources: at most one value per type, borrowed at run time.

use std::any::{Any, TypeId};
use std::collections::HashMap;

use super::borrow::{BorrowFlag, Ref, RefMut, SharedCell};
use super::bundle::Component;
use super::error::{BorrowTarget, EcsError};

struct ResourceCell {
    flag: BorrowFlag,
    value: SharedCell<Box<dyn Any + Send + Sync>>,
}

/// Storage of resources keyed by type. Lookup only; never iterated, so the
/// hash map's order cannot leak into results.
#[derive(Default)]
pub(crate) struct Resources {
    cells: HashMap<TypeId, ResourceCell>,
}

const STORED_TYPE: &str = "a resource cell holds the type it is keyed by";

impl Resources {
    pub fn insert<R: Component>(&mut self, value: R) -> Option<R> {
        let cell = ResourceCell {
            flag: BorrowFlag::new(),
            value: SharedCell::new(Box::new(value)),
        };
        let old = self.cells.insert(TypeId::of::<R>(), cell)?;
        let old: Box<dyn Any + Send + Sync> = old.value.into_inner();
        Some(*old.downcast::<R>().expect(STORED_TYPE))
    }

    pub fn remove<R: Component>(&mut self) -> Option<R> {
        let old = self.cells.remove(&TypeId::of::<R>())?;
        Some(*old.value.into_inner().downcast::<R>().expect(STORED_TYPE))
    }

    pub fn contains<R: Component>(&self) -> bool {
        self.cells.contains_key(&TypeId::of::<R>())
    }

    fn cell<R: Component>(&self, mutable: bool) -> Result<&ResourceCell, EcsError> {
        let type_name = std::any::type_name::<R>();
        let cell = self
            .cells
            .get(&TypeId::of::<R>())
            .ok_or(EcsError::MissingResource { type_name })?;
        cell.flag
            .try_acquire(mutable)
            .map_err(|conflict| EcsError::Borrow {
                target: BorrowTarget::Resource,
                type_name,
                conflict,
            })?;
        Ok(cell)
    }

    pub fn borrow<R: Component>(&self) -> Result<Ref<'_, R>, EcsError> {
        let cell = self.cell::<R>(false)?;
        // SAFETY: the shared flag is held; the `Ref` releases it on drop.
        let value = unsafe { cell.value.get() };
        Ok(Ref::new(
            value.downcast_ref::<R>().expect(STORED_TYPE),
            &cell.flag,
        ))
    }

    pub fn borrow_mut<R: Component>(&self) -> Result<RefMut<'_, R>, EcsError> {
        let cell = self.cell::<R>(true)?;
        // SAFETY: the unique flag is held; the `RefMut` releases it on drop.
        let value = unsafe { cell.value.get_mut() };
        Ok(RefMut::new(
            value.downcast_mut::<R>().expect(STORED_TYPE),
            &cell.flag,
        ))
    }
}
