//! Type-erased component columns: a `Vec<T>` behind a trait object.

use std::any::Any;

/// One archetype column: all values of one component type, one per row.
pub(crate) trait Column: Any + Send + Sync {
    /// Removes `row` (the last row moves into it) and drops the value.
    fn swap_remove_drop(&mut self, row: usize);
    /// Removes `row` (the last row moves into it) and pushes the value onto `dst`,
    /// which must be a column of the same type.
    fn swap_remove_into(&mut self, row: usize, dst: &mut dyn Column);
    /// Reserves room for `additional` more rows.
    fn reserve(&mut self, additional: usize);
}

impl<T: Send + Sync + 'static> Column for Vec<T> {
    fn swap_remove_drop(&mut self, row: usize) {
        self.swap_remove(row);
    }

    fn swap_remove_into(&mut self, row: usize, dst: &mut dyn Column) {
        let value = self.swap_remove(row);
        let dst: &mut dyn Any = dst;
        dst.downcast_mut::<Vec<T>>()
            .expect("columns of one component type hold the same Rust type")
            .push(value);
    }

    fn reserve(&mut self, additional: usize) {
        Vec::reserve(self, additional);
    }
}
