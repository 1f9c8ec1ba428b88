//! The writer thread of a [`SeriesStream`](super::SeriesStream): it takes
//! the loop's records off the queue, formats them as CSV rows and writes
//! them in whole rows, one write per file every [`FLUSH_PERIOD`] of
//! simulated time. Everything that formats, allocates, locks or calls the
//! system happens here, never on the loop's thread.

use std::fs::File;
use std::io::Write;
use std::path::PathBuf;
use std::sync::Arc;
use std::sync::atomic::{AtomicU8, Ordering};
use std::time::Duration;

use serde::Serialize;

use super::series_record::SeriesRecord;
use crate::error::RunError;
use crate::transport::{StopSignal, TerminationWatch};

/// Simulated time between flushes, s: a kill loses at most the last
/// 100 ms of run time.
pub const FLUSH_PERIOD: f64 = 0.1;

/// How long the writer sleeps when the queue is empty: the wall-clock
/// delay before a record is formatted and before a signal is seen.
const IDLE: Duration = Duration::from_millis(1);

/// A file that receives bytes into a buffer and writes the buffer to the
/// file in one call on `flush`.
#[derive(Debug)]
struct WholeRecords {
    file: File,
    buffer: Vec<u8>,
}

impl Write for WholeRecords {
    fn write(&mut self, bytes: &[u8]) -> std::io::Result<usize> {
        self.buffer.extend_from_slice(bytes);
        Ok(bytes.len())
    }

    fn flush(&mut self) -> std::io::Result<()> {
        self.file.write_all(&self.buffer)?;
        self.buffer.clear();
        Ok(())
    }
}

/// One CSV file written in whole records: rows are serialised into a
/// buffer, which goes to the file in one write per flush (the CSV writer
/// flushes its own buffer into it first), so a kill between flushes leaves
/// whole lines only.
#[derive(Debug)]
pub(super) struct CsvStream {
    path: PathBuf,
    rows: csv::Writer<WholeRecords>,
}

impl CsvStream {
    /// Creates (truncates) the file at `path`.
    ///
    /// # Errors
    /// The file cannot be created.
    pub(super) fn create(path: PathBuf) -> Result<Self, RunError> {
        let file = File::create(&path).map_err(|e| RunError::write(&path, e))?;
        // Capacity for a second of 1 kHz rows (under 400 bytes each): no
        // growth within a flush period.
        let sink = WholeRecords {
            file,
            buffer: Vec::with_capacity(1 << 19),
        };
        Ok(Self {
            path,
            rows: csv::Writer::from_writer(sink),
        })
    }

    fn push<T: Serialize>(&mut self, row: &T) -> Result<(), RunError> {
        self.rows
            .serialize(row)
            .map_err(|e| RunError::write(&self.path, e))
    }

    fn flush(&mut self) -> Result<(), RunError> {
        self.rows
            .flush()
            .map_err(|e| RunError::write(&self.path, e))
    }
}

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
    next_flush: f64,
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
            next_flush: FLUSH_PERIOD,
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
                if time >= self.next_flush {
                    self.flush();
                    self.next_flush = time + FLUSH_PERIOD;
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
