//! A queue of deferred changes to a target (the [`World`](super::World)),
//! applied in recording order. It names no world type, so the world can own
//! one without depending on the command API built on top of it.

use super::error::{CommandsError, EcsError};

/// One recorded change to a `W`.
type Deferred<W> = Box<dyn FnOnce(&mut W) -> Result<(), EcsError> + Send>;

/// Recorded changes to a `W`, applied by [`CommandQueue::run_on`] in the
/// order they were recorded. [`CommandBuffer`](super::CommandBuffer) is the
/// queue over a world, with spawn, insert, remove and despawn.
pub struct CommandQueue<W> {
    commands: Vec<Deferred<W>>,
}

impl<W> Default for CommandQueue<W> {
    fn default() -> Self {
        CommandQueue {
            commands: Vec::new(),
        }
    }
}

impl<W> CommandQueue<W> {
    /// An empty queue.
    pub fn new() -> Self {
        Self::default()
    }

    /// Records an arbitrary change.
    pub fn push(&mut self, command: impl FnOnce(&mut W) -> Result<(), EcsError> + Send + 'static) {
        self.commands.push(Box::new(command));
    }

    /// Number of recorded commands.
    pub fn len(&self) -> usize {
        self.commands.len()
    }

    /// Whether nothing is recorded.
    pub fn is_empty(&self) -> bool {
        self.commands.is_empty()
    }

    /// Applies every command in recording order and empties the queue. A
    /// failing command (e.g. its target was despawned) does not stop the
    /// others; all failures are returned together.
    pub fn run_on(&mut self, target: &mut W) -> Result<(), CommandsError> {
        let failures: Vec<(usize, EcsError)> = self
            .commands
            .drain(..)
            .enumerate()
            .filter_map(|(index, command)| command(target).err().map(|error| (index, error)))
            .collect();
        if failures.is_empty() {
            Ok(())
        } else {
            Err(CommandsError { failures })
        }
    }
}
