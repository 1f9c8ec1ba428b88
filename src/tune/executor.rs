//! The local executor: runs a sweep's jobs on N threads with a progress bar,
//! skipping the jobs whose row files are already there (resumption).
//!
//! Each thread takes the next pending job, runs it in process
//! ([`run_closed_loop_on`]) and writes its row file atomically
//! ([`JobRow::write`]). Runs share nothing, so the order in which threads
//! finish changes no result; the tables are written in job order from the
//! row files afterwards.

use std::path::Path;
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};

use crate::closed_loop::run_closed_loop_on;
use crate::error::RunError;
use crate::progress::run_bar;
use crate::tune::job_list::Job;
use crate::tune::job_outcome::{JobOutcome, JobRow, JobTiming};

/// What an execution did.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Tally {
    /// Jobs run now.
    pub ran: usize,
    /// Jobs whose results were already there.
    pub skipped: usize,
}

/// The machine's cores: the default of `--jobs`.
pub fn default_threads() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

/// Runs every job of `jobs` without a row file under `dir`, `threads` at a
/// time, writing each one's row file as it finishes. `names[i]` names the
/// scenario of index i in progress lines.
pub fn run_pending(
    jobs: &[&Job],
    dir: &Path,
    threads: usize,
    names: &[String],
) -> Result<Tally, RunError> {
    let rows = dir.join("rows");
    std::fs::create_dir_all(&rows).map_err(|e| RunError::write(&rows, e))?;
    let pending: Vec<&Job> = jobs
        .iter()
        .copied()
        .filter(|j| JobRow::read(dir, &j.record.id).is_none())
        .collect();
    let tally = Tally {
        ran: pending.len(),
        skipped: jobs.len() - pending.len(),
    };
    if pending.is_empty() {
        return Ok(tally);
    }
    let bar = run_bar(pending.len(), "");
    let next = AtomicUsize::new(0);
    let first_error: Mutex<Option<RunError>> = Mutex::new(None);
    let threads = threads.clamp(1, pending.len());
    std::thread::scope(|scope| {
        for _ in 0..threads {
            scope.spawn(|| {
                loop {
                    let i = next.fetch_add(1, Ordering::Relaxed);
                    let Some(job) = pending.get(i) else { break };
                    let result = run_job(job, dir);
                    let line = match &result {
                        Ok(row) => describe(job, row, names),
                        Err(e) => format!("job {}: {e}", job.record.index),
                    };
                    // A closed or full stdout stops the sweep like a failed row
                    // write (the rows written so far stay; a rerun skips them).
                    let printed = if bar.is_hidden() {
                        crate::outln!("[{}/{}] {line}", i + 1, pending.len())
                    } else {
                        bar.println(line);
                        Ok(())
                    };
                    bar.inc(1);
                    let failed = result.err().or(printed.err());
                    if let Some(e) = failed {
                        let mut slot = first_error.lock().unwrap_or_else(|p| p.into_inner());
                        slot.get_or_insert(e);
                        // No thread takes another job.
                        next.store(pending.len(), Ordering::Relaxed);
                        break;
                    }
                }
            });
        }
    });
    bar.finish_and_clear();
    match first_error.into_inner().unwrap_or_else(|p| p.into_inner()) {
        Some(e) => Err(e),
        None => Ok(tally),
    }
}

/// Runs one job and writes its row file. A run that cannot be set up is
/// a row too (`end = "error: …"`), so that a bad setting does not stop the
/// sweep; only failing to write is an error.
#[allow(clippy::disallowed_methods)] // Wall time of a job is a statistic, not a model input.
fn run_job(job: &Job, dir: &Path) -> Result<JobRow, RunError> {
    let started = std::time::Instant::now();
    let run = run_closed_loop_on(&job.scenario, job.choice, job.replica);
    let run_s = started.elapsed().as_secs_f64();
    let (outcome, loop_s, ticks, plans) = match &run {
        Ok(r) => (
            JobOutcome::from_run(r),
            r.output.wall_s,
            r.output.tick_times,
            r.output.plan_times,
        ),
        Err(e) => {
            let none = crate::closed_loop::TickTimes::from_durations(&mut []);
            (JobOutcome::from_error(e), 0.0, none, none)
        }
    };
    let mut row = JobRow {
        id: job.record.id.clone(),
        outcome,
        timing: JobTiming {
            tick_median_us: ticks.median_us,
            tick_p99_us: ticks.p99_us,
            tick_max_us: ticks.max_us,
            plan_p99_us: plans.p99_us,
            loop_s,
            run_s,
            job_s: 0.0,
        },
    };
    drop(run);
    row.timing.job_s = started.elapsed().as_secs_f64();
    row.write(dir)?;
    Ok(row)
}

/// One progress line for a finished job.
fn describe(job: &Job, row: &JobRow, names: &[String]) -> String {
    let r = &job.record;
    let o = &row.outcome;
    let name = names.get(r.scenario).map_or("?", String::as_str);
    format!(
        "job {} {name} {} (setting {}, variant {}, replica {}): work {:.4} J, max deformation {:.3} mm, peak Fv {:.2} N, {:.2} s, {} ({:.1} s)",
        r.index,
        r.controller,
        r.setting,
        r.variant,
        r.replica,
        o.work_j,
        o.max_deformation_m * 1e3,
        o.peak_force_vertical_n,
        o.duration_s,
        o.end,
        row.timing.job_s
    )
}
