//! Robust statistics of a setting over the objects it will meet: per
//! scenario and controller setting, the mean, the worst and the spread
//! (worst − best) of each objective over its runs (variants × replicas).

use serde::Serialize;

use crate::tune::job_list::JobRecord;
use crate::tune::job_outcome::JobRow;
use crate::tune::objective::Objective;

/// One setting's statistics on one scenario; objectives in
/// [`Objective::ALL`]'s order, SI units.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SettingStats {
    /// Index of the scenario in the sweep.
    pub scenario: usize,
    /// Index of the setting in the sweep.
    pub setting: usize,
    /// The controller.
    pub controller: String,
    /// Runs of the setting on the scenario.
    pub runs: usize,
    /// Of them, runs that reached the target depth.
    pub completed: usize,
    /// Mean over the runs.
    pub mean: [f64; 4],
    /// Largest value over the runs (every objective is to be made small).
    pub worst: [f64; 4],
    /// Largest less smallest value over the runs.
    pub spread: [f64; 4],
}

impl SettingStats {
    /// Whether every run completed: only then are its numbers comparable
    /// (a cut that stopped short did less work).
    pub fn all_completed(&self) -> bool {
        self.runs > 0 && self.completed == self.runs
    }
}

/// The statistics of every (scenario, setting) with runs among `finished`,
/// ordered by scenario, then setting.
pub fn setting_stats(finished: &[(&JobRecord, &JobRow)]) -> Vec<SettingStats> {
    let mut keys: Vec<(usize, usize)> = finished
        .iter()
        .map(|(j, _)| (j.scenario, j.setting))
        .collect();
    keys.sort_unstable();
    keys.dedup();
    keys.into_iter()
        .map(|(scenario, setting)| {
            let runs: Vec<&(&JobRecord, &JobRow)> = finished
                .iter()
                .filter(|(j, _)| j.scenario == scenario && j.setting == setting)
                .collect();
            let mut mean = [0.0; 4];
            let mut worst = [f64::NEG_INFINITY; 4];
            let mut best = [f64::INFINITY; 4];
            for (i, o) in Objective::ALL.iter().enumerate() {
                for (_, row) in &runs {
                    let x = o.of(&row.outcome);
                    mean[i] += x / runs.len() as f64;
                    worst[i] = worst[i].max(x);
                    best[i] = best[i].min(x);
                }
            }
            SettingStats {
                scenario,
                setting,
                controller: runs[0].0.controller.clone(),
                runs: runs.len(),
                completed: runs.iter().filter(|(_, r)| r.outcome.completed).count(),
                mean,
                worst,
                spread: std::array::from_fn(|i| worst[i] - best[i]),
            }
        })
        .collect()
}
