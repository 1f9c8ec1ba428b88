//! `simulate`'s results streamed to disk as the cuts go: each step's
//! sample to `timeseries.csv`, flushed every
//! [`FLUSH_PERIOD`](crate::csv_stream::FLUSH_PERIOD) of a cut's simulated
//! time and at its end, and each finished cut's summary to `cuts.csv` as
//! the cut ends. A simulation killed at any moment (SIGKILL included)
//! leaves every step up to the last flush and every finished cut's
//! summary, in whole rows that parse.

use std::path::Path;

use crate::csv_stream::{CsvStream, FlushSchedule};
use crate::cut_record::{CutSample, CutSummary};
use crate::error::RunError;

/// What a simulation hands over as it runs.
pub trait CutRecorder {
    /// A step's sample of the cut in progress.
    ///
    /// # Errors
    /// The sample cannot be recorded (a failed write).
    fn sample(&mut self, sample: &CutSample) -> Result<(), RunError>;

    /// The end of a cut, with its summary.
    ///
    /// # Errors
    /// As [`CutRecorder::sample`].
    fn cut_done(&mut self, summary: &CutSummary) -> Result<(), RunError>;
}

/// Records nothing: the simulation's output in memory is all.
#[derive(Debug, Clone, Copy, Default)]
pub struct NoCutRecorder;

impl CutRecorder for NoCutRecorder {
    fn sample(&mut self, _: &CutSample) -> Result<(), RunError> {
        Ok(())
    }

    fn cut_done(&mut self, _: &CutSummary) -> Result<(), RunError> {
        Ok(())
    }
}

/// `timeseries.csv` and `cuts.csv` of a simulation's directory, written
/// as the simulation goes on its own thread (a simulation has no tick to
/// keep: formatting a row costs it less than a step).
///
/// The files hold the same bytes as the same rows written at the end
/// would ([`crate::result_file::write_csv`]).
#[derive(Debug)]
pub struct CutStream {
    timeseries: CsvStream,
    cuts: CsvStream,
    schedule: FlushSchedule,
}

impl CutStream {
    /// Creates both files in `dir` (empty until the first flush).
    ///
    /// # Errors
    /// A file cannot be created.
    pub fn create(dir: &Path) -> Result<Self, RunError> {
        Ok(Self {
            timeseries: CsvStream::create(dir.join("timeseries.csv"))?,
            cuts: CsvStream::create(dir.join("cuts.csv"))?,
            schedule: FlushSchedule::default(),
        })
    }

    /// Writes what is buffered (a stopped simulation's last steps).
    ///
    /// # Errors
    /// A write failed.
    pub fn finish(mut self) -> Result<(), RunError> {
        self.timeseries.flush()?;
        self.cuts.flush()
    }
}

impl CutRecorder for CutStream {
    fn sample(&mut self, sample: &CutSample) -> Result<(), RunError> {
        self.timeseries.push(sample)?;
        if self.schedule.due(sample.time_s) {
            self.timeseries.flush()?;
        }
        Ok(())
    }

    fn cut_done(&mut self, summary: &CutSummary) -> Result<(), RunError> {
        self.timeseries.flush()?;
        self.cuts.push(summary)?;
        self.cuts.flush()?;
        // The next cut's time starts again from zero.
        self.schedule = FlushSchedule::default();
        Ok(())
    }
}
