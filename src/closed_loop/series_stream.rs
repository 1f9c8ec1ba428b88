//! The loop's time series streamed to disk as the run goes, so that a run
//! killed at any moment leaves every tick up to the last flush in files that
//! parse.

use std::fs::File;
use std::io::Write;
use std::path::{Path, PathBuf};

use serde::Serialize;

use super::control_record::ControlSample;
use crate::cut_record::CutSample;
use crate::error::RunError;
use crate::transport::{StopSignal, TerminationWatch};

/// Simulated time between flushes, s: the issue's "at least every 100 ms
/// of run time".
pub const FLUSH_PERIOD: f64 = 0.1;

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
struct CsvStream {
    path: PathBuf,
    rows: csv::Writer<WholeRecords>,
}

impl CsvStream {
    fn create(path: PathBuf) -> Result<Self, RunError> {
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

/// `timeseries.csv` and `controller.csv` of a run directory, written as
/// the loop runs and flushed every [`FLUSH_PERIOD`] of simulated time.
///
/// The files are the run's final ones (the same columns and rows as the
/// in-memory output). A write that fails is kept and reported by
/// [`SeriesStream::finish`]; the loop goes on.
#[derive(Debug)]
pub struct SeriesStream {
    timeseries: CsvStream,
    controller: CsvStream,
    next_flush: f64,
    error: Option<RunError>,
    watch: Option<TerminationWatch>,
    stop: Option<StopSignal>,
}

impl SeriesStream {
    /// Creates both files in `dir`.
    ///
    /// # Errors
    /// A file cannot be created.
    pub fn create(dir: &Path) -> Result<Self, RunError> {
        Ok(Self {
            timeseries: CsvStream::create(dir.join("timeseries.csv"))?,
            controller: CsvStream::create(dir.join("controller.csv"))?,
            next_flush: FLUSH_PERIOD,
            error: None,
            watch: None,
            stop: None,
        })
    }

    /// Also watches for SIGINT/SIGTERM at each flush (every
    /// [`FLUSH_PERIOD`] of simulated time) and asks the loop to stop.
    pub fn watching(mut self, watch: TerminationWatch) -> Self {
        self.watch = Some(watch);
        self
    }

    fn keep(&mut self, r: Result<(), RunError>) {
        if let Err(e) = r
            && self.error.is_none()
        {
            self.error = Some(e);
        }
    }

    /// Writes what is buffered; reports the first write that failed.
    ///
    /// # Errors
    /// The first failed write of the run.
    pub fn finish(mut self) -> Result<(), RunError> {
        let r = self.timeseries.flush();
        self.keep(r);
        let r = self.controller.flush();
        self.keep(r);
        self.error.map_or(Ok(()), Err)
    }
}

impl LoopRecorder for SeriesStream {
    fn sample(&mut self, sample: &CutSample) {
        let r = self.timeseries.push(sample);
        self.keep(r);
    }

    fn control(&mut self, record: &ControlSample) {
        let r = self.controller.push(record);
        self.keep(r);
    }

    fn tick_done(&mut self, time: f64) {
        if time >= self.next_flush {
            let r = self.timeseries.flush();
            self.keep(r);
            let r = self.controller.flush();
            self.keep(r);
            self.next_flush = time + FLUSH_PERIOD;
            if self.stop.is_none() {
                self.stop = self.watch.as_ref().and_then(TerminationWatch::requested);
            }
        }
    }

    fn stop_requested(&self) -> Option<StopSignal> {
        self.stop
    }
}
