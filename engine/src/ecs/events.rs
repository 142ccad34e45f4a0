//! Double-buffered event queues.

/// A queue of events of type `T`, kept as a resource.
///
/// Double-buffered: [`Events::update`] (called by the `App` once per step,
/// before the systems) retires the previous buffer and starts a new one. An
/// event is therefore readable during the step it was sent in and during the
/// next step, then dropped. Readers keep their own [`EventReader`] cursor, so
/// each event is seen once per reader.
///
/// ```
/// use engine::ecs::{EventReader, Events};
/// let mut events = Events::new();
/// let mut reader = EventReader::default();
/// events.send("landed");
/// assert_eq!(reader.read(&events).collect::<Vec<_>>(), vec![&"landed"]);
/// assert_eq!(reader.read(&events).count(), 0, "seen once per reader");
/// events.update();
/// events.update();
/// assert!(events.is_empty(), "dropped after two updates");
/// ```
#[derive(Debug, Clone)]
pub struct Events<T> {
    previous: Vec<T>,
    previous_start: u64,
    current: Vec<T>,
    current_start: u64,
}

impl<T> Default for Events<T> {
    fn default() -> Self {
        Self::new()
    }
}

impl<T> Events<T> {
    /// An empty queue.
    pub fn new() -> Self {
        Events {
            previous: Vec::new(),
            previous_start: 0,
            current: Vec::new(),
            current_start: 0,
        }
    }

    /// Sends an event.
    pub fn send(&mut self, event: T) {
        self.current.push(event);
    }

    /// Drops the events of the previous update and makes the current ones previous.
    pub fn update(&mut self) {
        std::mem::swap(&mut self.previous, &mut self.current);
        self.current.clear();
        self.previous_start = self.current_start;
        self.current_start = self.previous_start + self.previous.len() as u64;
    }

    /// Takes every readable event out, oldest first.
    pub fn drain(&mut self) -> impl Iterator<Item = T> + '_ {
        let end = self.end_id();
        self.previous_start = end;
        self.current_start = end;
        self.previous.drain(..).chain(self.current.drain(..))
    }

    /// Events sent since the last [`Events::update`].
    pub fn iter_current_update(&self) -> impl Iterator<Item = &T> + '_ {
        self.current.iter()
    }

    /// Every readable event, oldest first.
    pub fn iter(&self) -> impl Iterator<Item = &T> + '_ {
        self.previous.iter().chain(self.current.iter())
    }

    /// Number of readable events.
    pub fn len(&self) -> usize {
        self.previous.len() + self.current.len()
    }

    /// Whether no event is readable.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    fn end_id(&self) -> u64 {
        self.current_start + self.current.len() as u64
    }
}

/// A reader's position in an [`Events`] queue.
#[derive(Debug, Clone, Copy, Default)]
pub struct EventReader {
    next_id: u64,
}

impl EventReader {
    /// A reader that skips every event sent so far.
    pub fn new_at_end<T>(events: &Events<T>) -> Self {
        EventReader {
            next_id: events.end_id(),
        }
    }

    /// Events not yet seen by this reader, oldest first. Events retired
    /// before the reader caught up are skipped.
    pub fn read<'e, T>(&mut self, events: &'e Events<T>) -> impl Iterator<Item = &'e T> + 'e {
        let start = self.next_id.max(events.previous_start);
        self.next_id = events.end_id();
        let skip_previous = (start - events.previous_start) as usize;
        let skip_current = start.saturating_sub(events.current_start) as usize;
        events
            .previous
            .iter()
            .skip(skip_previous)
            .chain(events.current.iter().skip(skip_current))
    }
}
