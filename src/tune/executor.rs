//! The local executor: runs a batch of jobs on N threads with a progress
//! bar, in a fixed order of taking, on several threads the longest
//! expected first ([`execute`], [`dispatch_order`](crate::tune::dispatch_order)); for a
//! sweep, skipping the jobs whose row files are already there (resumption,
//! [`run_pending`]).
//!
//! Each thread takes the next job, runs it in process and hands its result
//! back in its slot of the job order. Runs share nothing, so the order in
//! which threads finish changes no result; tables are written in job order
//! afterwards. SIGINT/SIGTERM ([`StopRequest`]) end the runs in flight at
//! their next tick (those are not results) and start no other.

use std::path::Path;
use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

use crate::closed_loop::{LoopEnd, RunOutput, run_closed_loop_recorded};
use crate::error::RunError;
use crate::progress::run_bar;
use crate::transport::StopSignal;
use crate::tune::dispatch_order::{expected_ticks, longest_first};
use crate::tune::job_list::Job;
use crate::tune::job_outcome::JobRow;
use crate::tune::stop_request::{StopAtTick, StopRequest};

/// What an execution of a sweep did.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Tally {
    /// Jobs run now.
    pub ran: usize,
    /// Jobs whose results were already there.
    pub skipped: usize,
    /// The signal that stopped the execution before every job ran.
    pub stopped: Option<StopSignal>,
}

/// What a batch gave: each job's result in job order, `None` for a job
/// not run or stopped mid-run.
#[derive(Debug)]
pub struct Executed<T> {
    /// The jobs' results, in job order.
    pub results: Vec<Option<T>>,
    /// The signal that stopped the batch before every job ran.
    pub stopped: Option<StopSignal>,
}

/// How often the watcher thread looks for a signal, ms: the longest a
/// signal waits before the runs in flight are asked to stop. The watcher
/// sleeps in between (each look wakes a core), and is woken at once when
/// the batch ends.
const SIGNAL_POLL_MS: u64 = 50;

/// The machine's cores: the default of `--jobs`.
pub fn default_threads() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

/// Runs `jobs`, `threads` at a time, each thread taking the next job: with
/// more than one thread in the order of `expected` (a job's expected cost:
/// the largest first, ties in job order, [`longest_first`]), with one in
/// job order. Under a progress bar labelled `label`
/// (on a terminal; elsewhere one line per finished job, `[k/n] line`, k
/// counting the finished jobs). `run` gives a job's result, or
/// `None` when the job was stopped mid-run; `describe` its progress line.
/// The first error from `run` (or from printing a line) lets no thread
/// take another job and is returned. A stop request lets no thread take
/// another job; the results so far are returned with the signal.
pub fn execute<J: Sync, T: Send>(
    jobs: &[J],
    threads: usize,
    label: &str,
    stop: &StopRequest,
    expected: impl Fn(&J) -> f64,
    run: impl Fn(&J) -> Result<Option<T>, RunError> + Sync,
    describe: impl Fn(&J, &T) -> Option<String> + Sync,
) -> Result<Executed<T>, RunError> {
    let slots: Mutex<Vec<Option<T>>> = Mutex::new(jobs.iter().map(|_| None).collect());
    if jobs.is_empty() || stop.signal().is_some() {
        return Ok(Executed {
            results: slots.into_inner().unwrap_or_else(|p| p.into_inner()),
            stopped: stop.signal(),
        });
    }
    let bar = run_bar(jobs.len(), label);
    let next = AtomicUsize::new(0);
    let printed_lines = AtomicUsize::new(0);
    let finished = AtomicBool::new(false);
    let first_error: Mutex<Option<RunError>> = Mutex::new(None);
    let threads = threads.clamp(1, jobs.len());
    // One thread ends when its last job does, whatever the order.
    let order = if threads > 1 {
        longest_first(&jobs.iter().map(expected).collect::<Vec<_>>())
    } else {
        (0..jobs.len()).collect()
    };
    std::thread::scope(|scope| {
        let watcher = stop.is_watching().then(|| {
            scope.spawn(|| {
                while !finished.load(Ordering::Acquire) && stop.poll().is_none() {
                    std::thread::park_timeout(std::time::Duration::from_millis(SIGNAL_POLL_MS));
                }
            })
        });
        let workers: Vec<_> = (0..threads)
            .map(|_| {
                scope.spawn(|| {
                    while stop.signal().is_none() {
                        let Some(&i) = order.get(next.fetch_add(1, Ordering::Relaxed)) else {
                            break;
                        };
                        let job = &jobs[i];
                        let result = run(job);
                        // A closed or full stdout stops the batch like a
                        // failed run (the results so far stay).
                        let printed = match result.as_ref().map(|r| r.as_ref()) {
                            Ok(Some(done)) => match describe(job, done) {
                                Some(line) if bar.is_hidden() => {
                                    let k = printed_lines.fetch_add(1, Ordering::Relaxed) + 1;
                                    crate::outln!("[{k}/{}] {line}", jobs.len())
                                }
                                Some(line) => {
                                    bar.println(line);
                                    Ok(())
                                }
                                None => Ok(()),
                            },
                            _ => Ok(()),
                        };
                        bar.inc(1);
                        match result.and_then(|r| printed.map(|()| r)) {
                            Ok(done) => {
                                slots.lock().unwrap_or_else(|p| p.into_inner())[i] = done;
                            }
                            Err(e) => {
                                let mut slot =
                                    first_error.lock().unwrap_or_else(|p| p.into_inner());
                                slot.get_or_insert(e);
                                // No thread takes another job.
                                next.store(jobs.len(), Ordering::Relaxed);
                                break;
                            }
                        }
                    }
                })
            })
            .collect();
        for worker in workers {
            let _ = worker.join();
        }
        finished.store(true, Ordering::Release);
        if let Some(watcher) = watcher {
            watcher.thread().unpark();
        }
    });
    bar.finish_and_clear();
    match first_error.into_inner().unwrap_or_else(|p| p.into_inner()) {
        Some(e) => Err(e),
        None => Ok(Executed {
            results: slots.into_inner().unwrap_or_else(|p| p.into_inner()),
            stopped: stop.signal(),
        }),
    }
}

/// Runs every job of `jobs` without a row file under `dir`, `threads` at a
/// time, writing each one's row file as it finishes (a run stopped by
/// `stop` writes none: a re-run runs it). `names[i]` names the scenario of
/// index i in progress lines.
pub fn run_pending(
    jobs: &[&Job],
    dir: &Path,
    threads: usize,
    names: &[String],
    stop: &StopRequest,
) -> Result<Tally, RunError> {
    let rows = dir.join("rows");
    std::fs::create_dir_all(&rows).map_err(|e| RunError::write(&rows, e))?;
    let pending: Vec<&Job> = jobs
        .iter()
        .copied()
        .filter(|j| JobRow::read(dir, &j.record.id).is_none())
        .collect();
    let executed = execute(
        &pending,
        threads,
        "",
        stop,
        |job| expected_ticks(job),
        |job| run_job(job, dir, stop),
        |job, row| Some(describe(job, row, names)),
    )?;
    Ok(Tally {
        ran: executed.results.iter().flatten().count(),
        skipped: jobs.len() - pending.len(),
        stopped: executed.stopped,
    })
}

/// Runs one job and writes its row file. A run that cannot be set up is
/// a row too (`end = "error: …"`), so that a bad setting does not stop the
/// sweep; only failing to write is an error. A run stopped by `stop` is
/// `None`, no row.
#[allow(clippy::disallowed_methods)] // Wall time of a job is a statistic, not a model input.
fn run_job(job: &Job, dir: &Path, stop: &StopRequest) -> Result<Option<JobRow>, RunError> {
    let started = std::time::Instant::now();
    let Some((run, run_s)) = timed_run(job, stop) else {
        return Ok(None);
    };
    let mut row = JobRow::of_run(&job.record.id, &run, run_s);
    drop(run);
    row.timing.job_s = started.elapsed().as_secs_f64();
    row.write(dir)?;
    Ok(Some(row))
}

/// Runs `job` in process, ending at its next tick when `stop` is asked:
/// the run and its wall time, s; `None` if it was stopped (a stopped run is
/// not a result).
#[allow(clippy::disallowed_methods)] // A run's wall time is a statistic, not a model input.
pub(crate) fn timed_run(
    job: &Job,
    stop: &StopRequest,
) -> Option<(Result<RunOutput, RunError>, f64)> {
    let started = std::time::Instant::now();
    let run = run_closed_loop_recorded(
        &job.scenario,
        job.choice,
        job.replica,
        &mut StopAtTick(stop),
    );
    let run_s = started.elapsed().as_secs_f64();
    let stopped = matches!(&run, Ok(r) if matches!(r.output.end, LoopEnd::Stopped(_)));
    (!stopped).then_some((run, run_s))
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn results_stay_in_job_order_whatever_the_order_of_taking() {
        // Expected costs rising with the index: two threads take the jobs
        // from the last to the first; one thread in job order.
        let jobs: Vec<usize> = (0..7).collect();
        for threads in [1, 2] {
            let taken = Mutex::new(Vec::new());
            let done = execute(
                &jobs,
                threads,
                "",
                &StopRequest::never(),
                |&j| j as f64,
                |&j| {
                    taken.lock().unwrap().push(j);
                    Ok(Some(10 * j))
                },
                |_, _| None,
            )
            .unwrap();
            let want: Vec<Option<usize>> = jobs.iter().map(|j| Some(10 * j)).collect();
            assert_eq!(done.results, want);
            let mut taken = taken.into_inner().unwrap();
            if threads == 1 {
                assert_eq!(taken, jobs);
            }
            taken.sort_unstable();
            assert_eq!(taken, jobs);
        }
    }
}
