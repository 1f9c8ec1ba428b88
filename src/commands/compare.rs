//! `shearcut compare`: the MPC against the baselines on one scenario — the
//! pressing knife, the best constant slice-push ratio under the same blade
//! budget (found by search), and the force loop — in the same closed loop.

use std::path::Path;

use serde::Serialize;

use crate::commands::run::{LoopSetup, RunOutput, run_closed_loop};
use crate::controller_choice::ControllerChoice;
use crate::cut_record::write_json;
use crate::error::RunError;
use crate::plot::comparison::draw_comparison;
use crate::render_plot;
use crate::run_dir;
use crate::scenario::Scenario;

/// Points of the coarse search over constant ratios.
const SEARCH_POINTS: usize = 6;
/// Golden-section refinements after the coarse search.
const REFINEMENTS: usize = 3;

/// `x` rounded to 3 decimals (ratios named in tables stay readable; the
/// search's resolution is far coarser).
fn round3(x: f64) -> f64 {
    (x * 1e3).round() / 1e3
}

/// One controller's result in the comparison table.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ComparisonRow {
    /// The controller (e.g. `slice:0.75`).
    pub controller: String,
    /// Role in the comparison: `mpc`, `press`, `best constant`, `force`, or
    /// `search` for the other constant ratios tried.
    pub role: String,
    /// Total knife work, J.
    pub work_j: f64,
    /// Peak vertical force, N.
    pub peak_force_vertical_n: f64,
    /// Largest surface deformation, mm.
    pub max_deformation_mm: f64,
    /// Time to the target depth, s.
    pub duration_s: f64,
    /// Blade used (largest tangential displacement from the start), mm.
    pub blade_travel_mm: f64,
    /// Tangential path over all strokes, mm.
    pub blade_path_mm: f64,
    /// Reversals of the tangential direction (sawing).
    pub reversals: u32,
    /// Whether the target depth was reached.
    pub completed: bool,
    /// Commands the arm refused.
    pub limit_faults: usize,
    /// 99th percentile of the planning ticks' wall time, µs (0 without plans).
    pub plan_p99_us: f64,
}

impl ComparisonRow {
    fn new(role: &str, run: &RunOutput) -> Self {
        let c = &run.summary;
        Self {
            controller: run.controller.clone(),
            role: role.to_string(),
            work_j: c.work_j,
            peak_force_vertical_n: c.peak_force_vertical_n,
            max_deformation_mm: c.max_deformation_m * 1e3,
            duration_s: c.duration_s,
            blade_travel_mm: c.blade_travel_m * 1e3,
            blade_path_mm: c.blade_path_m * 1e3,
            reversals: c.reversals,
            completed: c.completed,
            limit_faults: run.output.limit_faults,
            plan_p99_us: run.output.plan_times.p99_us,
        }
    }
}

/// Runs `choices` on `s`, two at a time (the machine's cores).
fn run_all(s: &Scenario, choices: &[ControllerChoice]) -> Vec<Result<RunOutput, RunError>> {
    let mut results: Vec<Option<Result<RunOutput, RunError>>> =
        choices.iter().map(|_| None).collect();
    for (chunk, slots) in choices.chunks(2).zip(results.chunks_mut(2)) {
        std::thread::scope(|scope| {
            let handles: Vec<_> = chunk
                .iter()
                .map(|&c| scope.spawn(move || run_closed_loop(s, c)))
                .collect();
            for (h, slot) in handles.into_iter().zip(slots.iter_mut()) {
                *slot = Some(h.join().expect("a closed-loop run does not panic"));
            }
        });
        for (c, r) in chunk.iter().zip(slots.iter()) {
            if let Some(Ok(run)) = r {
                println!(
                    "  {c:<12} work {:.4} J, peak Fv {:.2} N, completed {}",
                    run.summary.work_j, run.summary.peak_force_vertical_n, run.summary.completed
                );
            }
        }
    }
    results
        .into_iter()
        .map(|r| r.expect("every slot filled"))
        .collect()
}

/// The comparison for a loaded scenario.
pub fn compare(s: &Scenario) -> Result<Vec<ComparisonRow>, RunError> {
    let task = LoopSetup::new(s, ControllerChoice::Press)?.task;
    let target = task.target_depth;
    // The largest constant ratio the blade allows over the whole cut.
    let xi_cap = (task.blade_budget / target).min(s.controller.mpc.max_slice_push_ratio);
    println!(
        "{}: blade budget {:.1} mm for {:.1} mm of depth: constant ratios up to {xi_cap:.3}",
        s.name,
        task.blade_budget * 1e3,
        target * 1e3
    );
    let mut rows = Vec::new();
    // Coarse search over constant ratios (ξ = 0 is pressing).
    let grid: Vec<f64> = (0..SEARCH_POINTS)
        .map(|i| round3(xi_cap * i as f64 / (SEARCH_POINTS - 1) as f64))
        .collect();
    let choices: Vec<ControllerChoice> = grid
        .iter()
        .map(|&xi| {
            if xi == 0.0 {
                ControllerChoice::Press
            } else {
                ControllerChoice::Slice(xi)
            }
        })
        .collect();
    println!("searching the best constant ratio:");
    let mut tried: Vec<(f64, RunOutput)> = Vec::new();
    for (xi, r) in grid.iter().zip(run_all(s, &choices)) {
        tried.push((*xi, r?));
    }
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
        let fresh: Vec<ControllerChoice> = [a, b]
            .into_iter()
            .filter(|x| !tried.iter().any(|(t, _)| t == x))
            .map(ControllerChoice::Slice)
            .collect();
        for (c, r) in fresh.iter().zip(run_all(s, &fresh)) {
            if let ControllerChoice::Slice(x) = c {
                tried.push((*x, r?));
            }
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
    let best = best_index(&tried);
    // The other contestants.
    let setpoint = s.controller.force_setpoint;
    let others = run_all(
        s,
        &[ControllerChoice::Mpc, ControllerChoice::Force(setpoint)],
    );
    let mut others = others.into_iter();
    match others.next().expect("two runs") {
        Ok(run) => rows.push(ComparisonRow::new("mpc", &run)),
        Err(e) => println!("  mpc: not run ({e})"),
    }
    let press = tried
        .iter()
        .find(|(xi, _)| *xi == 0.0)
        .map(|(_, r)| r)
        .expect("the grid starts at 0");
    rows.push(ComparisonRow::new("press", press));
    rows.push(ComparisonRow::new("best constant", &tried[best].1));
    rows.push(ComparisonRow::new(
        "force",
        &others.next().expect("two runs")?,
    ));
    for (i, (_, r)) in tried.iter().enumerate() {
        if i != best && r.controller != "press" {
            rows.push(ComparisonRow::new("search", r));
        }
    }
    Ok(rows)
}

/// Markdown table of the main rows.
pub fn markdown_table(rows: &[ComparisonRow]) -> String {
    let mut t = String::from(
        "| controller | role | work (J) | peak Fv (N) | max deformation (mm) | time (s) | blade used (mm) | blade path (mm) | reversals | completed | limit faults | plan p99 (µs) |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n",
    );
    for r in rows.iter().filter(|r| r.role != "search") {
        t += &format!(
            "| {} | {} | {:.4} | {:.2} | {:.3} | {:.2} | {:.1} | {:.1} | {} | {} | {} | {:.0} |\n",
            r.controller,
            r.role,
            r.work_j,
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

/// Runs the subcommand: compare, print the table, write table, CSV, JSON
/// and the bar plot.
pub fn run(scenario: &str, out: Option<&Path>) -> Result<(), RunError> {
    let s = Scenario::load(scenario)?;
    let rows = compare(&s)?;
    let dir = run_dir::create(&format!("{}-compare", s.name), out)?;
    let table = markdown_table(&rows);
    println!("\n{table}");
    std::fs::write(dir.join("comparison.md"), &table)
        .map_err(|e| RunError::write(dir.join("comparison.md"), e))?;
    let path = dir.join("comparison.csv");
    let mut w = csv::Writer::from_path(&path).map_err(|e| RunError::write(&path, e))?;
    for r in &rows {
        w.serialize(r).map_err(|e| RunError::write(&path, e))?;
    }
    w.flush().map_err(|e| RunError::write(&path, e))?;
    write_json(&dir.join("comparison.json"), &rows)?;
    let main: Vec<ComparisonRow> = rows
        .iter()
        .filter(|r| r.role != "search")
        .cloned()
        .collect();
    let title = format!("{}: controllers compared in closed loop", s.name);
    for name in ["comparison.svg", "comparison.png"] {
        render_plot!(&dir.join(name), (1600, 500), |root| draw_comparison(
            root, &title, &main
        ))?;
    }
    println!(
        "results: {}/ (comparison.md, comparison.csv, comparison.json, comparison.svg/.png)",
        dir.display()
    );
    Ok(())
}
