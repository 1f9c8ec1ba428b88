//! The loop's time series streamed to disk as the run goes, so that a run
//! killed at any moment leaves every tick up to the last flush in files that
//! parse. The loop's thread only copies each record into a preallocated
//! lock-free queue; a writer thread ([`super::series_writer`]) formats and
//! writes them.

use std::path::Path;
use std::sync::Arc;
use std::thread::JoinHandle;

use serde::Serialize;

use super::control_record::ControlSample;
use super::series_record::SeriesRecord;
use super::series_writer::{SeriesWriter, StopFlag};
use crate::csv_stream::CsvStream;
use crate::cut_record::CutSample;
use crate::error::RunError;
use crate::transport::{StopSignal, TerminationWatch};

/// Records the queue between the loop and the writer holds: 65 536, about
/// 20 s of a 1 kHz loop (up to three records a tick) that the writer may
/// fall behind before rows are dropped. Allocated once, at creation
/// (about 12 MB of address space, touched only as it fills).
pub const QUEUE_RECORDS: usize = 1 << 16;

/// What the loop hands over as it runs: each sample and control record,
/// and the end of each tick.
pub trait LoopRecorder {
    /// A sample of the cut (a tick in contact).
    fn sample(&mut self, sample: &CutSample);
    /// The controller's record of a tick.
    fn control(&mut self, record: &ControlSample);
    /// The end of the tick at simulated time `time` (s).
    fn tick_done(&mut self, time: f64);
    /// A stop asked of the run from outside (a signal), seen at the end of
    /// a tick: the loop ends with [`LoopEnd::Stopped`](super::LoopEnd).
    fn stop_requested(&self) -> Option<StopSignal> {
        None
    }
}

/// Records nothing: the loop's output in memory is all.
#[derive(Debug, Clone, Copy, Default)]
pub struct NoRecorder;

impl LoopRecorder for NoRecorder {
    fn sample(&mut self, _: &CutSample) {}
    fn control(&mut self, _: &ControlSample) {}
    fn tick_done(&mut self, _: f64) {}
}

/// Rows the loop could not queue because the queue was full (the writer
/// had fallen [`QUEUE_RECORDS`] behind): missing from the files, never
/// waited for.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize)]
pub struct DroppedRows {
    /// Rows of `timeseries.csv`.
    pub timeseries: u64,
    /// Rows of `controller.csv`.
    pub controller: u64,
}

impl DroppedRows {
    /// Rows dropped from both files.
    pub fn total(&self) -> u64 {
        self.timeseries + self.controller
    }
}

/// `timeseries.csv` and `controller.csv` of a run directory, written as
/// the loop runs and flushed every [`FLUSH_PERIOD`](super::FLUSH_PERIOD)
/// of simulated time, in whole rows.
///
/// The files are the run's final ones (the same columns and rows as the
/// in-memory output, unless rows were dropped: [`DroppedRows`]). The
/// loop's calls ([`LoopRecorder`]) copy one `Copy` record into a
/// single-producer single-consumer queue allocated at creation: no
/// allocation, no lock, no system call. A write that fails is kept and
/// reported by [`SeriesStream::finish`]; the loop goes on.
///
/// ## Memory allocation
/// [`create`](Self::create) allocates the queue ([`QUEUE_RECORDS`]
/// records), the files' buffers and the writer thread; the recorder's
/// calls allocate nothing (`tests/series_stream_alloc.rs`).
#[derive(Debug)]
pub struct SeriesStream {
    queue: rtrb::Producer<SeriesRecord>,
    dropped: DroppedRows,
    stop: Arc<StopFlag>,
    writer: Option<JoinHandle<Result<(), RunError>>>,
}

impl SeriesStream {
    /// Creates both files in `dir` and starts their writer thread.
    ///
    /// # Errors
    /// A file cannot be created, or the thread cannot be started.
    pub fn create(dir: &Path) -> Result<Self, RunError> {
        Self::start(dir, None)
    }

    /// [`create`](Self::create), the writer thread also watching for
    /// SIGINT/SIGTERM: the loop sees the request through
    /// [`LoopRecorder::stop_requested`] (an atomic load) at its next tick.
    ///
    /// # Errors
    /// As [`create`](Self::create).
    pub fn create_watching(dir: &Path, watch: TerminationWatch) -> Result<Self, RunError> {
        Self::start(dir, Some(watch))
    }

    fn start(dir: &Path, watch: Option<TerminationWatch>) -> Result<Self, RunError> {
        let (mut stream, writer) = Self::unstarted(dir, watch, QUEUE_RECORDS)?;
        stream.writer = Some(
            std::thread::Builder::new()
                .name("series-writer".to_string())
                .spawn(move || writer.run())
                .map_err(|e| {
                    RunError::write(dir, format!("cannot start the series writer: {e}"))
                })?,
        );
        Ok(stream)
    }

    /// The stream and its writer, not yet running: a queue of `capacity`
    /// records.
    fn unstarted(
        dir: &Path,
        watch: Option<TerminationWatch>,
        capacity: usize,
    ) -> Result<(Self, SeriesWriter), RunError> {
        let timeseries = CsvStream::create(dir.join("timeseries.csv"))?;
        let controller = CsvStream::create(dir.join("controller.csv"))?;
        let (producer, consumer) = rtrb::RingBuffer::new(capacity);
        let stop = Arc::new(StopFlag::default());
        let writer = SeriesWriter::new(timeseries, controller, consumer, watch, Arc::clone(&stop));
        let stream = Self {
            queue: producer,
            dropped: DroppedRows::default(),
            stop,
            writer: None,
        };
        Ok((stream, writer))
    }

    /// Ends the stream: the writer writes every queued record and what is
    /// buffered, and stops. Returns the rows dropped for a full queue.
    ///
    /// # Errors
    /// The first failed write of the run.
    pub fn finish(self) -> Result<DroppedRows, RunError> {
        let Self {
            queue,
            dropped,
            writer,
            ..
        } = self;
        // The writer drains the queue and returns once it sees its
        // producer gone.
        drop(queue);
        if let Some(writer) = writer {
            writer
                .join()
                .map_err(|_| RunError::Loop("the series writer thread panicked".to_string()))??;
        }
        if dropped.total() > 0 {
            tracing::warn!(
                "{} rows of timeseries.csv and {} of controller.csv dropped: the series writer fell {QUEUE_RECORDS} records behind",
                dropped.timeseries,
                dropped.controller
            );
        }
        Ok(dropped)
    }
}

impl LoopRecorder for SeriesStream {
    fn sample(&mut self, sample: &CutSample) {
        if self.queue.push(SeriesRecord::Sample(*sample)).is_err() {
            self.dropped.timeseries += 1;
        }
    }

    fn control(&mut self, record: &ControlSample) {
        if self.queue.push(SeriesRecord::Control(*record)).is_err() {
            self.dropped.controller += 1;
        }
    }

    fn tick_done(&mut self, time: f64) {
        // A dropped tick end only delays the flush to the next one queued.
        let _ = self.queue.push(SeriesRecord::TickDone(time));
    }

    fn stop_requested(&self) -> Option<StopSignal> {
        self.stop.get()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::closed_loop::FLUSH_PERIOD;
    use shearcut_controllers::controller::ControllerTelemetry;
    use shearcut_sim::arm::KnifeCommand;

    fn record(time: f64) -> ControlSample {
        let t = ControllerTelemetry::moving(0.01, 0.0075, 0.0, false);
        ControlSample::new(time, &t, &KnifeCommand::default())
    }

    fn rows(path: &Path) -> Vec<f64> {
        let mut r = csv::Reader::from_path(path).unwrap();
        r.records()
            .map(|row| row.unwrap()[0].parse::<f64>().unwrap())
            .collect()
    }

    fn scratch(tag: &str) -> std::path::PathBuf {
        let d = std::env::temp_dir().join(format!("shearcut-series-{tag}-{}", std::process::id()));
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    /// A full queue drops the rows that do not fit and counts them; the
    /// loop never waits, and the rows that fit are written in order.
    #[test]
    fn a_full_queue_drops_and_counts_rows_without_waiting() {
        let dir = scratch("full");
        let (mut stream, writer) = SeriesStream::unstarted(&dir, None, 8).unwrap();
        // The writer is not running: the first 8 records fit, the rest
        // find the queue full.
        for k in 0..20 {
            stream.control(&record(k as f64 * 1e-3));
        }
        stream.writer = Some(std::thread::spawn(move || writer.run()));
        let dropped = stream.finish().unwrap();
        assert_eq!(
            dropped,
            DroppedRows {
                timeseries: 0,
                controller: 12
            }
        );
        let times = rows(&dir.join("controller.csv"));
        assert_eq!(times, (0..8).map(|k| k as f64 * 1e-3).collect::<Vec<_>>());
        std::fs::remove_dir_all(&dir).ok();
    }

    /// Rows reach the file by the flush that follows a
    /// [`FLUSH_PERIOD`] of simulated time, before the stream ends.
    #[test]
    #[allow(clippy::disallowed_methods)] // A watchdog on the writer thread.
    fn rows_are_on_disk_after_a_flush_period_before_the_end() {
        let dir = scratch("flush");
        let mut stream = SeriesStream::create(&dir).unwrap();
        let ticks = (FLUSH_PERIOD / 1e-3).round() as usize;
        for k in 1..=ticks {
            stream.control(&record(k as f64 * 1e-3));
            stream.tick_done(k as f64 * 1e-3);
        }
        let path = dir.join("controller.csv");
        let started = std::time::Instant::now();
        while rows_on_disk(&path) < ticks {
            assert!(
                started.elapsed() < std::time::Duration::from_secs(60),
                "no flush"
            );
            std::thread::sleep(std::time::Duration::from_millis(1));
        }
        assert_eq!(stream.finish().unwrap(), DroppedRows::default());
        assert_eq!(rows(&path).len(), ticks);
        std::fs::remove_dir_all(&dir).ok();
    }

    fn rows_on_disk(path: &Path) -> usize {
        std::fs::read(path).map_or(0, |b| {
            b.iter().filter(|&&c| c == b'\n').count().saturating_sub(1)
        })
    }
}
