//! What one job of a sweep produced, and its file `rows/<job id>.json`.
//!
//! The outcome ([`JobOutcome`]) is deterministic: the same job gives the
//! same bits on any machine, in any shard, in any order. The wall-clock
//! statistics ([`JobTiming`]) are measurements and differ from run to run;
//! they are kept apart so that the results table can be compared bit for
//! bit.
//!
//! A row file is written to a temporary name and renamed into place, so a
//! file under its job's name is always whole: an interrupted sweep leaves
//! finished jobs' files and nothing half-written, and a re-run skips them.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use shearcut_sim::capped_read::read_capped_text;

use crate::closed_loop::RunOutput;
use crate::error::RunError;

/// The deterministic result of one run (SI units).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JobOutcome {
    /// Whether the cut reached its target depth.
    pub completed: bool,
    /// How the run ended: `completed`, `timed_out`, `failed: …` (the loop
    /// failed) or `error: …` (the run could not be set up).
    pub end: String,
    /// Total knife work, J.
    #[serde(with = "lenient_f64")]
    pub work_j: f64,
    /// Largest surface deformation next to the blade, m.
    #[serde(with = "lenient_f64")]
    pub max_deformation_m: f64,
    /// Peak vertical force, N.
    #[serde(with = "lenient_f64")]
    pub peak_force_vertical_n: f64,
    /// Peak horizontal force, N.
    #[serde(with = "lenient_f64")]
    pub peak_force_horizontal_n: f64,
    /// Time to the target depth (or to the end of the run), s.
    #[serde(with = "lenient_f64")]
    pub duration_s: f64,
    /// Crack depth reached, m.
    #[serde(with = "lenient_f64")]
    pub cut_depth_m: f64,
    /// Blade used: the largest tangential displacement from the start, m.
    #[serde(with = "lenient_f64")]
    pub blade_travel_m: f64,
    /// Tangential path over all strokes, m.
    #[serde(with = "lenient_f64")]
    pub blade_path_m: f64,
    /// Reversals of the tangential direction.
    pub reversals: u32,
    /// Commands the arm refused for breaking a limit.
    pub limit_faults: usize,
    /// Plans that fell back to the previous plan.
    pub plan_fallbacks: u64,
    /// Servo ticks run.
    pub ticks: usize,
}

/// Result columns of a [`JobOutcome`], in its field order.
pub const OUTCOME_COLUMNS: [&str; 14] = [
    "completed",
    "end",
    "work_j",
    "max_deformation_m",
    "peak_force_vertical_n",
    "peak_force_horizontal_n",
    "duration_s",
    "cut_depth_m",
    "blade_travel_m",
    "blade_path_m",
    "reversals",
    "limit_faults",
    "plan_fallbacks",
    "ticks",
];

/// Wall-clock statistics of one job (measured; not reproducible).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JobTiming {
    /// Median of the controller's ticks, µs.
    pub tick_median_us: f64,
    /// 99th percentile of the controller's ticks, µs.
    pub tick_p99_us: f64,
    /// Longest controller tick, µs.
    pub tick_max_us: f64,
    /// 99th percentile of the planning ticks, µs (0 without plans).
    pub plan_p99_us: f64,
    /// 99th percentile of the plans themselves on the planner thread, µs
    /// (0 without a planner thread).
    pub solve_p99_us: f64,
    /// The loop itself, first command to last answer, s.
    pub loop_s: f64,
    /// The whole run: set-up (knife, object, surrogate, controller,
    /// plant) and loop, s.
    pub run_s: f64,
    /// The whole job: the run and summarising it, s (the row file's write
    /// that follows, a few kB, is not included).
    pub job_s: f64,
}

/// Result columns of a [`JobTiming`], in its field order.
pub const TIMING_COLUMNS: [&str; 8] = [
    "tick_median_us",
    "tick_p99_us",
    "tick_max_us",
    "plan_p99_us",
    "solve_p99_us",
    "loop_s",
    "run_s",
    "job_s",
];

impl JobOutcome {
    /// The outcome of a run.
    pub fn from_run(run: &RunOutput) -> Self {
        let c = &run.summary;
        let o = &run.output;
        Self {
            completed: c.completed,
            end: o.end.label(),
            work_j: c.work_j,
            max_deformation_m: c.max_deformation_m,
            peak_force_vertical_n: c.peak_force_vertical_n,
            peak_force_horizontal_n: c.peak_force_horizontal_n,
            duration_s: c.duration_s,
            cut_depth_m: c.cut_depth_m,
            blade_travel_m: c.blade_travel_m,
            blade_path_m: c.blade_path_m,
            reversals: c.reversals,
            limit_faults: o.limit_faults,
            plan_fallbacks: o.fallbacks,
            ticks: o.ticks,
        }
    }

    /// The outcome of a run that could not be set up: not completed, every
    /// number NaN.
    pub fn from_error(e: &RunError) -> Self {
        Self {
            completed: false,
            end: format!("error: {e}"),
            work_j: f64::NAN,
            max_deformation_m: f64::NAN,
            peak_force_vertical_n: f64::NAN,
            peak_force_horizontal_n: f64::NAN,
            duration_s: f64::NAN,
            cut_depth_m: f64::NAN,
            blade_travel_m: f64::NAN,
            blade_path_m: f64::NAN,
            reversals: 0,
            limit_faults: 0,
            plan_fallbacks: 0,
            ticks: 0,
        }
    }

    /// The outcome's cells, in [`OUTCOME_COLUMNS`]' order (numbers in
    /// their shortest exact form).
    pub fn cells(&self) -> Vec<String> {
        let f = crate::tune::perturbation::float_cell;
        vec![
            self.completed.to_string(),
            self.end.clone(),
            f(self.work_j),
            f(self.max_deformation_m),
            f(self.peak_force_vertical_n),
            f(self.peak_force_horizontal_n),
            f(self.duration_s),
            f(self.cut_depth_m),
            f(self.blade_travel_m),
            f(self.blade_path_m),
            self.reversals.to_string(),
            self.limit_faults.to_string(),
            self.plan_fallbacks.to_string(),
            self.ticks.to_string(),
        ]
    }
}

impl JobTiming {
    /// The timing's cells, in [`TIMING_COLUMNS`]' order.
    pub fn cells(&self) -> Vec<String> {
        [
            self.tick_median_us,
            self.tick_p99_us,
            self.tick_max_us,
            self.plan_p99_us,
            self.solve_p99_us,
            self.loop_s,
            self.run_s,
            self.job_s,
        ]
        .map(crate::tune::perturbation::float_cell)
        .to_vec()
    }
}

/// The content of `rows/<id>.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JobRow {
    /// The job's id ([`crate::tune::job_list::Job::id`]).
    pub id: String,
    /// What the run gave.
    pub outcome: JobOutcome,
    /// How long it took.
    pub timing: JobTiming,
}

impl JobRow {
    /// The row of job `id` from its run, or from its set-up's failure (an
    /// `error: …` outcome, [`JobOutcome::from_error`]); `run_s` is the
    /// run's wall time, s, which the row's `job_s` starts equal to.
    pub fn of_run(id: &str, run: &Result<RunOutput, RunError>, run_s: f64) -> Self {
        let (outcome, loop_s, ticks, plans, solves) = match run {
            Ok(r) => (
                JobOutcome::from_run(r),
                r.output.wall_s,
                r.output.tick_times,
                r.output.plan_times,
                r.output.solve_times,
            ),
            Err(e) => {
                let none = crate::closed_loop::TickTimes::from_durations(&mut []);
                (JobOutcome::from_error(e), 0.0, none, none, none)
            }
        };
        Self {
            id: id.to_string(),
            outcome,
            timing: JobTiming {
                tick_median_us: ticks.median_us,
                tick_p99_us: ticks.p99_us,
                tick_max_us: ticks.max_us,
                plan_p99_us: plans.p99_us,
                solve_p99_us: solves.p99_us,
                loop_s,
                run_s,
                job_s: run_s,
            },
        }
    }

    /// The row file of job `id` under `dir`: `dir/rows/<id>.json`.
    pub fn path(dir: &Path, id: &str) -> PathBuf {
        dir.join("rows").join(format!("{id}.json"))
    }

    /// Writes the row under `dir` whole or not at all
    /// ([`crate::result_file::publish`]): the rows directory holds whole
    /// rows only.
    pub fn write(&self, dir: &Path) -> Result<(), RunError> {
        crate::result_file::write_json(&Self::path(dir, &self.id), self)
    }

    /// Reads job `id`'s row under `dir`; `None` if there is none, or it is
    /// unreadable (not a regular file, over [`ROW_BYTES`]) or of another
    /// job (it is then run again).
    pub fn read(dir: &Path, id: &str) -> Option<Self> {
        let text = read_capped_text(&Self::path(dir, id), ROW_BYTES).ok()?;
        let row: Self = serde_json::from_str(&text).ok()?;
        (row.id == id).then_some(row)
    }
}

/// Largest row file read back, bytes: a row is a few kilobytes; a pipe,
/// or an endless device or a file past this size, is not read as a row.
pub const ROW_BYTES: u64 = 1 << 20;

/// An `f64` in JSON: a number when finite, else the string `NaN`, `inf`
/// or `-inf` (JSON has no such numbers; a run that could not be set up has
/// NaN results).
mod lenient_f64 {
    use serde::{Deserialize, Deserializer, Serializer};

    pub fn serialize<S: Serializer>(x: &f64, s: S) -> Result<S::Ok, S::Error> {
        if x.is_finite() {
            s.serialize_f64(*x)
        } else {
            s.serialize_str(&format!("{x}"))
        }
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
        #[derive(Deserialize)]
        #[serde(untagged)]
        enum NumberOrText {
            Number(f64),
            Text(String),
        }
        match NumberOrText::deserialize(d)? {
            NumberOrText::Number(x) => Ok(x),
            NumberOrText::Text(t) => t.parse().map_err(serde::de::Error::custom),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_row_reads_back_bit_for_bit_even_when_not_a_number() {
        let dir = std::env::temp_dir().join(format!("shearcut-row-{}", std::process::id()));
        std::fs::create_dir_all(dir.join("rows")).unwrap();
        let mut outcome = JobOutcome::from_error(&RunError::Loop("x".into()));
        outcome.work_j = 0.1 + 0.2;
        outcome.duration_s = f64::INFINITY;
        let row = JobRow {
            id: "abc".into(),
            outcome,
            timing: JobTiming {
                tick_median_us: 1.0 / 3.0,
                tick_p99_us: 2.0,
                tick_max_us: 3.0,
                plan_p99_us: 0.0,
                solve_p99_us: 0.0,
                loop_s: 1e-7,
                run_s: 2.5,
                job_s: 2.6,
            },
        };
        row.write(&dir).unwrap();
        let back = JobRow::read(&dir, "abc").unwrap();
        assert_eq!(back.outcome.cells(), row.outcome.cells());
        assert_eq!(back.outcome.work_j.to_bits(), (0.1_f64 + 0.2).to_bits());
        assert!(back.outcome.max_deformation_m.is_nan());
        assert_eq!(back.timing, row.timing);
        assert!(JobRow::read(&dir, "other").is_none());
        // An endless file in a row's place is not read whole: no row.
        #[cfg(unix)]
        {
            std::os::unix::fs::symlink("/dev/zero", JobRow::path(&dir, "endless")).unwrap();
            assert!(JobRow::read(&dir, "endless").is_none());
            std::fs::remove_file(JobRow::path(&dir, "endless")).unwrap();
        }

        // A row that cannot be put in place (here a directory holds its
        // name, as a full device fails a write) is an error and leaves no
        // temporary file behind.
        let blocked = JobRow {
            id: "blocked".into(),
            ..row
        };
        std::fs::create_dir_all(JobRow::path(&dir, "blocked").join("x")).unwrap();
        assert!(blocked.write(&dir).is_err());
        let names: Vec<String> = std::fs::read_dir(dir.join("rows"))
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        assert!(
            names
                .iter()
                .all(|n| !n.starts_with(crate::result_file::PARTIAL_PREFIX)),
            "{names:?}"
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
