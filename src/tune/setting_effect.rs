//! Each setting's effect: for every column that takes more than one value
//! on a scenario's runs (a swept controller key, a variant's factor, the
//! controller itself), the mean of each objective over the completed runs
//! with each value — the main effect of that column, averaged over
//! everything else the sweep varied.

use serde::Serialize;

use crate::tune::job_list::{JobCatalog, JobRecord};
use crate::tune::job_outcome::JobRow;
use crate::tune::objective::Objective;

/// The effect of one column's value on one scenario.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct EffectLevel {
    /// The column (e.g. `controller.mpc.deformation_weight`).
    pub column: String,
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
    let mut out = Vec::new();
    for (c, column) in catalog.setting_columns.iter().enumerate() {
        let mut values: Vec<&str> = Vec::new();
        for (j, _) in &runs {
            if !values.contains(&j.cells[c].as_str()) {
                values.push(&j.cells[c]);
            }
        }
        if values.len() < 2 {
            continue;
        }
        for v in values {
            let with: Vec<&JobRow> = runs
                .iter()
                .filter(|(j, _)| j.cells[c] == v)
                .map(|(_, r)| *r)
                .collect();
            let n = with.len() as f64;
            out.push(EffectLevel {
                column: column.clone(),
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
    out
}
