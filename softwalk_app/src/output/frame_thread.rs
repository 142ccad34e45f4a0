//! Frame outputs on a writer thread, so that encoding (PNG frames, GIF,
//! thumbnails) overlaps with drawing the next frames.

use std::sync::mpsc::{Receiver, SyncSender, sync_channel};
use std::thread::JoinHandle;

use image::RgbaImage;

use crate::runner::{Frame, ObserverError, RunObserver};

/// Frames waiting for the writer thread before drawing waits for it.
const QUEUE: usize = 4;

/// One frame sent to the writer thread: step, time and pixels.
type Sent = (u64, f64, RgbaImage);

/// An observer of frames running on its own thread: [`RunObserver::on_frame`]
/// copies the frame to the thread and returns. The observer is given back,
/// with the first error it raised, by [`FrameThread::finish`].
pub struct FrameThread<O> {
    sender: Option<SyncSender<Sent>>,
    thread: Option<JoinHandle<(O, Result<(), ObserverError>)>>,
}

impl<O: RunObserver + 'static> FrameThread<O> {
    /// Runs `observer`'s [`RunObserver::on_frame`] on a new thread.
    pub fn spawn(observer: O) -> FrameThread<O> {
        let (sender, receiver) = sync_channel(QUEUE);
        let thread = std::thread::spawn(move || write_frames(observer, receiver));
        FrameThread {
            sender: Some(sender),
            thread: Some(thread),
        }
    }

    /// Waits for the frames sent so far to be written; gives back the
    /// observer, or the first error it raised.
    pub fn finish(mut self) -> Result<O, ObserverError> {
        self.sender = None;
        let thread = self.thread.take().expect("joined only here");
        let (observer, result) = thread
            .join()
            .map_err(|_| "the frame writer thread panicked")?;
        result.map(|()| observer)
    }
}

/// The writer thread: passes every frame received to `observer` until the
/// sender is dropped; after an error, drains the rest and reports the error.
fn write_frames<O: RunObserver>(
    mut observer: O,
    frames: Receiver<Sent>,
) -> (O, Result<(), ObserverError>) {
    let mut result = Ok(());
    for (step, t, image) in frames {
        if result.is_ok() {
            result = observer.on_frame(&Frame {
                step,
                t,
                image: &image,
            });
        }
    }
    (observer, result)
}

impl<O: RunObserver + 'static> RunObserver for FrameThread<O> {
    fn on_frame(&mut self, frame: &Frame<'_>) -> Result<(), ObserverError> {
        let sender = self.sender.as_ref().ok_or("the frame writer is finished")?;
        let sent = (frame.step, frame.t, frame.image.clone());
        // A closed channel means the thread stopped: `finish` reports why.
        let _ = sender.send(sent);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Counts frames and fails on the third.
    #[derive(Default)]
    struct Counter(u64);

    impl RunObserver for Counter {
        fn on_frame(&mut self, _frame: &Frame<'_>) -> Result<(), ObserverError> {
            self.0 += 1;
            if self.0 == 3 {
                return Err("third frame".into());
            }
            Ok(())
        }
    }

    fn send(thread: &mut FrameThread<Counter>, count: u64) {
        let image = RgbaImage::new(2, 2);
        for step in 0..count {
            let frame = Frame {
                step,
                t: 0.0,
                image: &image,
            };
            thread.on_frame(&frame).unwrap();
        }
    }

    #[test]
    fn every_frame_reaches_the_observer_and_errors_come_back() {
        let mut ok = FrameThread::spawn(Counter(10));
        send(&mut ok, 7);
        assert_eq!(ok.finish().unwrap().0, 17);
        let mut failing = FrameThread::spawn(Counter::default());
        send(&mut failing, 5);
        assert_eq!(failing.finish().err().unwrap().to_string(), "third frame");
    }
}
