//! `runs.csv`: one row per finished run, appended as the run ends (in the
//! order runs finish), so that a process killed at any moment (SIGKILL
//! included) leaves every finished run's row, whole, in a file that parses
//! ([`CsvStream`]: one write per row).
//!
//! Columns: the run's job id, its controller (a constant ratio as the
//! ratio it ran, `slice:0.35`), its replica, then the outcome
//! ([`OUTCOME_COLUMNS`], deterministic) and the timing ([`TIMING_COLUMNS`],
//! measured) of its [`JobRow`], the cells `tune`'s tables give them. A run
//! that could not be set up is a row too (`end` = `error: …`); a run
//! stopped by a signal is none.

use std::path::PathBuf;
use std::sync::Mutex;

use crate::csv_stream::CsvStream;
use crate::error::RunError;
use crate::tune::job_list::Job;
use crate::tune::job_outcome::{JobRow, OUTCOME_COLUMNS, TIMING_COLUMNS};

/// The file's name in a result directory.
pub const RUN_LOG: &str = "runs.csv";

/// Columns naming a run, before the outcome's and the timing's.
pub const RUN_COLUMNS: [&str; 3] = ["id", "controller", "replica"];

/// `runs.csv`, shared by the threads that finish runs.
#[derive(Debug)]
pub struct RunLog {
    /// The stream, and whether its header is written.
    stream: Mutex<(CsvStream, bool)>,
}

impl RunLog {
    /// Creates (truncates) `path`, empty until the first row: a result
    /// directory abandoned before any run finished holds only empty files
    /// ([`crate::run_dir::abandon`]).
    ///
    /// # Errors
    /// The file cannot be created.
    pub fn create(path: PathBuf) -> Result<Self, RunError> {
        Ok(Self {
            stream: Mutex::new((CsvStream::create(path)?, false)),
        })
    }

    /// Appends the row of `job`'s finished run and writes it to the file
    /// (with the header before the first row) in one write.
    ///
    /// # Errors
    /// The row cannot be written.
    pub fn append(&self, job: &Job, row: &JobRow) -> Result<(), RunError> {
        let mut guard = self.stream.lock().unwrap_or_else(|p| p.into_inner());
        let (stream, header_written) = &mut *guard;
        if !*header_written {
            let header: Vec<&str> = RUN_COLUMNS
                .iter()
                .chain(&OUTCOME_COLUMNS)
                .chain(&TIMING_COLUMNS)
                .copied()
                .collect();
            stream.push(&header)?;
            *header_written = true;
        }
        let cells: Vec<String> = [
            row.id.clone(),
            job.choice.to_string(),
            job.replica.index.to_string(),
        ]
        .into_iter()
        .chain(row.outcome.cells())
        .chain(row.timing.cells())
        .collect();
        stream.push(&cells)?;
        stream.flush()
    }
}
