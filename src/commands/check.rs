//! `shearcut check`: validate a scenario and print it with presets resolved.
//!
//! Checks everything a run would refuse before it starts: every value in
//! its physical range, the object's mesh file (read and checked as a closed
//! surface), the surrogate the MPC would plan with (read and checked), and
//! the resource estimate against its budget (docs/reliability.md).

use shearcut_sim::resource_budget::{PLANT_NODES_BUDGET, SECTION_NODES_BUDGET, SERIES_ROWS_BUDGET};

use crate::cli::print;
use crate::controller_choice::ControllerChoice;
use crate::error::{ConfigError, RunError};
use crate::scenario::{Scenario, WireSlabScenario};
use crate::surrogates::surrogate_for;

/// Loads and validates `scenario` (a path or a built-in name), opens the
/// surrogate its MPC would use (when the controller is the MPC or a
/// surrogate is named) and prints the resolved values as TOML with the
/// resource estimate as a comment.
pub fn run(scenario: &str) -> Result<(), RunError> {
    if let Some(s) = WireSlabScenario::load(scenario)? {
        print(&format!(
            "# {scenario}: valid. Resolved values (SI units):\n{}",
            toml::to_string_pretty(&s)
                .expect("a resolved scenario is plain data and always serialises")
        ))?;
        return Ok(());
    }
    let s = Scenario::load(scenario)?;
    let invalid = |setting| {
        RunError::Config(ConfigError::Invalid {
            path: scenario.to_string(),
            setting,
        })
    };
    if s.controller.kind == ControllerChoice::Mpc || s.controller.surrogate.is_some() {
        surrogate_for(&s).map_err(invalid)?;
    }
    let r = s.resources(s.object_extent().map_err(invalid)?);
    print(&format!(
        "# {scenario}: valid. Resolved values (SI units):\n\
         # resources: section mesh {:.0} nodes (budget {SECTION_NODES_BUDGET}), plant meshes {:.0} nodes (budget {PLANT_NODES_BUDGET}), series {:.0} rows (budget {SERIES_ROWS_BUDGET})\n{}",
        r.section_nodes,
        r.plant_nodes,
        r.series_rows,
        resolved_toml(&s)
    ))
}

/// The resolved scenario as TOML text.
pub fn resolved_toml(s: &Scenario) -> String {
    toml::to_string_pretty(s).expect("a resolved scenario is plain data and always serialises")
}
