//! A CSV file written as a run goes, in whole rows, flushed every
//! [`FLUSH_PERIOD`] of simulated time: a run killed at any moment leaves
//! every row up to the last flush in a file that parses.
//!
//! Used by the closed loop's writer thread
//! ([`SeriesStream`](crate::closed_loop::SeriesStream)) and by `simulate`,
//! which writes its rows on its own thread ([`crate::commands::simulate`]).

use std::fs::File;
use std::io::Write;
use std::path::{Path, PathBuf};

use serde::Serialize;

use crate::error::RunError;

/// Simulated time between flushes, s: a kill loses at most the last
/// 100 ms of run time.
pub const FLUSH_PERIOD: f64 = 0.1;

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
/// whole lines only. A kill during a flush's write can cut that write's
/// last line short, without its newline: a reader drops a final line that
/// has none.
///
/// The rows and the header are the same bytes as
/// [`write_csv`](crate::result_file::write_csv) writes for the same rows.
#[derive(Debug)]
pub struct CsvStream {
    path: PathBuf,
    rows: csv::Writer<WholeRecords>,
}

impl CsvStream {
    /// Creates (truncates) the file at `path`.
    ///
    /// # Errors
    /// The file cannot be created.
    pub fn create(path: PathBuf) -> Result<Self, RunError> {
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

    /// The file's path.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Appends `row` to the buffer (the header first, before the first
    /// row).
    ///
    /// # Errors
    /// The row cannot be serialised.
    pub fn push<T: Serialize>(&mut self, row: &T) -> Result<(), RunError> {
        self.rows
            .serialize(row)
            .map_err(|e| RunError::write(&self.path, e))
    }

    /// Writes the buffered rows to the file in one write.
    ///
    /// # Errors
    /// The write failed.
    pub fn flush(&mut self) -> Result<(), RunError> {
        self.rows
            .flush()
            .map_err(|e| RunError::write(&self.path, e))
    }
}

/// When the next flush of a series is due, in the series' simulated time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FlushSchedule {
    next: f64,
}

impl Default for FlushSchedule {
    /// The first flush is due at [`FLUSH_PERIOD`].
    fn default() -> Self {
        Self { next: FLUSH_PERIOD }
    }
}

impl FlushSchedule {
    /// Whether a flush is due at simulated time `time` (s); when it is, the
    /// next one is due [`FLUSH_PERIOD`] after `time`.
    pub fn due(&mut self, time: f64) -> bool {
        let due = time >= self.next;
        if due {
            self.next = time + FLUSH_PERIOD;
        }
        due
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Serialize)]
    struct Row {
        time_s: f64,
        done: Option<bool>,
    }

    /// The streamed file is byte for byte what `write_csv` writes for the
    /// same rows, and holds nothing before its first flush.
    #[test]
    fn a_stream_writes_what_write_csv_writes_and_only_on_flush() {
        let dir = std::env::temp_dir().join(format!("shearcut-csv-stream-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let rows = [
            Row {
                time_s: 0.5,
                done: None,
            },
            Row {
                time_s: 1e-7,
                done: Some(true),
            },
        ];
        let mut s = CsvStream::create(dir.join("streamed.csv")).unwrap();
        for r in &rows {
            s.push(r).unwrap();
        }
        assert_eq!(std::fs::read(s.path()).unwrap().len(), 0);
        s.flush().unwrap();
        crate::result_file::write_csv(&dir.join("whole.csv"), &rows).unwrap();
        assert_eq!(
            std::fs::read(dir.join("streamed.csv")).unwrap(),
            std::fs::read(dir.join("whole.csv")).unwrap()
        );
        std::fs::remove_dir_all(&dir).ok();
    }

    /// Flushes fall at least a period apart, the first at one period.
    #[test]
    fn a_flush_is_due_once_a_period_has_passed() {
        let mut f = FlushSchedule::default();
        let due: Vec<bool> = [0.0, 0.05, 0.1, 0.15, 0.199, 0.2, 0.35]
            .iter()
            .map(|&t| f.due(t))
            .collect();
        assert_eq!(due, [false, false, true, false, false, true, true]);
    }
}
