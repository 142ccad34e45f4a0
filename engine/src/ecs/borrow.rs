//! Runtime borrow flags, the shared cell they guard, and the `Ref`/`RefMut` guards.

use std::cell::UnsafeCell;
use std::fmt;
use std::ops::{Deref, DerefMut};
use std::sync::atomic::{AtomicUsize, Ordering};

use super::error::BorrowConflict;

const UNIQUE: usize = 1 << (usize::BITS - 1);

/// A reader/writer flag: a count of shared borrows, or the `UNIQUE` bit.
pub(crate) struct BorrowFlag(AtomicUsize);

impl BorrowFlag {
    pub fn new() -> Self {
        BorrowFlag(AtomicUsize::new(0))
    }

    pub fn try_shared(&self) -> Result<(), BorrowConflict> {
        let previous = self.0.fetch_add(1, Ordering::Acquire);
        if previous & UNIQUE != 0 {
            self.0.fetch_sub(1, Ordering::Release);
            return Err(BorrowConflict::AlreadyMutable);
        }
        assert!(previous + 1 < UNIQUE, "too many shared borrows");
        Ok(())
    }

    pub fn try_unique(&self) -> Result<(), BorrowConflict> {
        self.0
            .compare_exchange(0, UNIQUE, Ordering::Acquire, Ordering::Relaxed)
            .map(|_| ())
            .map_err(|current| {
                if current & UNIQUE != 0 {
                    BorrowConflict::AlreadyMutable
                } else {
                    BorrowConflict::AlreadyShared
                }
            })
    }

    pub fn try_acquire(&self, mutable: bool) -> Result<(), BorrowConflict> {
        if mutable {
            self.try_unique()
        } else {
            self.try_shared()
        }
    }

    pub fn release(&self, mutable: bool) {
        if mutable {
            // Clear only the bit: a failed concurrent `try_shared` may have a
            // transient increment in flight that it undoes itself.
            self.0.fetch_and(!UNIQUE, Ordering::Release);
        } else {
            self.0.fetch_sub(1, Ordering::Release);
        }
    }
}

/// Interior-mutable storage whose access is guarded by a [`BorrowFlag`] held
/// elsewhere (per component type or per resource).
pub(crate) struct SharedCell<T: ?Sized>(UnsafeCell<T>);

// SAFETY: `SharedCell` only hands out references through `get`/`get_mut`, whose
// callers must hold the matching `BorrowFlag` (shared for `get`, unique for
// `get_mut`) or `&mut World`. The flags are atomic, so the usual reader/writer
// rules hold across threads; `T: Send + Sync` makes sharing the value itself sound.
unsafe impl<T: ?Sized + Send + Sync> Sync for SharedCell<T> {}

impl<T> SharedCell<T> {
    pub fn new(value: T) -> Self {
        SharedCell(UnsafeCell::new(value))
    }

    pub fn into_inner(self) -> T {
        self.0.into_inner()
    }
}

impl<T: ?Sized> SharedCell<T> {
    /// Exclusive access, checked by the compiler.
    pub fn get_exclusive(&mut self) -> &mut T {
        self.0.get_mut()
    }

    /// Shared access.
    ///
    /// # Safety
    /// No `&mut` obtained through [`SharedCell::get_mut`] may be live for the
    /// returned lifetime: the caller holds a shared borrow flag for this cell.
    pub unsafe fn get(&self) -> &T {
        // SAFETY: by the caller's contract there is no live mutable reference.
        unsafe { &*self.0.get() }
    }

    /// Mutable access from a shared reference.
    ///
    /// # Safety
    /// No other reference into the cell may be live for the returned lifetime:
    /// the caller holds the unique borrow flag for this cell (or `&mut World`).
    #[allow(clippy::mut_from_ref)] // guarded by the runtime borrow flag, see `# Safety`
    pub unsafe fn get_mut(&self) -> &mut T {
        // SAFETY: by the caller's contract this is the only live reference.
        unsafe { &mut *self.0.get() }
    }
}

/// A shared borrow of a component or resource, released on drop.
pub struct Ref<'a, T: ?Sized> {
    value: &'a T,
    flag: &'a BorrowFlag,
}

impl<'a, T: ?Sized> Ref<'a, T> {
    /// `flag` must be held shared by the caller; it is released when the `Ref` drops.
    pub(crate) fn new(value: &'a T, flag: &'a BorrowFlag) -> Self {
        Ref { value, flag }
    }
}

impl<T: ?Sized> Deref for Ref<'_, T> {
    type Target = T;
    fn deref(&self) -> &T {
        self.value
    }
}

impl<T: ?Sized> Drop for Ref<'_, T> {
    fn drop(&mut self) {
        self.flag.release(false);
    }
}

impl<T: ?Sized + fmt::Debug> fmt::Debug for Ref<'_, T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.value.fmt(f)
    }
}

/// A mutable borrow of a component or resource, released on drop.
pub struct RefMut<'a, T: ?Sized> {
    value: &'a mut T,
    flag: &'a BorrowFlag,
}

impl<'a, T: ?Sized> RefMut<'a, T> {
    /// `flag` must be held uniquely by the caller; it is released when the `RefMut` drops.
    pub(crate) fn new(value: &'a mut T, flag: &'a BorrowFlag) -> Self {
        RefMut { value, flag }
    }
}

impl<T: ?Sized> Deref for RefMut<'_, T> {
    type Target = T;
    fn deref(&self) -> &T {
        self.value
    }
}

impl<T: ?Sized> DerefMut for RefMut<'_, T> {
    fn deref_mut(&mut self) -> &mut T {
        self.value
    }
}

impl<T: ?Sized> Drop for RefMut<'_, T> {
    fn drop(&mut self) {
        self.flag.release(true);
    }
}

impl<T: ?Sized + fmt::Debug> fmt::Debug for RefMut<'_, T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.value.fmt(f)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn flag_reader_writer_rules() {
        let flag = BorrowFlag::new();
        flag.try_shared().unwrap();
        flag.try_shared().unwrap();
        assert_eq!(flag.try_unique(), Err(BorrowConflict::AlreadyShared));
        flag.release(false);
        flag.release(false);
        flag.try_unique().unwrap();
        assert_eq!(flag.try_shared(), Err(BorrowConflict::AlreadyMutable));
        assert_eq!(flag.try_unique(), Err(BorrowConflict::AlreadyMutable));
        flag.release(true);
        flag.try_unique().unwrap();
    }
}
