//! A finished sweep written as a table, for the analyses' unit tests: one
//! scenario, the MPC as setting 0 and a best-constant grid after it, and
//! one run per row.

use crate::error::RunError;
use crate::tune::job_list::{JobCatalog, JobRecord, SettingRecord};
use crate::tune::job_outcome::{JobOutcome, JobRow, JobTiming};

/// One run of the table.
#[derive(Debug, Clone, Copy)]
pub struct Run {
    /// Setting index (0: the MPC; k ≥ 1: grid point k − 1).
    pub setting: usize,
    /// Variant index.
    pub variant: usize,
    /// Replica.
    pub replica: u32,
    /// Work, J.
    pub work: f64,
    /// Maximum deformation, m.
    pub deformation: f64,
    /// Whether the run reached the target depth.
    pub completed: bool,
}

/// The finished sweep: its catalog, and each job with its row.
pub struct FinishedSweep {
    /// The sweep's catalog.
    pub catalog: JobCatalog,
    /// The jobs, one per run.
    pub jobs: Vec<JobRecord>,
    /// The rows, one per job.
    pub rows: Vec<JobRow>,
}

impl FinishedSweep {
    /// Scenario `scenario` with `variants`, the MPC and a grid of
    /// `points` points (`best-constant:i/(points − 1)`), and `runs`. A grid
    /// point's controller kind is `slice:0.k` for setting k; every MPC run's
    /// planning p99 is 700 µs.
    pub fn new(scenario: &str, variants: &[&str], points: usize, runs: &[Run]) -> Self {
        let mut settings = vec![setting("mpc", false)];
        settings.extend(
            (0..points).map(|i| setting(&format!("best-constant:{i}/{}", points - 1), true)),
        );
        let jobs = runs
            .iter()
            .enumerate()
            .map(|(index, r)| JobRecord {
                index,
                id: index.to_string(),
                scenario: 0,
                setting: r.setting,
                variant: r.variant,
                replica: r.replica,
                controller: String::new(),
                cells: vec![format!("slice:0.{}", r.setting)],
            })
            .collect::<Vec<_>>();
        let rows = runs.iter().map(row).collect();
        let catalog = JobCatalog {
            sweep: "s".into(),
            scenarios: vec![scenario.into()],
            variants: variants.iter().map(|v| v.to_string()).collect(),
            settings: vec![settings],
            setting_columns: vec!["controller.kind".into()],
            jobs: jobs.clone(),
            weightings: Default::default(),
        };
        Self {
            catalog,
            jobs,
            rows,
        }
    }

    /// Each job with its row, as an analysis takes them.
    pub fn finished(&self) -> Vec<(&JobRecord, &JobRow)> {
        self.jobs.iter().zip(&self.rows).collect()
    }
}

/// A setting with no overrides.
fn setting(controller: &str, best_constant: bool) -> SettingRecord {
    SettingRecord {
        controller: controller.into(),
        best_constant,
        overrides: Vec::new(),
        controller_toml: String::new(),
    }
}

/// The row of a run.
fn row(r: &Run) -> JobRow {
    let mut outcome = JobOutcome::from_error(&RunError::Loop("x".into()));
    outcome.completed = r.completed;
    outcome.work_j = r.work;
    outcome.max_deformation_m = r.deformation;
    JobRow {
        id: String::new(),
        outcome,
        timing: JobTiming {
            tick_median_us: 0.0,
            tick_p99_us: 0.0,
            tick_max_us: 0.0,
            plan_p99_us: 700.0,
            solve_p99_us: 450.0,
            loop_s: 0.0,
            run_s: 0.0,
            job_s: 0.0,
        },
    }
}
