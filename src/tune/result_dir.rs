//! A sweep's result directory:
//!
//! - `sweep.toml`: the sweep file as read;
//! - `jobs.json`: the job catalogue ([`JobCatalog`]), the same in every
//!   shard of a sweep;
//! - `rows/<id>.json`: one file per finished job ([`JobRow`]);
//! - `results.csv`, `timings.csv`: the tables ([`write_tables`]);
//! - for a complete sweep, its analysis (see [`crate::tune::analysis`]).

use std::path::Path;

use shearcut_sim::InvalidSetting;
use shearcut_sim::capped_read::read_capped_text;

use crate::error::{ConfigError, RunError};
use crate::result_file::{PARTIAL_PREFIX, write_json, write_text};
use crate::tune::job_list::JobCatalog;
use crate::tune::job_outcome::JobRow;
use crate::tune::result_table::write_tables;

/// Largest `jobs.json` read back, bytes: the catalogue of the largest
/// sweep allowed ([`crate::tune::sweep_file::MAX_JOBS`] jobs) is well
/// below it; a pipe in its place is refused at once, an endless device
/// after this many bytes.
pub const CATALOG_BYTES: u64 = 256 << 20;

/// A result directory held by this process while it writes it: an
/// exclusive advisory lock on the directory (`flock`), released when
/// dropped. It keeps out processes on the same machine; a file system
/// without locks gets none, and a network file system may not carry it
/// between nodes.
#[must_use = "the directory is held only while the lock lives"]
#[derive(Debug)]
pub struct DirectoryLock {
    _file: Option<std::fs::File>,
}

/// Takes `dir`'s lock ([`DirectoryLock`]).
///
/// # Errors
/// Another process holds it (exit 2).
fn lock_directory(dir: &Path) -> Result<DirectoryLock, RunError> {
    let Ok(file) = std::fs::File::open(dir) else {
        return Ok(DirectoryLock { _file: None });
    };
    match file.try_lock() {
        Err(std::fs::TryLockError::WouldBlock) => Err(crate::run_dir::refused(
            dir,
            "a directory no other `shearcut tune` is writing (one is: let it finish, or give another --out)",
        )),
        // Locked, or a file system without locks.
        locked => Ok(DirectoryLock {
            _file: locked.is_ok().then_some(file),
        }),
    }
}

/// Takes `dir` (created if needed) for the sweep: locks it against other
/// processes ([`DirectoryLock`], held until the returned lock is dropped)
/// and writes `sweep.toml` and `jobs.json` under it.
///
/// # Errors
/// `dir` holds files but is not a sweep's result directory (no
/// `jobs.json`, or one that is not a sweep's catalogue: a sweep's tables
/// would be written among another command's files, over its `jobs.json`),
/// another `shearcut tune` is writing it, or it cannot be created (exit 2).
pub fn write_catalog(
    dir: &Path,
    catalog: &JobCatalog,
    sweep_text: &str,
) -> Result<DirectoryLock, RunError> {
    const ALLOWED: &str =
        "a new or empty directory, or a `shearcut tune` result directory to resume";
    // The directory is the user's `--out`: one that cannot be created is
    // bad input (exit 2).
    if !dir.exists() {
        std::fs::create_dir_all(dir).map_err(|e| crate::run_dir::uncreatable(dir, dir, &e))?;
    }
    let lock = lock_directory(dir)?;
    if dir.join("jobs.json").is_file() {
        if let Err(e) = read_catalog(dir) {
            let why = match e {
                ConfigError::Argument(e) => e.allowed,
                other => other.to_string(),
            };
            return Err(crate::run_dir::refused(dir, format!("{ALLOWED} ({why})")));
        }
    } else if dir.is_dir()
        && crate::run_dir::holds_files(dir)?
        && !interrupted_claim(dir, sweep_text)
    {
        return Err(crate::run_dir::refused(
            dir,
            format!(
                "{ALLOWED} (it holds files and no jobs.json, and is not this sweep's start cut short: \
                 an empty rows/ and this sweep's sweep.toml)"
            ),
        ));
    }
    let rows = dir.join("rows");
    std::fs::create_dir_all(&rows).map_err(|e| crate::run_dir::uncreatable(dir, &rows, &e))?;
    write_text(&dir.join("sweep.toml"), sweep_text)?;
    write_json(&dir.join("jobs.json"), catalog)?;
    Ok(lock)
}

/// Whether `dir` holds only what [`write_catalog`] writes before
/// `jobs.json`, for the sweep `sweep_text`: an empty `rows/`, this sweep's
/// `sweep.toml`, a partly written `sweep.toml` or `jobs.json`. That is a
/// sweep killed while claiming its directory, resumed by running it again.
fn interrupted_claim(dir: &Path, sweep_text: &str) -> bool {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return false;
    };
    let mut has_rows = false;
    let all_ours = entries.flatten().all(|e| {
        let name = e.file_name();
        let name = name.to_string_lossy();
        match name.as_ref() {
            "rows" => {
                has_rows = std::fs::read_dir(e.path()).is_ok_and(|mut r| r.next().is_none());
                has_rows
            }
            "sweep.toml" => std::fs::read(e.path()).is_ok_and(|t| t == sweep_text.as_bytes()),
            n => n
                .strip_prefix(PARTIAL_PREFIX)
                .is_some_and(|f| f == "sweep.toml" || f == "jobs.json"),
        }
    });
    all_ours && has_rows
}

/// Reads `dir/jobs.json` and `dir/sweep.toml`.
pub fn read_catalog(dir: &Path) -> Result<(JobCatalog, String), ConfigError> {
    let not_a_result = |why: String| {
        ConfigError::Argument(InvalidSetting::new(
            "DIR",
            dir.display(),
            format!("is not a `shearcut tune` result directory: {why}"),
        ))
    };
    let path = dir.join("jobs.json");
    let text = read_capped_text(&path, CATALOG_BYTES)
        .map_err(|e| not_a_result(format!("{}: {e}", path.display())))?;
    let catalog: JobCatalog = serde_json::from_str(&text)
        .map_err(|e| not_a_result(format!("{}: {e}", path.display())))?;
    catalog
        .check()
        .map_err(|e| not_a_result(format!("{}: {e}", path.display())))?;
    let sweep = read_capped_text(
        &dir.join("sweep.toml"),
        shearcut_sim::resource_budget::CONFIG_FILE_BYTES,
    )
    .unwrap_or_default();
    Ok((catalog, sweep))
}

/// The row of every job of `catalog` found under `dir`, in job order
/// (`None` where a job has none).
pub fn read_rows(dir: &Path, catalog: &JobCatalog) -> Vec<Option<JobRow>> {
    catalog
        .jobs
        .iter()
        .map(|j| JobRow::read(dir, &j.id))
        .collect()
}

/// Writes the tables of the jobs of `rows` that have one (in job order)
/// under `dir`; the number of jobs tabulated.
pub fn tabulate(
    dir: &Path,
    catalog: &JobCatalog,
    rows: &[Option<JobRow>],
) -> Result<usize, RunError> {
    let finished: Vec<_> = catalog
        .jobs
        .iter()
        .zip(rows)
        .filter_map(|(j, r)| r.as_ref().map(|r| (j, r)))
        .collect();
    write_tables(dir, catalog, &finished)?;
    Ok(finished.len())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tune::job_list::list_of;

    /// A sweep killed while it claimed its directory resumes there; a
    /// directory holding anything else is refused.
    #[test]
    fn a_claim_killed_before_jobs_json_resumes_and_other_files_are_refused() {
        let dir = std::env::temp_dir().join(format!("shearcut-claim-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let catalog =
            list_of("scenarios = [\"loop-potato-cuboid\"]\n[[controllers]]\nkind = \"press\"\n")
                .catalog;
        // What a kill between sweep.toml and jobs.json leaves.
        std::fs::create_dir_all(dir.join("rows")).unwrap();
        std::fs::write(dir.join("sweep.toml"), "sweep").unwrap();
        std::fs::write(dir.join(".partial-jobs.json"), "{\"swe").unwrap();
        let lock = write_catalog(&dir, &catalog, "sweep").unwrap();
        assert_eq!(
            read_catalog(&dir).unwrap(),
            (catalog.clone(), "sweep".into())
        );
        // While one holds it, no other takes it; then it resumes.
        let e = write_catalog(&dir, &catalog, "sweep").unwrap_err();
        assert!(e.to_string().contains("no other `shearcut tune`"), "{e}");
        drop(lock);
        drop(write_catalog(&dir, &catalog, "sweep").unwrap());
        // Another sweep's file, or a sweep.toml alone (no rows/): not ours.
        let kept = dir.join("kept");
        std::fs::create_dir_all(kept.join("rows")).unwrap();
        std::fs::write(kept.join("sweep.toml"), "another sweep").unwrap();
        assert!(write_catalog(&kept, &catalog, "sweep").is_err());
        let alone = dir.join("alone");
        std::fs::create_dir_all(&alone).unwrap();
        std::fs::write(alone.join("sweep.toml"), "sweep").unwrap();
        assert!(write_catalog(&alone, &catalog, "sweep").is_err());
        // Another command's files.
        let other = dir.join("other");
        std::fs::create_dir_all(other.join("rows")).unwrap();
        std::fs::write(other.join("results.csv"), "a,b\n").unwrap();
        let e = write_catalog(&other, &catalog, "sweep").unwrap_err();
        assert!(e.to_string().contains("no jobs.json"), "{e}");
        // A row: a sweep's directory whose jobs.json is gone is not
        // silently re-claimed.
        let ran = dir.join("ran");
        std::fs::create_dir_all(ran.join("rows")).unwrap();
        std::fs::write(ran.join("rows/0123.json"), "{}").unwrap();
        assert!(write_catalog(&ran, &catalog, "sweep").is_err());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
