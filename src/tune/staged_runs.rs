//! Runs chosen stage by stage from earlier runs' results (`compare`'s
//! search for the best constant ratio): each stage is a small sweep on one
//! scenario as given ([`StagedRuns::sweep`]: its jobs built by the sweep's
//! job list, [`JobList`]), run as one batch on the executor
//! ([`execute`]); a job whose id was run in an earlier stage is not run
//! again, as a re-run sweep skips its finished jobs. Results stay in
//! memory; with a [`RunLog`], each finished run's row is also appended to
//! it as the run ends.

use std::collections::BTreeMap;

use crate::closed_loop::RunOutput;
use crate::controller_choice::ControllerChoice;
use crate::error::RunError;
use crate::scenario::Scenario;
use crate::transport::StopSignal;
use crate::tune::controller_setting::ControllerSetting;
use crate::tune::dispatch_order::expected_ticks;
use crate::tune::executor::{execute, timed_run};
use crate::tune::job_list::{Job, JobList};
use crate::tune::job_outcome::JobRow;
use crate::tune::perturbation::Perturbation;
use crate::tune::run_log::RunLog;
use crate::tune::stop_request::StopRequest;
use crate::tune::sweep_file::{Sweep, VariantSource};

/// One finished run of a stage.
#[derive(Debug, Clone)]
pub struct StagedRun {
    /// The job's id (its sweep's [`crate::tune::job_list::job_id`]).
    pub id: String,
    /// The controller it ran.
    pub choice: ControllerChoice,
    /// The run.
    pub output: RunOutput,
}

/// How a stage ended: the jobs that could not be set up, and the signal
/// that stopped it before every job ran.
#[derive(Debug, Default)]
pub struct StageEnd {
    /// Each failed job's controller and error, in job order.
    pub failed: Vec<(ControllerChoice, RunError)>,
    /// The signal that stopped the stage.
    pub stopped: Option<StopSignal>,
}

/// The runs of one scenario, stage by stage.
#[derive(Debug)]
pub struct StagedRuns<'a> {
    scenario: &'a Scenario,
    threads: usize,
    stop: &'a StopRequest,
    label: String,
    log: Option<&'a RunLog>,
    done: Vec<StagedRun>,
}

impl<'a> StagedRuns<'a> {
    /// No runs yet of `scenario`; stages run `threads` at a time under a
    /// progress bar labelled `label`, stopped by `stop`; each finished
    /// run's row (a run that could not be set up included) is appended to
    /// `log` as it ends.
    pub fn new(
        scenario: &'a Scenario,
        threads: usize,
        stop: &'a StopRequest,
        label: &str,
        log: Option<&'a RunLog>,
    ) -> Self {
        Self {
            scenario,
            threads,
            stop,
            label: label.to_string(),
            log,
            done: Vec::new(),
        }
    }

    /// The jobs of the sweep of `settings` on the scenario as given (one
    /// variant, no change), on replicas 0 to `replicas` − 1, in the sweep's
    /// order (settings, then replicas).
    pub fn sweep(
        &self,
        settings: Vec<ControllerSetting>,
        replicas: u32,
    ) -> Result<Vec<Job>, RunError> {
        let sweep = Sweep {
            name: self.scenario.name.clone(),
            text: String::new(),
            scenarios: vec![self.scenario.clone()],
            variants: vec![Perturbation::default()],
            variants_from: VariantSource::Scenario,
            settings,
            replicas,
            specimens: Default::default(),
            weightings: BTreeMap::new(),
        };
        Ok(JobList::new(&sweep, &self.scenario.name)?.jobs)
    }

    /// Runs the jobs of `jobs` not run before (by id; the first of equal
    /// ids) as one batch; the finished ones join [`StagedRuns::done`] in
    /// job order, a run stopped mid-way does not.
    pub fn run(&mut self, jobs: Vec<Job>) -> Result<StageEnd, RunError> {
        let mut fresh: Vec<Job> = Vec::new();
        for job in jobs {
            let id = &job.record.id;
            if !self.done.iter().any(|r| &r.id == id) && !fresh.iter().any(|j| &j.record.id == id) {
                fresh.push(job);
            }
        }
        let (stop, log) = (self.stop, self.log);
        let executed = execute(
            &fresh,
            self.threads,
            &self.label,
            stop,
            expected_ticks,
            |job| {
                let Some((run, run_s)) = timed_run(job, stop) else {
                    return Ok(None);
                };
                if let Some(log) = log {
                    log.append(job, &JobRow::of_run(&job.record.id, &run, run_s))?;
                }
                Ok(Some(run))
            },
            |job, run| run.as_ref().ok().map(|r| describe(job, r)),
        )?;
        let mut end = StageEnd {
            stopped: executed.stopped,
            ..StageEnd::default()
        };
        for (job, result) in fresh.into_iter().zip(executed.results) {
            match result {
                Some(Ok(output)) => self.done.push(StagedRun {
                    id: job.record.id,
                    choice: job.choice,
                    output,
                }),
                Some(Err(e)) => end.failed.push((job.choice, e)),
                None => {}
            }
        }
        Ok(end)
    }

    /// Every finished run, in the order of the stages and of their jobs.
    pub fn done(&self) -> &[StagedRun] {
        &self.done
    }

    /// The finished runs of controller `choice`, by replica.
    pub fn of(&self, choice: ControllerChoice) -> Vec<&RunOutput> {
        let mut runs: Vec<&RunOutput> = self
            .done
            .iter()
            .filter(|r| r.choice == choice)
            .map(|r| &r.output)
            .collect();
        runs.sort_by_key(|r| r.replica.index);
        runs
    }
}

/// One progress line for a finished run.
fn describe(job: &Job, run: &RunOutput) -> String {
    let on = match job.replica.index {
        0 => String::new(),
        k => format!(" (replica {k})"),
    };
    format!(
        "{:<25} work {:.4} J, peak Fv {:.2} N, completed {}",
        format!("{}{on}", job.choice),
        run.summary.work_j,
        run.summary.peak_force_vertical_n,
        run.summary.completed
    )
}
