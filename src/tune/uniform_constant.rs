//! The MPC against each point of a sweep's best-constant grid held over all
//! its variants: `constant-grid.csv` and a section of `summary.md`.
//!
//! Point i of n is one policy on every variant: slice at i/(n − 1) of the
//! largest constant ratio the variant's blade allows over its depth
//! (pressing at 0; [`crate::tune::constant_grid`]). The best constant of
//! `best-constant.csv` is chosen on each variant itself, in hindsight; a
//! point held over the variants is a constant ratio as a lab tunes it:
//! chosen on one set of objects, then used on objects it was not chosen on.
//! The point a sweep's variants tune ([`tuned_point`]) is the one with the
//! least mean excess work over each variant's best constant, among the
//! points that completed every run on every variant. Choose it on a tuning
//! set, then read its row in the summary of the held-out set: the MPC
//! against a constant tuned as the MPC was, both judged on objects neither
//! was tuned on.
//!
//! Per point, over the variants: its excess work over each variant's best
//! constant (mean and most, per cent of the best's mean work), the MPC's
//! mean paired work difference against it (mean over the variants of
//! [`ConstantPair::work`]'s mean), and on how many variants the MPC is no
//! worse ([`ConstantPair::no_worse`]) and wins ([`ConstantPair::clear_win`]).

use std::path::Path;

use crate::constant_ratio::least_mean_work;
use crate::error::RunError;
use crate::result_file::write_table;
use crate::tune::best_constant_pairing::{
    ConstantPair, KEY_COLUMNS, PAIR_COLUMNS, grid_mean_work, groups, key_cells, mean_or_nan,
    pair_cells, pair_in_group,
};
use crate::tune::job_list::{JobCatalog, JobRecord};
use crate::tune::job_outcome::JobRow;
use crate::tune::perturbation::float_cell;

/// The MPC against one grid point on one variant.
#[derive(Debug, Clone, PartialEq)]
pub struct GridPointPair {
    /// The point's place in the grid: 0 is pressing, the last the cap.
    pub point: usize,
    /// The point's name (`best-constant:i/n`).
    pub label: String,
    /// The MPC against the point's runs.
    pub pair: ConstantPair,
    /// The point's mean work over the variant's best constant's, less 1,
    /// per cent (`None` unless both completed every run).
    pub excess_percent: Option<f64>,
}

/// One grid point held over every variant of a scenario, against one MPC
/// setting.
#[derive(Debug, Clone, PartialEq)]
pub struct GridPointTally {
    /// Index of the scenario in the sweep.
    pub scenario: usize,
    /// Index of the MPC's setting in the sweep.
    pub mpc_setting: usize,
    /// The point's place in the grid.
    pub point: usize,
    /// The point's name (`best-constant:i/n`).
    pub label: String,
    /// Variants the MPC ran on.
    pub variants: usize,
    /// Variants on which the point completed every run.
    pub completed: usize,
    /// Mean over those variants of the point's excess work over the
    /// variant's best constant, per cent (NaN if none).
    pub mean_excess_percent: f64,
    /// The largest of those excesses, per cent (NaN if none).
    pub max_excess_percent: f64,
    /// Mean over the variants paired of the MPC's mean paired work
    /// difference against the point, per cent (NaN if none).
    pub mean_work_difference_percent: f64,
    /// Variants on which the MPC is no worse than the point.
    pub no_worse: usize,
    /// Variants on which the MPC wins clearly against the point.
    pub wins: usize,
}

/// The MPC against every grid point on every variant of a finished sweep
/// (every job with its row), grouped by scenario, MPC setting and variant,
/// the points in grid order; empty without a best-constant grid.
pub fn grid_point_pairs(
    catalog: &JobCatalog,
    finished: &[(&JobRecord, &JobRow)],
) -> Vec<GridPointPair> {
    let mut out = Vec::new();
    for g in groups(catalog, finished) {
        let works: Vec<(usize, Option<f64>)> = g
            .grid
            .iter()
            .map(|&k| (k, grid_mean_work(finished, &g, k)))
            .collect();
        let best_work = least_mean_work(works.iter().copied())
            .and_then(|best| works.iter().find(|(k, _)| *k == best))
            .and_then(|(_, w)| *w);
        for (point, &(k, work)) in works.iter().enumerate() {
            let excess_percent = match (work, best_work) {
                (Some(w), Some(b)) => Some(100.0 * (w / b - 1.0)),
                _ => None,
            };
            out.push(GridPointPair {
                point,
                label: catalog.settings[g.scenario][k].controller.clone(),
                pair: pair_in_group(catalog, finished, &g, Some(k)),
                excess_percent,
            });
        }
    }
    out
}

/// Each grid point held over the variants, per scenario and MPC setting,
/// in the order of `pairs` ([`grid_point_pairs`]).
pub fn tallies(pairs: &[GridPointPair]) -> Vec<GridPointTally> {
    let mut out: Vec<GridPointTally> = Vec::new();
    for p in pairs {
        let key = (p.pair.scenario, p.pair.mpc_setting, p.point);
        let at = out
            .iter()
            .position(|t| (t.scenario, t.mpc_setting, t.point) == key);
        let at = at.unwrap_or_else(|| {
            out.push(GridPointTally {
                scenario: key.0,
                mpc_setting: key.1,
                point: key.2,
                label: p.label.clone(),
                variants: 0,
                completed: 0,
                mean_excess_percent: f64::NAN,
                max_excess_percent: f64::NAN,
                mean_work_difference_percent: f64::NAN,
                no_worse: 0,
                wins: 0,
            });
            out.len() - 1
        });
        let t = &mut out[at];
        t.variants += 1;
        t.no_worse += usize::from(p.pair.no_worse());
        t.wins += usize::from(p.pair.clear_win());
    }
    for t in &mut out {
        let of_point = || {
            pairs.iter().filter(|p| {
                (p.pair.scenario, p.pair.mpc_setting, p.point)
                    == (t.scenario, t.mpc_setting, t.point)
            })
        };
        let excesses: Vec<f64> = of_point().filter_map(|p| p.excess_percent).collect();
        let differences: Vec<f64> = of_point()
            .filter_map(|p| p.pair.work.as_ref().map(|w| w.mean_percent))
            .collect();
        t.completed = excesses.len();
        t.mean_excess_percent = mean_or_nan(&excesses);
        t.max_excess_percent = excesses
            .iter()
            .copied()
            .reduce(f64::max)
            .unwrap_or(f64::NAN);
        t.mean_work_difference_percent = mean_or_nan(&differences);
    }
    out
}

/// The point the variants of `scenario` tune against MPC setting
/// `mpc_setting`: the least mean excess work over each variant's best
/// constant, among the points that completed every run on every variant;
/// the first of equals; `None` if no point did.
pub fn tuned_point(
    tallies: &[GridPointTally],
    scenario: usize,
    mpc_setting: usize,
) -> Option<&GridPointTally> {
    tallies
        .iter()
        .filter(|t| t.scenario == scenario && t.mpc_setting == mpc_setting)
        .filter(|t| t.variants > 0 && t.completed == t.variants)
        .fold(None, |best: Option<&GridPointTally>, t| match best {
            Some(b) if b.mean_excess_percent <= t.mean_excess_percent => best,
            _ => Some(t),
        })
}

/// Writes `constant-grid.csv` under `dir` (deterministic) and returns the
/// summary's section (markdown); nothing without a best-constant grid.
pub fn write_grid(
    dir: &Path,
    catalog: &JobCatalog,
    pairs: &[GridPointPair],
) -> Result<String, RunError> {
    if pairs.is_empty() {
        return Ok(String::new());
    }
    let own = [
        "grid_point",
        "constant",
        "constant_completed",
        "excess_work_percent",
    ];
    let columns = [&KEY_COLUMNS[..], &own, &PAIR_COLUMNS[..]].concat();
    let rows = pairs.iter().map(|p| {
        let mut cells = key_cells(catalog, &p.pair);
        cells.extend([
            p.label.clone(),
            p.pair.constant_controller.clone(),
            p.pair.constant_completed.to_string(),
            p.excess_percent.map_or(String::new(), float_cell),
        ]);
        cells.extend(pair_cells(&p.pair));
        cells
    });
    write_table(&dir.join("constant-grid.csv"), &columns, rows)?;
    Ok(markdown(catalog, &tallies(pairs)))
}

/// The summary's section: one row per scenario, MPC setting and grid
/// point, then the point each scenario's variants tune.
fn markdown(catalog: &JobCatalog, tallies: &[GridPointTally]) -> String {
    let mut t = String::from(
        "\n## Each point of the grid held over the variants\n\n\
         Point i/n slices at i/n of the ratio each variant's blade allows over its depth. Excess: \
         the point's mean work over each variant's best constant's, per cent (mean, most; over \
         the variants it completed). MPC − point: the mean over the variants of the paired work \
         difference; no worse and wins by the bars above.\n\n\
         | scenario | MPC setting | grid point | completed on | excess over each variant's best: mean, most | MPC − point, work | MPC no worse on | MPC wins on |\n\
         |---|---|---|---|---|---|---|---|\n",
    );
    for x in tallies {
        t += &format!(
            "| {} | {} | {} | {} of {} | {:+.2} %, {:+.2} % | {:+.2} % | {} of {} | {} of {} |\n",
            catalog.scenarios[x.scenario],
            x.mpc_setting,
            x.label,
            x.completed,
            x.variants,
            x.mean_excess_percent,
            x.max_excess_percent,
            x.mean_work_difference_percent,
            x.no_worse,
            x.variants,
            x.wins,
            x.variants,
        );
    }
    t += "\nThe point these variants tune (least mean excess, completed on every variant):";
    let mut keys: Vec<(usize, usize)> = tallies
        .iter()
        .map(|x| (x.scenario, x.mpc_setting))
        .collect();
    keys.dedup();
    for (scenario, mpc_setting) in keys {
        let name = &catalog.scenarios[scenario];
        t += &match tuned_point(tallies, scenario, mpc_setting) {
            Some(x) => format!(
                " {name} (MPC setting {mpc_setting}): {} ({:+.2} %, MPC no worse on {} of {});",
                x.label, x.mean_excess_percent, x.no_worse, x.variants
            ),
            None => format!(" {name} (MPC setting {mpc_setting}): none;"),
        };
    }
    t.pop();
    t += ".\n";
    t
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tune::finished_sweep_fixture::{FinishedSweep, Run};

    /// One replica per setting and variant: (setting, variant, work in J,
    /// completed), every deformation 0.1 mm.
    fn sweep(scenario: &str, points: usize, table: &[(usize, usize, f64, bool)]) -> FinishedSweep {
        let runs: Vec<Run> = table
            .iter()
            .map(|&(setting, variant, work, completed)| Run {
                setting,
                variant,
                replica: 0,
                work,
                deformation: 1e-4,
                completed,
            })
            .collect();
        FinishedSweep::new(scenario, &["a", "b"], points, &runs)
    }

    #[test]
    fn the_tuned_point_has_the_least_mean_excess_over_each_variants_best() {
        // The MPC and a grid of three points on two variants, one replica.
        // Variant 0: points 1.00, 0.90, 0.95 J (best: point 1); variant 1:
        // 1.00, 1.10, 0.98 J (best: point 2). Excesses: point 0 +11.1 and
        // +2.04 % (mean 6.58), point 1 0 and +12.24 % (6.12), point 2
        // +5.56 and 0 % (2.78): point 2 is tuned. The MPC needs 0.96 and
        // 1.00 J: against point 2, +1.05 % (worse) and +2.04 % (worse).
        let sweep = sweep(
            "potato",
            3,
            &[
                (0, 0, 0.96, true),
                (1, 0, 1.00, true),
                (2, 0, 0.90, true),
                (3, 0, 0.95, true),
                (0, 1, 1.00, true),
                (1, 1, 1.00, true),
                (2, 1, 1.10, true),
                (3, 1, 0.98, true),
            ],
        );
        let pairs = grid_point_pairs(&sweep.catalog, &sweep.finished());
        assert_eq!(pairs.len(), 6);
        let excess = |variant: usize, point: usize| {
            pairs
                .iter()
                .find(|p| p.pair.variant == variant && p.point == point)
                .and_then(|p| p.excess_percent)
                .unwrap()
        };
        assert!((excess(0, 0) - 100.0 / 9.0).abs() < 1e-9);
        assert_eq!(excess(0, 1), 0.0);
        assert!((excess(1, 1) - 100.0 * (1.10 / 0.98 - 1.0)).abs() < 1e-9);
        let t = tallies(&pairs);
        assert_eq!(t.len(), 3);
        let tuned = tuned_point(&t, 0, 0).unwrap();
        assert_eq!(
            (tuned.point, tuned.label.as_str()),
            (2, "best-constant:2/2")
        );
        let expected = 0.5 * 100.0 * (0.95 / 0.90 - 1.0);
        assert!((tuned.mean_excess_percent - expected).abs() < 1e-9);
        assert_eq!((tuned.completed, tuned.variants), (2, 2));
        // The MPC against point 2: (0.96/0.95 − 1) and (1.00/0.98 − 1).
        let difference = 50.0 * (0.96 / 0.95 - 1.0 + 1.00 / 0.98 - 1.0);
        assert!((tuned.mean_work_difference_percent - difference).abs() < 1e-9);
        assert_eq!((tuned.no_worse, tuned.wins), (0, 0));
        // Against point 0 the MPC is no worse on both (−4 % and 0 %, equal
        // deformation), and wins on variant 0 (≥ 3 % less work).
        assert_eq!((t[0].no_worse, t[0].wins), (2, 1));
        let text = markdown(&sweep.catalog, &t);
        assert!(
            text.contains("| potato | 0 | best-constant:2/2 | 2 of 2 |"),
            "{text}"
        );
        assert!(
            text.contains("potato (MPC setting 0): best-constant:2/2 (+2.78 %"),
            "{text}"
        );
    }

    #[test]
    fn a_point_that_stopped_short_on_a_variant_is_not_tuned() {
        // Point 1 is cheapest on both variants but stopped short on
        // variant 1: it has no excess there and cannot be tuned.
        let sweep = sweep(
            "egg",
            2,
            &[
                (0, 0, 1.0, true),
                (1, 0, 1.0, true),
                (2, 0, 0.8, true),
                (0, 1, 1.0, true),
                (1, 1, 1.0, true),
                (2, 1, 0.7, false),
            ],
        );
        let t = tallies(&grid_point_pairs(&sweep.catalog, &sweep.finished()));
        assert_eq!((t[1].completed, t[1].variants), (1, 2));
        let tuned = tuned_point(&t, 0, 0).unwrap();
        assert_eq!(tuned.point, 0);
        // Point 0 is variant 0's 25 % excess and variant 1's best.
        assert!((tuned.mean_excess_percent - 12.5).abs() < 1e-9);
    }
}
