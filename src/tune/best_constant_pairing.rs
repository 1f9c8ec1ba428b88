//! The MPC against the best constant slice-push ratio on each variant of a
//! sweep, replica by replica: `best-constant.csv` and a section of
//! `summary.md`.
//!
//! For each scenario, variant and MPC setting, the best constant is the
//! point of the sweep's best-constant grid ([`crate::tune::constant_grid`])
//! with the least mean work over the variant's replicas, among the points
//! that completed every run ([`least_mean_work`], as `compare` chooses it,
//! without `compare`'s refinement around the grid's best: on a coarse grid
//! the best constant is a little worse than `compare`'s, in the MPC's
//! favour). The MPC's work and maximum deformation are then compared with
//! that ratio's on the same replicas ([`PairedDifference`]: mean of the
//! differences per cent of the constant's mean, its standard error, the
//! range of the single differences).

use std::path::Path;

use crate::commands::compare::PairedDifference;
use crate::constant_ratio::{completed_mean_work, least_mean_work};
use crate::error::RunError;
use crate::tune::job_list::{JobCatalog, JobRecord};
use crate::tune::job_outcome::JobRow;
use crate::tune::perturbation::float_cell;

/// The MPC's mean paired work difference that counts as no more work than
/// the best constant's, per cent (issue #28's bar).
pub const WORK_TIE_PERCENT: f64 = 0.5;
/// Less work that counts as a clear win, per cent.
pub const WORK_WIN_PERCENT: f64 = 3.0;
/// Less maximum deformation that counts as a clear win, per cent.
pub const DEFORMATION_WIN_PERCENT: f64 = 30.0;

/// One MPC setting against the best constant on one variant of a scenario.
#[derive(Debug, Clone, PartialEq)]
pub struct BestConstantPair {
    /// Index of the scenario in the sweep.
    pub scenario: usize,
    /// Index of the variant in the sweep.
    pub variant: usize,
    /// Index of the MPC's setting in the sweep.
    pub mpc_setting: usize,
    /// The best constant's grid point (its setting index), `None` if no
    /// point completed every run on the variant.
    pub best_setting: Option<usize>,
    /// The best constant's controller on the variant (e.g. `slice:0.48`;
    /// empty without one).
    pub best_controller: String,
    /// Replicas both ran on.
    pub replicas: usize,
    /// Whether every MPC run on the variant reached the target depth.
    pub mpc_completed: bool,
    /// Mean work of the MPC's runs, J.
    pub mpc_work_j: f64,
    /// Mean work of the best constant's runs, J (NaN without one).
    pub constant_work_j: f64,
    /// Mean maximum deformation of the MPC's runs, m.
    pub mpc_max_deformation_m: f64,
    /// Mean maximum deformation of the best constant's runs, m.
    pub constant_max_deformation_m: f64,
    /// The MPC's work against the constant's (`None` unless both completed
    /// on the same replicas).
    pub work: Option<PairedDifference>,
    /// The MPC's maximum deformation against the constant's.
    pub deformation: Option<PairedDifference>,
    /// Largest 99th percentile of the MPC's planning ticks over its runs,
    /// µs (measured: wall clock).
    pub mpc_plan_p99_us: f64,
}

impl BestConstantPair {
    /// Whether the MPC meets the bar on this variant: mean paired work
    /// difference ≤ [`WORK_TIE_PERCENT`] and no more deformation than the
    /// best constant (mean paired difference ≤ 0).
    pub fn no_worse(&self) -> bool {
        matches!((&self.work, &self.deformation), (Some(w), Some(d))
            if w.mean_percent <= WORK_TIE_PERCENT && d.mean_percent <= 0.0)
    }

    /// Whether the MPC wins clearly: ≥ [`WORK_WIN_PERCENT`] less work or
    /// ≥ [`DEFORMATION_WIN_PERCENT`] less deformation (mean paired).
    pub fn clear_win(&self) -> bool {
        let work = self
            .work
            .as_ref()
            .is_some_and(|w| w.mean_percent <= -WORK_WIN_PERCENT);
        let deformation = self
            .deformation
            .as_ref()
            .is_some_and(|d| d.mean_percent <= -DEFORMATION_WIN_PERCENT);
        work || deformation
    }
}

/// The runs of one (scenario, setting, variant), in replica order.
fn runs_of<'a>(
    finished: &[(&'a JobRecord, &'a JobRow)],
    scenario: usize,
    setting: usize,
    variant: usize,
) -> Vec<(&'a JobRecord, &'a JobRow)> {
    let mut runs: Vec<_> = finished
        .iter()
        .filter(|(j, _)| j.scenario == scenario && j.setting == setting && j.variant == variant)
        .copied()
        .collect();
    runs.sort_by_key(|(j, _)| j.replica);
    runs
}

/// The pairs of a finished sweep (every job with its row): one per
/// scenario, variant and MPC setting, if the sweep has a best-constant
/// grid (empty otherwise).
pub fn pairs(catalog: &JobCatalog, finished: &[(&JobRecord, &JobRow)]) -> Vec<BestConstantPair> {
    let kind_column = catalog
        .setting_columns
        .iter()
        .position(|c| c == "controller.kind");
    let mut out = Vec::new();
    for (si, settings) in catalog.settings.iter().enumerate() {
        let grid: Vec<usize> = (0..settings.len())
            .filter(|&k| settings[k].best_constant)
            .collect();
        let mpcs = (0..settings.len()).filter(|&k| settings[k].controller == "mpc");
        if grid.is_empty() {
            continue;
        }
        for mpc in mpcs {
            for variant in 0..catalog.variants.len().max(1) {
                let mpc_runs = runs_of(finished, si, mpc, variant);
                if mpc_runs.is_empty() {
                    continue;
                }
                let mean_work = |k: usize| {
                    completed_mean_work(
                        runs_of(finished, si, k, variant)
                            .iter()
                            .map(|(_, r)| (r.outcome.work_j, r.outcome.completed)),
                    )
                };
                let best = least_mean_work(grid.iter().map(|&k| (k, mean_work(k))));
                let of = |k| runs_of(finished, si, k, variant);
                out.push(pair([si, variant, mpc], &mpc_runs, best, of, kind_column));
            }
        }
    }
    out
}

/// The pair of the MPC's runs and the runs of grid point `best` (found by
/// `runs`), on the replicas both have, for [scenario, variant, MPC
/// setting] `at`.
fn pair<'a>(
    at: [usize; 3],
    mpc_runs: &[(&'a JobRecord, &'a JobRow)],
    best: Option<usize>,
    runs: impl Fn(usize) -> Vec<(&'a JobRecord, &'a JobRow)>,
    kind_column: Option<usize>,
) -> BestConstantPair {
    let constant_runs = best.map(&runs).unwrap_or_default();
    let on_both: Vec<(&JobRow, &JobRow)> = mpc_runs
        .iter()
        .filter_map(|(j, r)| {
            constant_runs
                .iter()
                .find(|(c, _)| c.replica == j.replica)
                .map(|(_, c)| (*r, *c))
        })
        .collect();
    let mean = |xs: Vec<f64>| {
        if xs.is_empty() {
            f64::NAN
        } else {
            xs.iter().sum::<f64>() / xs.len() as f64
        }
    };
    let mpc_completed = mpc_runs.iter().all(|(_, r)| r.outcome.completed);
    let all_completed =
        mpc_completed && on_both.iter().all(|(_, c)| c.outcome.completed) && !on_both.is_empty();
    let best_controller = constant_runs
        .first()
        .and_then(|(j, _)| kind_column.and_then(|i| j.cells.get(i)).cloned())
        .unwrap_or_default();
    let paired = |of: fn(&JobRow) -> f64| {
        let (a, b): (Vec<f64>, Vec<f64>) = on_both.iter().map(|(m, c)| (of(m), of(c))).unzip();
        all_completed
            .then(|| PairedDifference::from_values(&best_controller, &a, &b))
            .flatten()
    };
    let [scenario, variant, mpc_setting] = at;
    BestConstantPair {
        scenario,
        variant,
        mpc_setting,
        best_setting: best,
        best_controller: best_controller.clone(),
        replicas: on_both.len(),
        mpc_completed,
        mpc_work_j: mean(mpc_runs.iter().map(|(_, r)| r.outcome.work_j).collect()),
        constant_work_j: mean(
            constant_runs
                .iter()
                .map(|(_, r)| r.outcome.work_j)
                .collect(),
        ),
        mpc_max_deformation_m: mean(
            mpc_runs
                .iter()
                .map(|(_, r)| r.outcome.max_deformation_m)
                .collect(),
        ),
        constant_max_deformation_m: mean(
            constant_runs
                .iter()
                .map(|(_, r)| r.outcome.max_deformation_m)
                .collect(),
        ),
        work: paired(|r| r.outcome.work_j),
        deformation: paired(|r| r.outcome.max_deformation_m),
        mpc_plan_p99_us: mpc_runs
            .iter()
            .map(|(_, r)| r.timing.plan_p99_us)
            .fold(0.0, f64::max),
    }
}

/// Columns of `best-constant.csv`.
const COLUMNS: [&str; 22] = [
    "scenario",
    "variant",
    "variant_name",
    "mpc_setting",
    "mpc_overrides",
    "best_constant",
    "replicas",
    "mpc_completed",
    "mpc_work_j",
    "constant_work_j",
    "work_diff_percent",
    "work_diff_se_percent",
    "work_diff_min_percent",
    "work_diff_max_percent",
    "mpc_lower_work",
    "mpc_max_deformation_m",
    "constant_max_deformation_m",
    "deformation_diff_percent",
    "deformation_diff_se_percent",
    "deformation_diff_min_percent",
    "deformation_diff_max_percent",
    "mpc_lower_deformation",
];

/// The cells of a paired difference: mean, standard error, least, most
/// (per cent) and the MPC-lower count; empty without one.
fn difference_cells(d: &Option<PairedDifference>) -> Vec<String> {
    match d {
        Some(d) => vec![
            float_cell(d.mean_percent),
            d.standard_error_percent.map_or(String::new(), float_cell),
            float_cell(d.range_percent[0]),
            float_cell(d.range_percent[1]),
            d.mpc_lower.to_string(),
        ],
        None => vec![String::new(); 5],
    }
}

/// Writes `best-constant.csv` under `dir` (deterministic: the timings are
/// left to `timings.csv`) and returns the summary's section (markdown,
/// with the MPC's planning p99, measured); nothing without pairs.
pub fn write_pairs(
    dir: &Path,
    catalog: &JobCatalog,
    pairs: &[BestConstantPair],
) -> Result<String, RunError> {
    if pairs.is_empty() {
        return Ok(String::new());
    }
    let path = dir.join("best-constant.csv");
    let mut w = csv::Writer::from_path(&path).map_err(|e| RunError::write(&path, e))?;
    w.write_record(COLUMNS)
        .map_err(|e| RunError::write(&path, e))?;
    let variant_name = |v: usize| catalog.variants.get(v).cloned().unwrap_or_default();
    let overrides = |p: &BestConstantPair| {
        catalog.settings[p.scenario][p.mpc_setting]
            .overrides
            .join("; ")
    };
    for p in pairs {
        let mut cells = vec![
            catalog.scenarios[p.scenario].clone(),
            p.variant.to_string(),
            variant_name(p.variant),
            p.mpc_setting.to_string(),
            overrides(p),
            p.best_controller.clone(),
            p.replicas.to_string(),
            p.mpc_completed.to_string(),
            float_cell(p.mpc_work_j),
            float_cell(p.constant_work_j),
        ];
        cells.extend(difference_cells(&p.work));
        cells.push(float_cell(p.mpc_max_deformation_m));
        cells.push(float_cell(p.constant_max_deformation_m));
        cells.extend(difference_cells(&p.deformation));
        w.write_record(cells)
            .map_err(|e| RunError::write(&path, e))?;
    }
    w.flush().map_err(|e| RunError::write(&path, e))?;
    Ok(markdown(catalog, pairs))
}

/// The summary's section: one row per pair, then the tallies against the
/// bars.
fn markdown(catalog: &JobCatalog, pairs: &[BestConstantPair]) -> String {
    let mut t = String::from(
        "\n## The MPC against the best constant ratio, per variant\n\n\
         Paired over the replicas: mean of (MPC − best constant) per cent of the constant's mean \
         ± its standard error [least, most single difference]; plan p99 is measured (wall clock, \
         the largest over the MPC's runs).\n\n\
         | scenario | variant | MPC setting | best constant | replicas | MPC work (J) | constant work (J) | work, MPC − constant | lower on | MPC / constant max deformation (mm) | deformation, MPC − constant | plan p99 (ms) |\n\
         |---|---|---|---|---|---|---|---|---|---|---|---|\n",
    );
    let describe = |d: &Option<PairedDifference>| match d {
        Some(d) => format!(
            "{:+.2} %{} [{:+.2}, {:+.2}]",
            d.mean_percent,
            d.standard_error_percent
                .map_or(String::new(), |e| format!(" ± {e:.2}")),
            d.range_percent[0],
            d.range_percent[1]
        ),
        None => "—".to_string(),
    };
    for p in pairs {
        let settings = &catalog.settings[p.scenario][p.mpc_setting];
        let name = if settings.overrides.is_empty() {
            format!("{} (as given)", p.mpc_setting)
        } else {
            format!("{} ({})", p.mpc_setting, settings.overrides.join(", "))
        };
        t += &format!(
            "| {} | {} | {} | {} | {} | {:.4}{} | {:.4} | {} | {} | {:.3} / {:.3} | {} | {:.2} |\n",
            catalog.scenarios[p.scenario],
            catalog.variants.get(p.variant).map_or("", String::as_str),
            name,
            if p.best_controller.is_empty() {
                "none completed"
            } else {
                &p.best_controller
            },
            p.replicas,
            p.mpc_work_j,
            if p.mpc_completed { "" } else { " (short)" },
            p.constant_work_j,
            describe(&p.work),
            p.work.as_ref().map_or("—".to_string(), |w| format!(
                "{} of {}",
                w.mpc_lower, w.replicas
            )),
            1e3 * p.mpc_max_deformation_m,
            1e3 * p.constant_max_deformation_m,
            describe(&p.deformation),
            1e-3 * p.mpc_plan_p99_us,
        );
    }
    let no_worse = pairs.iter().filter(|p| p.no_worse()).count();
    let wins = pairs.iter().filter(|p| p.clear_win()).count();
    t += &format!(
        "\nNo more work (≤ +{WORK_TIE_PERCENT} %) and no more deformation than the best constant: \
         {no_worse} of {}. At least {WORK_WIN_PERCENT} % less work or {DEFORMATION_WIN_PERCENT} % \
         less deformation: {wins} of {}.\n",
        pairs.len(),
        pairs.len()
    );
    t
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tune::job_list::SettingRecord;
    use crate::tune::job_outcome::{JobOutcome, JobTiming};

    fn setting(controller: &str, best_constant: bool) -> SettingRecord {
        SettingRecord {
            controller: controller.into(),
            best_constant,
            overrides: Vec::new(),
            controller_toml: String::new(),
        }
    }

    fn row(work: f64, deformation: f64, completed: bool) -> JobRow {
        let mut outcome = JobOutcome::from_error(&RunError::Loop("x".into()));
        outcome.completed = completed;
        outcome.work_j = work;
        outcome.max_deformation_m = deformation;
        JobRow {
            id: String::new(),
            outcome,
            timing: JobTiming {
                tick_median_us: 0.0,
                tick_p99_us: 0.0,
                tick_max_us: 0.0,
                plan_p99_us: 700.0,
                solve_p99_us: 0.0,
                loop_s: 0.0,
                run_s: 0.0,
                job_s: 0.0,
            },
        }
    }

    #[test]
    fn the_mpc_meets_the_least_mean_work_of_the_completed_grid_points() {
        // Settings: the MPC, then three grid points; two replicas of one
        // variant. Point 1 has the least single run but did not complete
        // one replica; point 3's mean (1.00 J) beats point 2's (1.01 J).
        let settings = vec![
            setting("mpc", false),
            setting("best-constant:0/2", true),
            setting("best-constant:1/2", true),
            setting("best-constant:2/2", true),
        ];
        let table = [
            (0, 0, 0.98, 1.0e-4, true),
            (0, 1, 1.00, 1.2e-4, true),
            (1, 0, 0.90, 1.0e-4, true),
            (1, 1, 0.91, 1.0e-4, false),
            (2, 0, 1.00, 2.0e-4, true),
            (2, 1, 1.02, 2.0e-4, true),
            (3, 0, 0.99, 1.0e-4, true),
            (3, 1, 1.01, 1.0e-4, true),
        ];
        let jobs: Vec<JobRecord> = table
            .iter()
            .enumerate()
            .map(|(index, &(setting, replica, ..))| JobRecord {
                index,
                id: index.to_string(),
                scenario: 0,
                setting,
                variant: 0,
                replica,
                controller: String::new(),
                cells: vec![format!("slice:0.{setting}")],
            })
            .collect();
        let rows: Vec<JobRow> = table.iter().map(|&(_, _, w, d, c)| row(w, d, c)).collect();
        let catalog = JobCatalog {
            sweep: "s".into(),
            scenarios: vec!["potato".into()],
            variants: vec!["as given".into()],
            settings: vec![settings],
            setting_columns: vec!["controller.kind".into()],
            jobs: jobs.clone(),
            weightings: Default::default(),
        };
        let finished: Vec<(&JobRecord, &JobRow)> = jobs.iter().zip(&rows).collect();
        let found = pairs(&catalog, &finished);
        assert_eq!(found.len(), 1);
        let p = &found[0];
        assert_eq!(
            (p.best_setting, p.best_controller.as_str()),
            (Some(3), "slice:0.3")
        );
        // Differences −0.01 J on both replicas: −1 % of 1.00 J, no spread.
        let w = p.work.as_ref().unwrap();
        assert!((w.mean_percent + 1.0).abs() < 1e-9, "{w:?}");
        assert!(w.standard_error_percent.unwrap() < 1e-9);
        assert_eq!(w.mpc_lower, 2);
        // Deformation +0 and +0.2e-4 m: +10 % of 1e-4 m on average.
        let d = p.deformation.as_ref().unwrap();
        assert!((d.mean_percent - 10.0).abs() < 1e-9, "{d:?}");
        assert!(!p.no_worse() && !p.clear_win());
        assert_eq!(p.mpc_plan_p99_us, 700.0);
        let text = markdown(&catalog, &found);
        assert!(
            text.contains("| potato | as given | 0 (as given) | slice:0.3 | 2 |"),
            "{text}"
        );
        assert!(text.contains("-1.00 % ± 0.00 [-1.00, -1.00]"), "{text}");
        assert!(text.contains(": 0 of 1."), "{text}");
    }
}
