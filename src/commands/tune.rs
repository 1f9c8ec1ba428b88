//! `shearcut tune SWEEP.toml` and `shearcut tune merge DIR…`: run a sweep
//! (locally, or one shard of it), and combine shards.

use std::path::{Path, PathBuf};

use clap::{Args, Subcommand};

use crate::error::{ConfigError, RunError};
use crate::transport::TerminationWatch;
use crate::tune::analysis::analyse;
use crate::tune::executor::{default_threads, run_pending};
use crate::tune::job_list::{JobCatalog, JobList};
use crate::tune::job_outcome::JobRow;
use crate::tune::merge::merge;
use crate::tune::result_dir::{read_rows, tabulate, write_catalog};
use crate::tune::shard::Shard;
use crate::tune::stop_request::StopRequest;
use crate::tune::sweep_file::Sweep;

/// `shearcut tune`'s arguments.
#[derive(Debug, Args)]
#[command(args_conflicts_with_subcommands = true, subcommand_negates_reqs = true)]
pub struct TuneArgs {
    /// `merge`: combine shards (else: run the sweep).
    #[command(subcommand)]
    pub action: Option<TuneAction>,
    /// The sweep file (see config/sweeps/ and docs/tuning.md).
    #[arg(required = true, value_name = "SWEEP.toml")]
    pub sweep: Option<PathBuf>,
    /// Runs at a time (default: the machine's cores).
    #[arg(long, value_name = "N", allow_negative_numbers = true,
          value_parser = clap::value_parser!(u32).range(1..=1024))]
    pub jobs: Option<u32>,
    /// Run shard I of N of the job list (jobs I, I+N, I+2N, …); default:
    /// the Slurm array task or Kubernetes completion index from the
    /// environment, else the whole list.
    #[arg(long, value_name = "I/N", allow_hyphen_values = true)]
    pub shard: Option<String>,
    /// Result directory (default: runs/tune-<sweep name>; a shard writes
    /// into its `shard-I-of-N/` below it). Re-running into it skips the
    /// runs already there.
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
}

/// `shearcut tune`'s subcommands.
#[derive(Debug, Subcommand)]
pub enum TuneAction {
    /// Combine the result directories of a sweep's shards into one, equal
    /// to a local run's.
    Merge {
        /// The shards' result directories.
        #[arg(required = true, value_name = "DIR")]
        dirs: Vec<PathBuf>,
        /// Where to write the merged results (default: runs/tune-<sweep name>).
        #[arg(long, value_name = "DIR")]
        out: Option<PathBuf>,
    },
}

/// Runs `shearcut tune …`.
pub fn run(args: TuneArgs) -> Result<(), RunError> {
    match args.action {
        Some(TuneAction::Merge { dirs, out }) => run_merge(&dirs, out.as_deref()),
        None => {
            let sweep = args.sweep.ok_or_else(|| {
                RunError::Config(ConfigError::Argument(shearcut_sim::InvalidSetting::new(
                    "SWEEP.toml",
                    "missing",
                    "name a sweep file",
                )))
            })?;
            let flag = args
                .shard
                .as_deref()
                .map(str::parse::<Shard>)
                .transpose()
                .map_err(|e| RunError::Config(ConfigError::Argument(e)))?;
            let shard = Shard::resolve(flag, |name| std::env::var(name).ok())
                .map_err(|e| RunError::Config(ConfigError::Argument(e)))?;
            let threads = args.jobs.map_or_else(default_threads, |n| n as usize);
            run_sweep(&sweep, shard, threads, args.out.as_deref())
        }
    }
}

/// Runs `shard` of the sweep in `path` on `threads` threads into `out`.
pub fn run_sweep(
    path: &Path,
    shard: Shard,
    threads: usize,
    out: Option<&Path>,
) -> Result<(), RunError> {
    // SIGINT/SIGTERM end the runs in flight at their next tick; the rows
    // finished are tabulated and the exit is 130/143 (a re-run resumes).
    let stop = StopRequest::watching(TerminationWatch::new());
    let sweep = Sweep::load(path)?;
    let list = JobList::new(&sweep, &path.display().to_string())?;
    let base = out.map_or_else(
        || PathBuf::from("runs").join(format!("tune-{}", sweep.name)),
        Path::to_path_buf,
    );
    let dir = if shard == Shard::WHOLE {
        base
    } else {
        base.join(format!("shard-{}-of-{}", shard.index, shard.count))
    };
    let _held = write_catalog(&dir, &list.catalog, &sweep.text)?;
    let mine: Vec<_> = list
        .jobs
        .iter()
        .filter(|j| shard.holds(j.record.index))
        .collect();
    crate::outln!(
        "{}: {} runs ({} scenarios × {} settings × {} variants × {} replicas){}, {} at a time",
        sweep.name,
        list.jobs.len(),
        sweep.scenarios.len(),
        sweep.settings.len(),
        sweep.variants.len(),
        sweep.replicas,
        if shard == Shard::WHOLE {
            String::new()
        } else {
            format!("; shard {shard}: {} of them", mine.len())
        },
        threads
    )?;
    let tally = run_pending(&mine, &dir, threads, &list.catalog.scenarios, &stop)?;
    if tally.skipped > 0 {
        crate::outln!(
            "{} runs already done in {} (skipped)",
            tally.skipped,
            dir.display()
        )?;
    }
    let rows = read_rows(&dir, &list.catalog);
    let n = tabulate(&dir, &list.catalog, &rows)?;
    crate::outln!(
        "results: {}/ (results.csv: {n} runs, timings.csv, jobs.json, rows/)",
        dir.display()
    )?;
    if let Some(signal) = tally.stopped {
        return Err(RunError::Stopped {
            signal,
            dir: dir.display().to_string(),
        });
    }
    let complete: Option<Vec<JobRow>> = rows.into_iter().collect();
    match complete {
        Some(rows) => report(&dir, &list.catalog, &rows)?,
        None => {
            crate::outln!(
                "{n} of {} runs of the sweep are here: merge the shards (`shearcut tune merge`) for the front and recommendations",
                list.jobs.len()
            )?;
        }
    }
    signalled_while_writing(&stop, &dir)
}

/// A SIGINT/SIGTERM that came after the last run, while the tables and
/// analysis were written: they are written whole (the watch keeps the
/// signal from ending the process mid-file), and the command then exits
/// 130/143 saying so.
fn signalled_while_writing(stop: &StopRequest, dir: &Path) -> Result<(), RunError> {
    match stop.poll() {
        Some(signal) => Err(RunError::Signalled {
            signal,
            message: format!(
                "{signal} came while the results were written: every file is written whole in {}/",
                dir.display()
            ),
        }),
        None => Ok(()),
    }
}

/// Analyses a complete sweep in `dir` and prints the summary.
fn report(dir: &Path, catalog: &JobCatalog, rows: &[JobRow]) -> Result<(), RunError> {
    let summary = analyse(dir, catalog, rows)?;
    crate::outln!("{summary}")?;
    let has_grid = catalog.settings.iter().flatten().any(|s| s.best_constant);
    crate::outln!(
        "analysis: {}/ (summary.md, front.csv, effects.csv, front-*.svg/.png, effects-*.svg/.png, recommended/{})",
        dir.display(),
        if has_grid {
            ", best-constant.csv, constant-grid.csv"
        } else {
            ""
        }
    )?;
    Ok(())
}

/// Merges the shard directories `dirs` into `out`.
pub fn run_merge(dirs: &[PathBuf], out: Option<&Path>) -> Result<(), RunError> {
    // SIGINT/SIGTERM wait for the merge, which writes every file whole
    // and is short, and are then acted on (130/143).
    let stop = StopRequest::watching(TerminationWatch::new());
    let (catalog, _) = crate::tune::result_dir::read_catalog(
        dirs.first().map_or(Path::new("."), PathBuf::as_path),
    )?;
    let out = out.map_or_else(
        || PathBuf::from("runs").join(format!("tune-{}", catalog.sweep)),
        Path::to_path_buf,
    );
    let merged = merge(dirs, &out)?;
    let rows: Vec<_> = merged.rows.iter().cloned().map(Some).collect();
    let n = tabulate(&out, &merged.catalog, &rows)?;
    crate::outln!(
        "merged {} directories: {}/ (results.csv: {n} runs, timings.csv, jobs.json, rows/)",
        dirs.len(),
        out.display()
    )?;
    // `merged.held` keeps the directory locked until the analysis is written.
    report(&out, &merged.catalog, &merged.rows)?;
    signalled_while_writing(&stop, &out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::transport::StopSignal;

    #[test]
    fn a_signal_while_the_results_are_written_is_acted_on_after_them() {
        let stop = StopRequest::never();
        assert!(signalled_while_writing(&stop, Path::new("d")).is_ok());
        stop.request(StopSignal::Sigterm);
        let e = signalled_while_writing(&stop, Path::new("d")).unwrap_err();
        assert_eq!(e.exit_code(), 143);
        assert_eq!(
            e.to_string(),
            "SIGTERM came while the results were written: every file is written whole in d/"
        );
    }
}
