//! `shearcut compare`: the MPC against the baselines on one scenario — the
//! pressing knife, the best constant slice-push ratio under the same blade
//! budget (found by search), and the force loop — in the same closed loop.
//!
//! The MPC and the best constant run on several replicas of the run (the
//! knife starting k·5 µm higher, [`RunReplica`]) and their rows are the
//! means over them, with the range of the work: the plant's discrete crack
//! events move single runs by a few per cent on the cuboids, depending on
//! where the servo ticks fall. The search over constant ratios runs on the
//! nominal replica; its [`RESAMPLED_CANDIDATES`] cheapest ratios are then
//! run on every replica and the best mean is the baseline, so that the
//! baseline is not simply the luckiest of a dozen single runs. Pressing
//! (unless among those candidates) and the force loop, far from the
//! contest and the longest runs, are run on the nominal replica only.
//!
//! The MPC and the best constant run on the same replicas, so their works
//! pair up replica by replica: [`PairedDifference`] is the mean of the
//! differences with its standard error, the resolution the table's means
//! have.

use serde::Serialize;

use crate::closed_loop::{LoopSetup, RunOutput};
use crate::constant_ratio::{
    completed_mean_work, constant_choice, least_mean_work, ratio_cap, round3,
};
use crate::controller_choice::ControllerChoice;
use crate::error::RunError;
use crate::plot::comparison::draw_comparison;
use crate::render_plot;
use crate::result_file::{write_csv, write_json, write_text};
use crate::run_dir::{self, Destination};
use crate::scenario::Scenario;
use crate::transport::{StopSignal, TerminationWatch};
use crate::tune::constant_grid::ConstantGridPoint;
use crate::tune::controller_setting::ControllerSetting;
use crate::tune::run_log::{RUN_LOG, RunLog};
use crate::tune::staged_runs::{StageEnd, StagedRuns};
use crate::tune::stop_request::StopRequest;

/// Points of the coarse search over constant ratios (0 to the cap).
pub const SEARCH_POINTS: usize = 6;
/// Golden-section refinements after the coarse search.
const REFINEMENTS: usize = 3;
/// Constant ratios of the search (cheapest on the nominal replica first)
/// that are run on every replica to choose the best constant.
pub const RESAMPLED_CANDIDATES: usize = 3;
/// Replicas per contestant by default.
pub const DEFAULT_REPLICAS: u64 = 8;
/// Most replicas accepted.
pub const MAX_REPLICAS: u64 = 21;

/// One controller's result in the comparison table.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ComparisonRow {
    /// The controller (e.g. `slice:0.75`).
    pub controller: String,
    /// Role in the comparison: `mpc`, `press`, `best constant`, `force`, or
    /// `search` for the other constant ratios tried.
    pub role: String,
    /// Total knife work, J (mean over the replicas).
    pub work_j: f64,
    /// Least work of a replica, J.
    pub work_min_j: f64,
    /// Most work of a replica, J.
    pub work_max_j: f64,
    /// Replicas run (1: the nominal replica only).
    pub replicas: usize,
    /// Peak vertical force, N (mean over the replicas).
    pub peak_force_vertical_n: f64,
    /// Largest surface deformation, mm (mean).
    pub max_deformation_mm: f64,
    /// Time to the target depth, s (mean).
    pub duration_s: f64,
    /// Blade used (largest tangential displacement from the start), mm
    /// (mean).
    pub blade_travel_mm: f64,
    /// Tangential path over all strokes, mm (mean).
    pub blade_path_mm: f64,
    /// Reversals of the tangential direction (sawing), on the nominal
    /// replica.
    pub reversals: u32,
    /// Whether every replica reached the target depth.
    pub completed: bool,
    /// Commands the arm refused, over all replicas.
    pub limit_faults: usize,
    /// 99th percentile of the planning ticks' wall time, µs (0 without
    /// plans; the largest over the replicas).
    pub plan_p99_us: f64,
}

impl ComparisonRow {
    /// The row of one contestant from its runs on the replicas (the
    /// nominal one first).
    fn new(role: &str, runs: &[&RunOutput]) -> Self {
        let n = runs.len() as f64;
        let mean = |f: fn(&RunOutput) -> f64| runs.iter().map(|r| f(r)).sum::<f64>() / n;
        let work = runs.iter().map(|r| r.summary.work_j);
        let nominal = runs[0];
        Self {
            controller: nominal.controller.clone(),
            role: role.to_string(),
            work_j: mean(|r| r.summary.work_j),
            work_min_j: work.clone().fold(f64::INFINITY, f64::min),
            work_max_j: work.fold(f64::NEG_INFINITY, f64::max),
            replicas: runs.len(),
            peak_force_vertical_n: mean(|r| r.summary.peak_force_vertical_n),
            max_deformation_mm: mean(|r| r.summary.max_deformation_m) * 1e3,
            duration_s: mean(|r| r.summary.duration_s),
            blade_travel_mm: mean(|r| r.summary.blade_travel_m) * 1e3,
            blade_path_mm: mean(|r| r.summary.blade_path_m) * 1e3,
            reversals: nominal.summary.reversals,
            completed: runs.iter().all(|r| r.summary.completed),
            limit_faults: runs.iter().map(|r| r.output.limit_faults).sum(),
            plan_p99_us: runs
                .iter()
                .map(|r| r.output.plan_times.p99_us)
                .fold(0.0, f64::max),
        }
    }
}

/// The MPC's work (or another outcome) against a baseline's on the same
/// replicas, replica by replica: how far the table's means can be trusted
/// to tell them apart.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PairedDifference {
    /// The baseline (e.g. `slice:0.526`).
    pub against: String,
    /// Replicas paired.
    pub replicas: usize,
    /// Mean of (MPC − baseline) over the replicas, per cent of the
    /// baseline's mean (negative: the MPC's is smaller).
    pub mean_percent: f64,
    /// Standard error of that mean, per cent (the differences' sample
    /// standard deviation over √replicas; `None` for one replica).
    pub standard_error_percent: Option<f64>,
    /// The smallest and the largest single difference, per cent of the
    /// baseline's mean.
    pub range_percent: [f64; 2],
    /// Replicas on which the MPC's value was below the baseline's.
    pub mpc_lower: usize,
}

impl PairedDifference {
    /// The paired difference of the MPC's runs and a baseline's, both in
    /// replica order (`None` unless both ran on the same replicas and
    /// every run completed: a run that stopped short did less work).
    pub fn new(mpc: &[&RunOutput], baseline: &[&RunOutput]) -> Option<Self> {
        let completed = mpc.iter().chain(baseline).all(|r| r.summary.completed);
        let same_replicas = completed
            && mpc.len() == baseline.len()
            && mpc
                .iter()
                .zip(baseline)
                .all(|(a, b)| a.replica == b.replica);
        if !same_replicas || mpc.is_empty() {
            return None;
        }
        let works =
            |runs: &[&RunOutput]| -> Vec<f64> { runs.iter().map(|r| r.summary.work_j).collect() };
        Self::from_values(&baseline[0].controller, &works(mpc), &works(baseline))
    }

    /// The paired difference of values (works in J, deformations in m, …)
    /// on the same replicas, in the same order; `None` unless both are
    /// non-empty and of equal length.
    pub fn from_values(against: &str, mpc: &[f64], baseline: &[f64]) -> Option<Self> {
        if mpc.is_empty() || mpc.len() != baseline.len() {
            return None;
        }
        let n = mpc.len();
        let d: Vec<f64> = mpc.iter().zip(baseline).map(|(a, b)| a - b).collect();
        let scale = 100.0 * n as f64 / baseline.iter().sum::<f64>();
        let mean = d.iter().sum::<f64>() / n as f64;
        let standard_error = (n > 1).then(|| {
            let var = d.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1) as f64;
            (var / n as f64).sqrt() * scale
        });
        let (least, most) = d
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
                (a.min(x), b.max(x))
            });
        Some(Self {
            against: against.to_string(),
            replicas: n,
            mean_percent: mean * scale,
            standard_error_percent: standard_error,
            range_percent: [least * scale, most * scale],
            mpc_lower: d.iter().filter(|&&x| x < 0.0).count(),
        })
    }

    /// One line for the table's footer.
    pub fn describe(&self) -> String {
        let se = self
            .standard_error_percent
            .map_or(String::new(), |e| format!(" ± {e:.2} % (standard error)"));
        format!(
            "MPC − {} (paired over {} replicas): {:+.2} %{se}; the MPC needed less work on {} of {}",
            self.against, self.replicas, self.mean_percent, self.mpc_lower, self.replicas
        )
    }
}

/// What `compare` found: the rows, and the MPC against the best constant
/// replica by replica.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Comparison {
    /// Every contestant's row (the main rows first, then the search's
    /// other ratios, role `search`).
    pub rows: Vec<ComparisonRow>,
    /// The MPC's work against the best constant's, paired by replica
    /// (`None` if the MPC did not run).
    pub mpc_vs_best_constant: Option<PairedDifference>,
    /// The signal that stopped the comparison before its last run: the
    /// rows are then those of the runs finished, one per controller, roles
    /// `mpc`, `press`, `force` or `search` (no best constant chosen).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stopped: Option<StopSignal>,
}

impl Comparison {
    /// The comparison stopped by `signal`: a row per controller of the
    /// runs finished, in the order they were first run.
    fn stopped(runs: &StagedRuns, signal: StopSignal) -> Self {
        let mut choices: Vec<ControllerChoice> = Vec::new();
        for r in runs.done() {
            if !choices.contains(&r.choice) {
                choices.push(r.choice);
            }
        }
        let rows = choices
            .into_iter()
            .map(|c| {
                let role = match c {
                    ControllerChoice::Mpc => "mpc",
                    ControllerChoice::Press => "press",
                    ControllerChoice::Force(_) => "force",
                    ControllerChoice::Slice(_) => "search",
                };
                ComparisonRow::new(role, &runs.of(c))
            })
            .collect();
        Self {
            rows,
            mpc_vs_best_constant: None,
            stopped: Some(signal),
        }
    }

    /// The rows of the table and the plot: the main rows, or every row of
    /// a stopped comparison.
    fn shown_rows(&self) -> Vec<ComparisonRow> {
        self.rows
            .iter()
            .filter(|r| self.stopped.is_some() || r.role != "search")
            .cloned()
            .collect()
    }
}

/// The comparison for a loaded scenario, each contestant on `replicas`
/// replicas of the run (1: the nominal replica only), `threads` runs at a
/// time; a stop request ends it with the rows of the runs finished
/// ([`Comparison::stopped`]). Each finished run's row is appended to `log`
/// as it ends.
///
/// Its runs are small sweeps on the scenario ([`StagedRuns`]), one batch
/// each: the coarse grid (a `best-constant` grid of [`SEARCH_POINTS`]
/// points, nominal replica), each golden-section step (`slice:a`,
/// `slice:b`), then the MPC and the cheapest candidates on every replica
/// with the force loop on the nominal one (runs done before are not run
/// again).
pub fn compare(
    s: &Scenario,
    replicas: u64,
    threads: usize,
    stop: &StopRequest,
    log: Option<&RunLog>,
) -> Result<Comparison, RunError> {
    let replicas = replicas.clamp(1, MAX_REPLICAS) as usize;
    let task = LoopSetup::new(s, ControllerChoice::Press)?.task;
    let target = task.target_depth;
    // The largest constant ratio the blade allows over the whole cut.
    let xi_cap = ratio_cap(&task, s.controller.mpc.max_slice_push_ratio);
    crate::outln!(
        "{}: blade budget {:.1} mm for {:.1} mm of depth: constant ratios up to {xi_cap:.3}",
        s.name,
        task.blade_budget * 1e3,
        target * 1e3
    )?;
    let mut runs = StagedRuns::new(s, threads, stop, &format!("compare {}", s.name), log);
    // Coarse search over constant ratios (ξ = 0 is pressing).
    crate::outln!("searching the best constant ratio:")?;
    let grid: Vec<ControllerSetting> = (0..SEARCH_POINTS)
        .map(|index| ControllerSetting {
            grid_point: Some(ConstantGridPoint {
                index,
                points: SEARCH_POINTS,
            }),
            ..ControllerSetting::fixed(ControllerChoice::Press)
        })
        .collect();
    let coarse = runs.sweep(grid, 1)?;
    let mut ratios: Vec<f64> = coarse.iter().map(|j| ratio_of(j.choice)).collect();
    if let Some(stopped) = stage_done(runs.run(coarse)?)? {
        return Ok(Comparison::stopped(&runs, stopped));
    }
    let nominal = |runs: &StagedRuns, xi: f64| -> Option<RunOutput> {
        runs.of(constant_choice(xi)).first().map(|r| (*r).clone())
    };
    let mut tried: Vec<(f64, RunOutput)> = ratios
        .iter()
        .filter_map(|&xi| nominal(&runs, xi).map(|r| (xi, r)))
        .collect();
    // Golden-section refinement around the best completed grid point.
    let work = |r: &RunOutput| {
        if r.summary.completed {
            r.summary.work_j
        } else {
            f64::INFINITY
        }
    };
    let best_index = |tried: &[(f64, RunOutput)]| {
        (0..tried.len())
            .min_by(|&a, &b| work(&tried[a].1).total_cmp(&work(&tried[b].1)))
            .expect("the grid is not empty")
    };
    let step = xi_cap / (SEARCH_POINTS - 1) as f64;
    let centre = tried[best_index(&tried)].0;
    let (mut lo, mut hi) = ((centre - step).max(0.0), (centre + step).min(xi_cap));
    const INV_PHI: f64 = 0.618_033_988_749_895;
    for _ in 0..REFINEMENTS {
        let a = round3(hi - INV_PHI * (hi - lo));
        let b = round3(lo + INV_PHI * (hi - lo));
        // Ratios already run (the rounding to 3 decimals makes repeats
        // likely near the end) are not run again.
        let mut fresh: Vec<f64> = Vec::new();
        for x in [a, b] {
            if !ratios.contains(&x) && !fresh.contains(&x) {
                fresh.push(x);
            }
        }
        let settings = fresh
            .iter()
            .map(|&x| ControllerSetting::fixed(ControllerChoice::Slice(x)))
            .collect();
        let jobs = runs.sweep(settings, 1)?;
        if let Some(stopped) = stage_done(runs.run(jobs)?)? {
            return Ok(Comparison::stopped(&runs, stopped));
        }
        for x in fresh {
            ratios.push(x);
            tried.extend(nominal(&runs, x).map(|r| (x, r)));
        }
        let work_at = |x: f64| {
            tried
                .iter()
                .find(|(t, _)| *t == x)
                .map_or(f64::INFINITY, |(_, r)| work(r))
        };
        if work_at(a) <= work_at(b) {
            hi = b;
        } else {
            lo = a;
        }
    }
    // The MPC and the search's cheapest ratios on the other replicas
    // (pressing and the force loop, far from the contest and the slowest
    // runs, on the nominal replica only).
    let mut order: Vec<usize> = (0..tried.len())
        .filter(|&i| tried[i].1.summary.completed)
        .collect();
    order.sort_by(|&a, &b| work(&tried[a].1).total_cmp(&work(&tried[b].1)));
    order.truncate(RESAMPLED_CANDIDATES);
    let press_index = tried
        .iter()
        .position(|(xi, _)| *xi == 0.0)
        .expect("the grid starts at 0");
    let setpoint = s.controller.force_setpoint;
    let (mpc, force) = (ControllerChoice::Mpc, ControllerChoice::Force(setpoint));
    if replicas > 1 {
        crate::outln!(
            "the contestants on {replicas} replicas of the run (the knife starting 0, 5, 10, … µm higher):"
        )?;
    }
    let contestants = std::iter::once(mpc)
        .chain(order.iter().map(|&i| constant_choice(tried[i].0)))
        .map(ControllerSetting::fixed)
        .collect();
    let mut jobs = runs.sweep(contestants, replicas as u32)?;
    jobs.extend(runs.sweep(vec![ControllerSetting::fixed(force)], 1)?);
    let end = runs.run(jobs)?;
    let mut mpc_failure = None;
    for (choice, e) in end.failed {
        match choice {
            ControllerChoice::Mpc => {
                mpc_failure.get_or_insert(e);
            }
            _ => return Err(e),
        }
    }
    if let Some(stopped) = end.stopped {
        return Ok(Comparison::stopped(&runs, stopped));
    }
    // Runs per contestant, the nominal replica's first.
    let replicated = |i: usize| runs.of(constant_choice(tried[i].0));
    let mean_work = |i: usize| {
        completed_mean_work(
            replicated(i)
                .iter()
                .map(|r| (r.summary.work_j, r.summary.completed)),
        )
    };
    let best = least_mean_work(order.iter().map(|&i| (i, mean_work(i))))
        .unwrap_or_else(|| best_index(&tried));
    let mut rows = Vec::new();
    let mut mpc_vs_best_constant = None;
    match mpc_failure {
        None => {
            let of_mpc = runs.of(mpc);
            rows.push(ComparisonRow::new("mpc", &of_mpc));
            mpc_vs_best_constant = PairedDifference::new(&of_mpc, &replicated(best));
        }
        Some(e) => crate::outln!("  mpc: not run ({e})")?,
    }
    rows.push(ComparisonRow::new("press", &replicated(press_index)));
    rows.push(ComparisonRow::new("best constant", &replicated(best)));
    rows.push(ComparisonRow::new("force", &runs.of(force)));
    for i in 0..tried.len() {
        if i != best && i != press_index {
            rows.push(ComparisonRow::new("search", &replicated(i)));
        }
    }
    Ok(Comparison {
        rows,
        mpc_vs_best_constant,
        stopped: None,
    })
}

/// The constant ratio a job's controller runs (0: pressing).
fn ratio_of(choice: ControllerChoice) -> f64 {
    match choice {
        ControllerChoice::Slice(xi) => xi,
        _ => 0.0,
    }
}

/// The end of a search stage: its first failure is the comparison's
/// error; else the signal that stopped it, if any.
fn stage_done(end: StageEnd) -> Result<Option<StopSignal>, RunError> {
    match end.failed.into_iter().next() {
        Some((_, e)) => Err(e),
        None => Ok(end.stopped),
    }
}

/// Markdown table of `rows`.
pub fn markdown_table(rows: &[ComparisonRow]) -> String {
    let mut t = String::from(
        "| controller | role | work (J) | work range (J) | replicas | peak Fv (N) | max deformation (mm) | time (s) | blade used (mm) | blade path (mm) | reversals | completed | limit faults | plan p99 (µs) |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n",
    );
    for r in rows {
        t += &format!(
            "| {} | {} | {:.4} | {:.4}–{:.4} | {} | {:.2} | {:.3} | {:.2} | {:.1} | {:.1} | {} | {} | {} | {:.0} |\n",
            r.controller,
            r.role,
            r.work_j,
            r.work_min_j,
            r.work_max_j,
            r.replicas,
            r.peak_force_vertical_n,
            r.max_deformation_mm,
            r.duration_s,
            r.blade_travel_mm,
            r.blade_path_mm,
            r.reversals,
            r.completed,
            r.limit_faults,
            r.plan_p99_us
        );
    }
    t
}

/// Runs the subcommand: compare (the MPC and the constant candidates on
/// `replicas` replicas of the run, `threads` runs at a time), print the
/// table, write table, CSV, JSON and the bar plot; `runs.csv` receives each
/// run's row as the run ends ([`RunLog`]). SIGINT/SIGTERM end the
/// runs in flight at their next tick: the rows of the finished runs are
/// written, marked stopped, and the exit is 130/143.
pub fn run(
    scenario: &str,
    replicas: u64,
    threads: usize,
    out: &Destination,
) -> Result<(), RunError> {
    let stop = StopRequest::watching(TerminationWatch::new());
    let s = Scenario::load(scenario)?;
    let dir = run_dir::claim(
        &format!("{}-compare", s.name),
        out,
        &crate::commands::check::resolved_toml(&s),
    )?;
    let comparison = RunLog::create(dir.join(RUN_LOG))
        .and_then(|log| compare(&s, replicas, threads, &stop, Some(&log)))
        .inspect_err(|_| run_dir::abandon(&dir))?;
    let rows = &comparison.rows;
    let shown = comparison.shown_rows();
    let mut table = markdown_table(&shown);
    if let Some(p) = &comparison.mpc_vs_best_constant {
        table += &format!("\n{}\n", p.describe());
    }
    if let Some(signal) = comparison.stopped {
        table += &format!(
            "\nstopped by {signal} before the comparison was complete: the rows of the runs finished, no best constant chosen\n"
        );
    }
    crate::outln!("\n{table}")?;
    write_text(&dir.join("comparison.md"), &table)?;
    write_csv(&dir.join("comparison.csv"), rows)?;
    write_json(&dir.join("comparison.json"), &comparison)?;
    let title = format!("{}: controllers compared in closed loop", s.name);
    if !shown.is_empty() {
        for name in ["comparison.svg", "comparison.png"] {
            render_plot!(&dir.join(name), (1600, 500), |root| draw_comparison(
                root, &title, &shown
            ))?;
        }
    }
    crate::outln!(
        "results: {}/ (comparison.md, comparison.csv, comparison.json, comparison.svg/.png, runs.csv)",
        dir.display()
    )?;
    match comparison.stopped {
        Some(signal) => Err(RunError::Stopped {
            signal,
            dir: dir.display().to_string(),
        }),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paired_differences_are_relative_to_the_baselines_mean() {
        // Differences −0.1 and +0.1 J against a mean of 1.5 J: mean 0, the
        // differences' standard deviation √0.02 J, its standard error 0.1 J,
        // 6.67 % of 1.5 J.
        let p = PairedDifference::from_values("slice:0.5", &[1.0, 2.0], &[1.1, 1.9]).unwrap();
        assert_eq!((p.replicas, p.mpc_lower), (2, 1));
        assert!(p.mean_percent.abs() < 1e-12, "{}", p.mean_percent);
        let se = p.standard_error_percent.unwrap();
        assert!((se - 100.0 / 15.0).abs() < 1e-9, "{se}");
        // Single differences of ∓0.1 J: ∓6.67 % of 1.5 J.
        let [least, most] = p.range_percent;
        assert!((least + 20.0 / 3.0).abs() < 1e-9 && (most - 20.0 / 3.0).abs() < 1e-9);
        let one = PairedDifference::from_values("press", &[0.9], &[1.0]).unwrap();
        assert!((one.mean_percent + 10.0).abs() < 1e-9);
        assert_eq!(one.standard_error_percent, None);
        assert!(one.describe().contains("-10.00 %"), "{}", one.describe());
        assert_eq!(PairedDifference::from_values("press", &[1.0], &[]), None);
    }
}
