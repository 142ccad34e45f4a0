//! File output that is written whole or not at all.
//!
//! Every output file of the engine and the `softwalk` program is written
//! through an [`AtomicFile`]: the bytes go into a hidden `.NAME.partial` file
//! beside the target, which is renamed over the target only when the writer
//! commits. A writer dropped before that removes its partial file. A process
//! killed mid-write (`kill -9`) leaves the `.NAME.partial` file behind, and
//! the next writer of the same target, or [`remove_partials`] on its folder,
//! removes it: the name is fixed, so a later run can find it.
#![forbid(unsafe_code)]

mod atomic_file;
mod partial;
mod write_atomic;
mod write_error;

pub use atomic_file::AtomicFile;
pub use partial::{partial_path, remove_partials};
pub use write_atomic::{write_atomic, write_bytes_atomic};
pub use write_error::WriteError;
