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
//! range of the single differences). The same pairing, with each point of
//! the grid in turn, serves [`crate::tune::uniform_constant`].

use std::path::Path;

use crate::commands::compare::PairedDifference;
use crate::constant_ratio::{completed_mean_work, least_mean_work};
use crate::error::RunError;
use crate::result_file::write_table;
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

/// One MPC setting against one constant of the grid (in `best-constant.csv`
/// the best) on one variant of a scenario.
#[derive(Debug, Clone, PartialEq)]
pub struct ConstantPair {
    /// Index of the scenario in the sweep.
    pub scenario: usize,
    /// Index of the variant in the sweep.
    pub variant: usize,
    /// Index of the MPC's setting in the sweep.
    pub mpc_setting: usize,
    /// The constant's grid point (its setting index); for the best
    /// constant, `None` if no point completed every run on the variant.
    pub constant_setting: Option<usize>,
    /// The constant's controller on the variant (e.g. `slice:0.48`; empty
    /// without one).
    pub constant_controller: String,
    /// Replicas both ran on.
    pub replicas: usize,
    /// Whether every MPC run on the variant reached the target depth.
    pub mpc_completed: bool,
    /// Whether every run of the constant on the variant reached the
    /// target depth (false without one).
    pub constant_completed: bool,
    /// Mean work of the MPC's runs, J.
    pub mpc_work_j: f64,
    /// Mean work of the constant's runs, J (NaN without one).
    pub constant_work_j: f64,
    /// Mean maximum deformation of the MPC's runs, m.
    pub mpc_max_deformation_m: f64,
    /// Mean maximum deformation of the constant's runs, m.
    pub constant_max_deformation_m: f64,
    /// The MPC's work against the constant's (`None` unless both completed
    /// on the same replicas).
    pub work: Option<PairedDifference>,
    /// The MPC's maximum deformation against the constant's.
    pub deformation: Option<PairedDifference>,
    /// Largest 99th percentile of the MPC's planning ticks over its runs,
    /// µs (measured: wall clock): the ticks that receive a plan, which in
    /// lockstep wait for the planner thread.
    pub mpc_plan_p99_us: f64,
    /// Largest 99th percentile of the MPC's plans themselves on its planner
    /// thread over its runs, µs (measured: wall clock; issue #28's
    /// planning time).
    pub mpc_solve_p99_us: f64,
}

impl ConstantPair {
    /// Whether the MPC meets the bar on this variant: mean paired work
    /// difference ≤ [`WORK_TIE_PERCENT`] and no more deformation than the
    /// constant (mean paired difference ≤ 0).
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

/// One scenario, MPC setting and variant of a sweep with a best-constant
/// grid, and the runs to pair.
pub(crate) struct PairGroup<'a> {
    /// Index of the scenario in the sweep.
    pub scenario: usize,
    /// Index of the MPC's setting in the sweep.
    pub mpc_setting: usize,
    /// Index of the variant in the sweep.
    pub variant: usize,
    /// The grid's settings (indices in the sweep), pressing first.
    pub grid: Vec<usize>,
    /// The MPC's runs on the variant, in replica order (not empty).
    pub mpc_runs: Vec<(&'a JobRecord, &'a JobRow)>,
}

/// The groups of a finished sweep (every job with its row): one per
/// scenario with a best-constant grid, MPC setting and variant the MPC
/// ran on, in that order.
pub(crate) fn groups<'a>(
    catalog: &JobCatalog,
    finished: &[(&'a JobRecord, &'a JobRow)],
) -> Vec<PairGroup<'a>> {
    let mut out = Vec::new();
    for (scenario, settings) in catalog.settings.iter().enumerate() {
        let grid: Vec<usize> = (0..settings.len())
            .filter(|&k| settings[k].best_constant)
            .collect();
        if grid.is_empty() {
            continue;
        }
        let mpcs = (0..settings.len()).filter(|&k| settings[k].controller == "mpc");
        for mpc_setting in mpcs {
            for variant in 0..catalog.variants.len().max(1) {
                let mpc_runs = runs_of(finished, scenario, mpc_setting, variant);
                if !mpc_runs.is_empty() {
                    out.push(PairGroup {
                        scenario,
                        mpc_setting,
                        variant,
                        grid: grid.clone(),
                        mpc_runs,
                    });
                }
            }
        }
    }
    out
}

/// The mean work of grid setting `k`'s runs on the group's variant, if
/// every one completed ([`completed_mean_work`]).
pub(crate) fn grid_mean_work(
    finished: &[(&JobRecord, &JobRow)],
    g: &PairGroup,
    k: usize,
) -> Option<f64> {
    completed_mean_work(
        runs_of(finished, g.scenario, k, g.variant)
            .iter()
            .map(|(_, r)| (r.outcome.work_j, r.outcome.completed)),
    )
}

/// The column of the controller's kind in the catalog's settings.
pub(crate) fn kind_column(catalog: &JobCatalog) -> Option<usize> {
    catalog
        .setting_columns
        .iter()
        .position(|c| c == "controller.kind")
}

/// The MPC of group `g` paired with grid setting `k` (`None`: no constant).
pub(crate) fn pair_in_group(
    catalog: &JobCatalog,
    finished: &[(&JobRecord, &JobRow)],
    g: &PairGroup,
    k: Option<usize>,
) -> ConstantPair {
    pair(
        [g.scenario, g.variant, g.mpc_setting],
        &g.mpc_runs,
        k,
        |k| runs_of(finished, g.scenario, k, g.variant),
        kind_column(catalog),
    )
}

/// The pairs of a finished sweep (every job with its row): one per
/// scenario, variant and MPC setting, each with its variant's best
/// constant, if the sweep has a best-constant grid (empty otherwise).
pub fn pairs(catalog: &JobCatalog, finished: &[(&JobRecord, &JobRow)]) -> Vec<ConstantPair> {
    groups(catalog, finished)
        .iter()
        .map(|g| {
            let best = least_mean_work(g.grid.iter().map(|&k| (k, grid_mean_work(finished, g, k))));
            pair_in_group(catalog, finished, g, best)
        })
        .collect()
}

/// The mean of `xs`, NaN if empty.
pub(crate) fn mean_or_nan(xs: &[f64]) -> f64 {
    if xs.is_empty() {
        f64::NAN
    } else {
        xs.iter().sum::<f64>() / xs.len() as f64
    }
}

/// The name of a grid point's constant over its runs: the controller, if
/// every run has the same (`slice:0.48`), else the range of its ratios
/// (`slice:0.46–0.51`): under `[specimens]` each specimen's point i/n is
/// i/n of that specimen's own cap. Empty without runs.
fn constant_name<'a>(controllers: impl Iterator<Item = &'a str>) -> String {
    let names: Vec<&str> = controllers.collect();
    let Some(&first) = names.first() else {
        return String::new();
    };
    if names.iter().all(|n| *n == first) {
        return first.to_string();
    }
    let ratio = |n: &str| n.strip_prefix("slice:").and_then(|x| x.parse::<f64>().ok());
    if names.iter().any(|n| ratio(n).is_none()) {
        let mut unique: Vec<&str> = names.clone();
        unique.sort_unstable();
        unique.dedup();
        return unique.join("/");
    }
    let by_ratio = |a: &&&str, b: &&&str| {
        let [a, b] = [a, b].map(|n| ratio(n).unwrap_or(f64::NAN));
        a.total_cmp(&b)
    };
    let lo = names.iter().min_by(by_ratio).unwrap_or(&first);
    let hi = names.iter().max_by(by_ratio).unwrap_or(&first);
    format!("{lo}–{}", hi.trim_start_matches("slice:"))
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
) -> ConstantPair {
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
    let mean = |xs: Vec<f64>| mean_or_nan(&xs);
    let mpc_completed = mpc_runs.iter().all(|(_, r)| r.outcome.completed);
    let constant_completed =
        !constant_runs.is_empty() && constant_runs.iter().all(|(_, c)| c.outcome.completed);
    let all_completed =
        mpc_completed && on_both.iter().all(|(_, c)| c.outcome.completed) && !on_both.is_empty();
    let constant_controller = constant_name(
        constant_runs
            .iter()
            .filter_map(|(j, _)| kind_column.and_then(|i| j.cells.get(i)))
            .map(String::as_str),
    );
    let paired = |of: fn(&JobRow) -> f64| {
        let (a, b): (Vec<f64>, Vec<f64>) = on_both.iter().map(|(m, c)| (of(m), of(c))).unzip();
        all_completed
            .then(|| PairedDifference::from_values(&constant_controller, &a, &b))
            .flatten()
    };
    let largest_mpc =
        |of: fn(&JobRow) -> f64| mpc_runs.iter().map(|(_, r)| of(r)).fold(0.0, f64::max);
    let [scenario, variant, mpc_setting] = at;
    ConstantPair {
        scenario,
        variant,
        mpc_setting,
        constant_setting: best,
        constant_controller: constant_controller.clone(),
        replicas: on_both.len(),
        mpc_completed,
        constant_completed,
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
        mpc_plan_p99_us: largest_mpc(|r| r.timing.plan_p99_us),
        mpc_solve_p99_us: largest_mpc(|r| r.timing.solve_p99_us),
    }
}

/// The leading columns of a table of pairs: which scenario, variant and
/// MPC setting ([`key_cells`]).
pub(crate) const KEY_COLUMNS: [&str; 5] = [
    "scenario",
    "variant",
    "variant_name",
    "mpc_setting",
    "mpc_overrides",
];

/// The closing columns of a table of pairs: the MPC against the constant
/// ([`pair_cells`]).
pub(crate) const PAIR_COLUMNS: [&str; 16] = [
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

/// The [`KEY_COLUMNS`] cells of pair `p`.
pub(crate) fn key_cells(catalog: &JobCatalog, p: &ConstantPair) -> Vec<String> {
    vec![
        catalog.scenarios[p.scenario].clone(),
        p.variant.to_string(),
        catalog.variants.get(p.variant).cloned().unwrap_or_default(),
        p.mpc_setting.to_string(),
        catalog.settings[p.scenario][p.mpc_setting]
            .overrides
            .join("; "),
    ]
}

/// The [`PAIR_COLUMNS`] cells of pair `p`.
pub(crate) fn pair_cells(p: &ConstantPair) -> Vec<String> {
    let mut cells = vec![
        p.replicas.to_string(),
        p.mpc_completed.to_string(),
        float_cell(p.mpc_work_j),
        float_cell(p.constant_work_j),
    ];
    cells.extend(difference_cells(&p.work));
    cells.push(float_cell(p.mpc_max_deformation_m));
    cells.push(float_cell(p.constant_max_deformation_m));
    cells.extend(difference_cells(&p.deformation));
    cells
}

/// Writes `best-constant.csv` under `dir` (deterministic: the timings are
/// left to `timings.csv`) and returns the summary's section (markdown,
/// with the MPC's planning p99, measured); nothing without pairs.
pub fn write_pairs(
    dir: &Path,
    catalog: &JobCatalog,
    pairs: &[ConstantPair],
) -> Result<String, RunError> {
    if pairs.is_empty() {
        return Ok(String::new());
    }
    let columns = [&KEY_COLUMNS[..], &["best_constant"], &PAIR_COLUMNS[..]].concat();
    let rows = pairs.iter().map(|p| {
        let mut cells = key_cells(catalog, p);
        cells.push(p.constant_controller.clone());
        cells.extend(pair_cells(p));
        cells
    });
    write_table(&dir.join("best-constant.csv"), &columns, rows)?;
    Ok(markdown(catalog, pairs))
}

/// The summary's section: one row per pair, then the tallies against the
/// bars.
fn markdown(catalog: &JobCatalog, pairs: &[ConstantPair]) -> String {
    let mut t = String::from(
        "\n## The MPC against the best constant ratio, per variant\n\n\
         Paired over the replicas: mean of (MPC − best constant) per cent of the constant's mean \
         ± its standard error [least, most single difference]. The two p99s are measured (wall \
         clock, the largest over the MPC's runs): the plans themselves on the planner thread, and \
         the ticks that receive a plan (in lockstep these wait for the planner thread, which \
         shares the cores with the plant).\n\n\
         | scenario | variant | MPC setting | best constant | replicas | MPC work (J) | constant work (J) | work, MPC − constant | lower on | MPC / constant max deformation (mm) | deformation, MPC − constant | plan p99 on the planner thread (ms) | planning tick p99 (ms) |\n\
         |---|---|---|---|---|---|---|---|---|---|---|---|---|\n",
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
            "| {} | {} | {} | {} | {} | {:.4}{} | {:.4} | {} | {} | {:.3} / {:.3} | {} | {:.2} | {:.2} |\n",
            catalog.scenarios[p.scenario],
            catalog.variants.get(p.variant).map_or("", String::as_str),
            name,
            if p.constant_controller.is_empty() {
                "none completed"
            } else {
                &p.constant_controller
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
            1e-3 * p.mpc_solve_p99_us,
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
    use crate::tune::finished_sweep_fixture::{FinishedSweep, Run};

    #[test]
    fn a_constant_is_named_by_the_range_of_its_specimens_ratios() {
        let name = |names: &[&str]| constant_name(names.iter().copied());
        assert_eq!(name(&[]), "");
        assert_eq!(name(&["press", "press"]), "press");
        assert_eq!(name(&["slice:0.48", "slice:0.48"]), "slice:0.48");
        assert_eq!(
            name(&["slice:0.48", "slice:0.512", "slice:0.459"]),
            "slice:0.459–0.512"
        );
        assert_eq!(name(&["slice:0.1", "force:5"]), "force:5/slice:0.1");
    }

    #[test]
    fn the_mpc_meets_the_least_mean_work_of_the_completed_grid_points() {
        // Settings: the MPC, then three grid points; two replicas of one
        // variant. Point 1 has the least single run but did not complete
        // one replica; point 3's mean (1.00 J) beats point 2's (1.01 J).
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
        let runs: Vec<Run> = table
            .iter()
            .map(|&(setting, replica, work, deformation, completed)| Run {
                setting,
                variant: 0,
                replica,
                work,
                deformation,
                completed,
            })
            .collect();
        let sweep = FinishedSweep::new("potato", &["as given"], 3, &runs);
        let catalog = &sweep.catalog;
        let found = pairs(catalog, &sweep.finished());
        assert_eq!(found.len(), 1);
        let p = &found[0];
        assert_eq!(
            (p.constant_setting, p.constant_controller.as_str()),
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
        assert_eq!((p.mpc_plan_p99_us, p.mpc_solve_p99_us), (700.0, 450.0));
        let text = markdown(catalog, &found);
        assert!(
            text.contains("| potato | as given | 0 (as given) | slice:0.3 | 2 |"),
            "{text}"
        );
        assert!(text.contains("-1.00 % ± 0.00 [-1.00, -1.00]"), "{text}");
        // The two p99s, planner thread first, in ms.
        assert!(text.contains("| 0.45 | 0.70 |\n"), "{text}");
        assert!(text.contains(": 0 of 1."), "{text}");
    }
}
