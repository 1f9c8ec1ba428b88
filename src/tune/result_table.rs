//! The results tables: `results.csv`, one row per run with every setting
//! and every outcome as a column (deterministic: bit-identical wherever and
//! however the runs were made), and `timings.csv`, the same runs' wall-clock
//! statistics (measured).
//!
//! Both are written in job order from the row files, by this one function
//! for a local run, a shard and a merge alike. A Python user loads them
//! with `pandas.read_csv("results.csv")`; `job` joins the two.

use std::path::Path;

use crate::error::RunError;
use crate::result_file::write_table;
use crate::tune::job_list::{JOB_COLUMNS, JobCatalog, JobRecord};
use crate::tune::job_outcome::{JobRow, OUTCOME_COLUMNS, TIMING_COLUMNS};

/// A job with its row.
pub type Finished<'a> = (&'a JobRecord, &'a JobRow);

/// Writes `results.csv` and `timings.csv` under `dir` for `finished` (in
/// job order).
pub fn write_tables(
    dir: &Path,
    catalog: &JobCatalog,
    finished: &[Finished],
) -> Result<(), RunError> {
    let header = JOB_COLUMNS
        .iter()
        .map(|c| c.to_string())
        .chain(catalog.setting_columns.iter().cloned())
        .chain(OUTCOME_COLUMNS.iter().map(|c| c.to_string()));
    let rows = finished.iter().map(|(job, row)| {
        job_cells(catalog, job)
            .into_iter()
            .chain(job.cells.iter().cloned())
            .chain(row.outcome.cells())
            .collect()
    });
    write_table(&dir.join("results.csv"), header, rows)?;
    let rows = finished.iter().map(|(job, row)| {
        [job.index.to_string(), job.id.clone()]
            .into_iter()
            .chain(row.timing.cells())
            .collect()
    });
    write_table(
        &dir.join("timings.csv"),
        ["job", "id"].iter().chain(TIMING_COLUMNS.iter()),
        rows,
    )
}

/// The cells of [`JOB_COLUMNS`] for `job`.
fn job_cells(catalog: &JobCatalog, job: &JobRecord) -> Vec<String> {
    vec![
        job.index.to_string(),
        job.id.clone(),
        catalog
            .scenarios
            .get(job.scenario)
            .cloned()
            .unwrap_or_default(),
        job.setting.to_string(),
        job.variant.to_string(),
        job.replica.to_string(),
        job.controller.clone(),
    ]
}
