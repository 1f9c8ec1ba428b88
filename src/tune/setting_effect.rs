//! Each setting's effect: for every column that takes more than one value
//! on a scenario's runs (a swept controller key, a variant's factor, the
//! controller itself), the mean of each objective over the completed runs
//! with each value — the main effect of that column, averaged over
//! everything else the sweep varied.
//!
//! A controller's own keys (`controller.*` but `controller.kind`) are
//! compared within each controller family (`mpc`, `slice`, `press`,
//! `force`) only: a baseline's row carries the MPC's default weights, which
//! it does not use, and would blur the MPC's levels.

use serde::Serialize;

use crate::tune::job_list::{JobCatalog, JobRecord};
use crate::tune::job_outcome::JobRow;
use crate::tune::objective::Objective;

/// The effect of one column's value on one scenario.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct EffectLevel {
    /// The column (e.g. `controller.mpc.deformation_weight`).
    pub column: String,
    /// The controller family the runs are of (`mpc`, `slice`, …), or
    /// empty for all the scenario's runs.
    pub family: String,
    /// The value, as in the results table.
    pub value: String,
    /// Completed runs with this value.
    pub runs: usize,
    /// Mean of each objective over them ([`Objective::ALL`]'s order, SI).
    pub mean: [f64; 4],
}

/// The effects of every column varied on the runs of `scenario` among
/// `finished`: per column in catalogue order, per value in first
/// appearance order.
pub fn effects(
    catalog: &JobCatalog,
    scenario: usize,
    finished: &[(&JobRecord, &JobRow)],
) -> Vec<EffectLevel> {
    let runs: Vec<&(&JobRecord, &JobRow)> = finished
        .iter()
        .filter(|(j, r)| j.scenario == scenario && r.outcome.completed)
        .collect();
    let family = |j: &JobRecord| j.controller.split(':').next().unwrap_or("").to_string();
    let mut families: Vec<String> = runs.iter().map(|(j, _)| family(j)).collect();
    families.sort();
    families.dedup();
    let mut out = Vec::new();
    for (c, column) in catalog.setting_columns.iter().enumerate() {
        let per_family = column.starts_with("controller.") && column != "controller.kind";
        let scopes: Vec<String> = if per_family {
            families.clone()
        } else {
            vec![String::new()]
        };
        for scope in scopes {
            let of: Vec<&(&JobRecord, &JobRow)> = runs
                .iter()
                .copied()
                .filter(|(j, _)| scope.is_empty() || family(j) == scope)
                .collect();
            let mut values: Vec<&str> = Vec::new();
            for (j, _) in &of {
                if !values.contains(&j.cells[c].as_str()) {
                    values.push(&j.cells[c]);
                }
            }
            if values.len() < 2 {
                continue;
            }
            for v in values {
                let with: Vec<&JobRow> = of
                    .iter()
                    .filter(|(j, _)| j.cells[c] == v)
                    .map(|(_, r)| *r)
                    .collect();
                let n = with.len() as f64;
                out.push(EffectLevel {
                    column: column.clone(),
                    family: scope.clone(),
                    value: v.to_string(),
                    runs: with.len(),
                    mean: std::array::from_fn(|i| {
                        with.iter()
                            .map(|r| Objective::ALL[i].of(&r.outcome))
                            .sum::<f64>()
                            / n
                    }),
                });
            }
        }
    }
    out
}
