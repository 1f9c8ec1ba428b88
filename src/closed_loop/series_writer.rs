//! The writer thread of a [`SeriesStream`](super::SeriesStream): it takes
//! the loop's records off the queue, formats them as CSV rows and writes
//! them in whole rows, one write per file every [`FLUSH_PERIOD`] of
//! simulated time. Everything that formats, allocates, locks or calls the
//! system happens here, never on the loop's thread.

use std::sync::Arc;
use std::sync::atomic::{AtomicU8, Ordering};
use std::time::Duration;

use super::series_record::SeriesRecord;
pub use crate::csv_stream::FLUSH_PERIOD;
use crate::csv_stream::{CsvStream, FlushSchedule};
use crate::error::RunError;
use crate::transport::{StopSignal, TerminationWatch};

/// How long the writer sleeps when the queue is empty: the wall-clock
/// delay before a record is formatted and before a signal is seen.
const IDLE: Duration = Duration::from_millis(1);

/// A stop request the writer thread saw, shared with the loop's thread:
/// 0 none, else [`StopSignal`] encoded by [`StopFlag::set`]. Reading it is
/// one atomic load.
#[derive(Debug, Default)]
pub(super) struct StopFlag(AtomicU8);

impl StopFlag {
    fn set(&self, signal: StopSignal) {
        let code = match signal {
            StopSignal::Sigint => 1,
            StopSignal::Sigterm => 2,
        };
        let _ = self
            .0
            .compare_exchange(0, code, Ordering::Release, Ordering::Relaxed);
    }

    /// The first signal seen, if any.
    pub(super) fn get(&self) -> Option<StopSignal> {
        match self.0.load(Ordering::Acquire) {
            1 => Some(StopSignal::Sigint),
            2 => Some(StopSignal::Sigterm),
            _ => None,
        }
    }
}

/// The writer thread's state: both files, the next flush time and the
/// first failed write.
#[derive(Debug)]
pub(super) struct SeriesWriter {
    pub(super) timeseries: CsvStream,
    pub(super) controller: CsvStream,
    pub(super) queue: rtrb::Consumer<SeriesRecord>,
    pub(super) watch: Option<TerminationWatch>,
    pub(super) stop: Arc<StopFlag>,
    schedule: FlushSchedule,
    error: Option<RunError>,
}

impl SeriesWriter {
    /// A writer of `timeseries` and `controller` fed by `queue`; with a
    /// `watch`, it also passes SIGINT/SIGTERM on to `stop`.
    pub(super) fn new(
        timeseries: CsvStream,
        controller: CsvStream,
        queue: rtrb::Consumer<SeriesRecord>,
        watch: Option<TerminationWatch>,
        stop: Arc<StopFlag>,
    ) -> Self {
        Self {
            timeseries,
            controller,
            queue,
            watch,
            stop,
            schedule: FlushSchedule::default(),
            error: None,
        }
    }

    fn keep(&mut self, r: Result<(), RunError>) {
        if let Err(e) = r
            && self.error.is_none()
        {
            self.error = Some(e);
        }
    }

    fn flush(&mut self) {
        let r = self.timeseries.flush();
        self.keep(r);
        let r = self.controller.flush();
        self.keep(r);
    }

    fn take(&mut self, record: SeriesRecord) {
        match record {
            SeriesRecord::Sample(s) => {
                let r = self.timeseries.push(&s);
                self.keep(r);
            }
            SeriesRecord::Control(c) => {
                let r = self.controller.push(&c);
                self.keep(r);
            }
            SeriesRecord::TickDone(time) => {
                if self.schedule.due(time) {
                    self.flush();
                }
            }
        }
    }

    /// Takes every record queued now; how many there were.
    fn drain(&mut self) -> usize {
        let mut n = 0;
        while let Ok(record) = self.queue.pop() {
            self.take(record);
            n += 1;
        }
        n
    }

    /// Runs until the queue's producer is gone and every record is
    /// written, then writes what is buffered.
    ///
    /// # Errors
    /// The first write that failed (the records after it are still taken
    /// off the queue, so the loop never finds it full for that reason).
    pub(super) fn run(mut self) -> Result<(), RunError> {
        loop {
            if let Some(signal) = self.watch.as_ref().and_then(TerminationWatch::requested) {
                self.stop.set(signal);
            }
            // Every record pushed before the producer was dropped is
            // visible once the abandonment is (Acquire on both sides).
            let abandoned = self.queue.is_abandoned();
            let taken = self.drain();
            if abandoned {
                break;
            }
            if taken == 0 {
                std::thread::sleep(IDLE);
            }
        }
        self.flush();
        self.error.map_or(Ok(()), Err)
    }
}
