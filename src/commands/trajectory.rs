//! `shearcut trajectory`: run jerk-limited trajectory cases from a JSONL file.

use std::io::Write;
use std::path::Path;

use crate::error::{ConfigError, RunError};
use crate::trajectory_cases::run_cases;

/// Reads one case per line from `cases` (ruckig's field names, see
/// `docs/trajectory.md`) and writes one JSON result line per case to `out`
/// (default stdout). Malformed lines get an error line; the rest still run.
pub fn run(cases: &Path, out: Option<&Path>) -> Result<(), RunError> {
    if !cases.is_file() {
        return Err(ConfigError::Read {
            path: cases.to_path_buf(),
            source: std::io::Error::new(std::io::ErrorKind::NotFound, "no such file"),
        }
        .into());
    }
    let report = match out {
        Some(path) => {
            let file = std::fs::File::create(path).map_err(|e| RunError::write(path, e))?;
            let mut w = std::io::BufWriter::new(file);
            let r = run_cases(cases, &mut w).map_err(|e| RunError::write(path, e))?;
            w.flush().map_err(|e| RunError::write(path, e))?;
            r
        }
        None => {
            let stdout = std::io::stdout();
            let mut w = std::io::BufWriter::new(stdout.lock());
            let r = run_cases(cases, &mut w).map_err(|e| RunError::write("stdout", e))?;
            w.flush().map_err(|e| RunError::write("stdout", e))?;
            r
        }
    };
    eprintln!(
        "{} cases: {} ok, {} errors",
        report.cases, report.ok, report.errors
    );
    Ok(())
}
