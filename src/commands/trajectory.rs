//! `shearcut trajectory`: run jerk-limited trajectory cases from a JSONL file.

use std::io::Write;
use std::path::Path;

use crate::error::{ConfigError, RunError};
use crate::run_dir::unusable_output;
use crate::trajectory_cases::{CasesError, CasesReport, run_cases};

/// Reads one case per line from `cases` (ruckig's field names, see
/// `docs/trajectory.md`) and writes one JSON result line per case to `out`
/// (default stdout). Malformed lines get an error line; the rest still run.
/// An unreadable `cases` file or an `out` that cannot be created is bad
/// input (exit 2); a failed write exits 1,
/// a closed stdout quietly (141).
pub fn run(cases: &Path, out: Option<&Path>) -> Result<(), RunError> {
    let read_error = |source| {
        RunError::Config(ConfigError::Read {
            path: cases.to_path_buf(),
            source,
        })
    };
    let report = match out {
        Some(path) => {
            if same_file(path, cases) {
                return Err(RunError::Config(ConfigError::Argument(
                    shearcut_sim::InvalidSetting::new(
                        "--out",
                        path.display(),
                        "a file other than --cases (writing would empty the cases before they are read)",
                    ),
                )));
            }
            let file = std::fs::File::create(path).map_err(|e| {
                unusable_output("--out", path, path, &e, "a file this process can create")
            })?;
            let mut w = std::io::BufWriter::new(file);
            let r = run_cases(cases, &mut w).map_err(|e| match e {
                CasesError::Read(e) => read_error(e),
                CasesError::Write(e) => RunError::write(path, e),
            })?;
            w.flush().map_err(|e| RunError::write(path, e))?;
            r
        }
        None => {
            let stdout = std::io::stdout();
            let mut w = std::io::BufWriter::new(stdout.lock());
            let r = run_cases(cases, &mut w).map_err(|e| match e {
                CasesError::Read(e) => read_error(e),
                CasesError::Write(e) => RunError::Stdout(e),
            })?;
            w.flush().map_err(RunError::Stdout)?;
            r
        }
    };
    report_counts(&report);
    Ok(())
}

/// Whether `a` and `b` name one existing file (by any path or link to it).
fn same_file(a: &Path, b: &Path) -> bool {
    match (std::fs::metadata(a), std::fs::metadata(b)) {
        #[cfg(unix)]
        (Ok(x), Ok(y)) => {
            use std::os::unix::fs::MetadataExt;
            (x.dev(), x.ino()) == (y.dev(), y.ino())
        }
        #[cfg(not(unix))]
        (Ok(_), Ok(_)) => std::fs::canonicalize(a).ok() == std::fs::canonicalize(b).ok(),
        _ => false,
    }
}

/// The counts line on stderr (a closed stderr is ignored).
fn report_counts(report: &CasesReport) {
    let _ = writeln!(
        std::io::stderr(),
        "{} cases: {} ok, {} errors",
        report.cases,
        report.ok,
        report.errors
    );
}
