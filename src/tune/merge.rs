//! `shearcut tune merge DIR…`: the shards of a sweep combined into one
//! result directory, equal to a local run's.
//!
//! Every DIR must hold the same sweep (`jobs.json` equal). Each job's row
//! is taken from whichever DIR has it and copied byte for byte into the
//! output's `rows/`; the tables are then written by the same code, in the
//! same job order, as a local run's, so the merged `results.csv` equals the
//! local one bit for bit.

use std::path::{Path, PathBuf};

use shearcut_sim::InvalidSetting;

use crate::error::{ConfigError, RunError};
use crate::result_file::publish;
use crate::tune::job_list::JobCatalog;
use crate::tune::job_outcome::JobRow;
use crate::tune::result_dir::{DirectoryLock, read_catalog, write_catalog};

/// The merged sweep: its catalogue and every job's row, in job order.
#[derive(Debug)]
pub struct Merged {
    /// The catalogue.
    pub catalog: JobCatalog,
    /// The sweep file's text.
    pub sweep_text: String,
    /// Every job's row.
    pub rows: Vec<JobRow>,
    /// The output directory's lock: hold it until its tables and analysis
    /// are written.
    pub held: DirectoryLock,
}

/// Whether `a` and `b` are one directory (by their canonical paths).
fn same_directory(a: &Path, b: &Path) -> bool {
    matches!(
        (std::fs::canonicalize(a), std::fs::canonicalize(b)),
        (Ok(a), Ok(b)) if a == b
    )
}

/// Reads the shards in `dirs` and writes their union under `out` (catalogue
/// and row files); the tables and analysis are the caller's.
pub fn merge(dirs: &[PathBuf], out: &Path) -> Result<Merged, RunError> {
    let argument = |key: &str, value: String, why: String| {
        RunError::Config(ConfigError::Argument(InvalidSetting::new(key, value, why)))
    };
    let Some(first) = dirs.first() else {
        return Err(argument(
            "DIR",
            "(none)".into(),
            "name at least one shard directory".into(),
        ));
    };
    for (i, d) in dirs.iter().enumerate() {
        let same = |e: &PathBuf| e == d || same_directory(e, d);
        if dirs[..i].iter().any(same) {
            return Err(argument(
                "DIR",
                d.display().to_string(),
                "is named twice: name each shard's directory once".into(),
            ));
        }
    }
    let (catalog, sweep_text) = read_catalog(first)?;
    for d in &dirs[1..] {
        let (other, _) = read_catalog(d)?;
        if other != catalog {
            return Err(argument(
                "DIR",
                d.display().to_string(),
                format!("holds another sweep's jobs than {}", first.display()),
            ));
        }
    }
    let held = write_catalog(out, &catalog, &sweep_text)?;
    let mut rows = Vec::with_capacity(catalog.jobs.len());
    let mut missing = Vec::new();
    let mut unreadable = None;
    for job in &catalog.jobs {
        let found = dirs
            .iter()
            .find_map(|d| JobRow::read(d, &job.id).map(|row| (d, row)));
        match found {
            Some((d, row)) => {
                let (from, to) = (JobRow::path(d, &job.id), JobRow::path(out, &job.id));
                if from != to {
                    // Whole or absent, as a shard writes its rows.
                    publish(&to, |tmp| {
                        std::fs::copy(&from, tmp)
                            .map(|_| ())
                            .map_err(|e| RunError::write(&to, e))
                    })?;
                }
                rows.push(row);
            }
            None => {
                // A row file that is there but does not read as this job's
                // row (cut short, edited) is named: it is not a shard yet to run.
                if unreadable.is_none() {
                    unreadable = dirs
                        .iter()
                        .map(|d| JobRow::path(d, &job.id))
                        .find(|p| p.exists());
                }
                missing.push(job.index);
            }
        }
    }
    if let Some(first_missing) = missing.first() {
        let why = match &unreadable {
            Some(path) => format!(
                "; {} is not a readable row of its job: delete it and run its shard again",
                path.display()
            ),
            None => ": run their shards, then merge again".to_string(),
        };
        return Err(argument(
            "DIR",
            dirs.iter()
                .map(|d| d.display().to_string())
                .collect::<Vec<_>>()
                .join(" "),
            format!(
                "{} of {} jobs have no result (first: job {first_missing}){why}",
                missing.len(),
                catalog.jobs.len()
            ),
        ));
    }
    Ok(Merged {
        catalog,
        sweep_text,
        rows,
        held,
    })
}
