//! `shearcut check`: validate a scenario and print it with presets resolved.
//!
//! Checks everything a run would refuse before it starts: every value in
//! its physical range, the object's mesh file (read and checked as a closed
//! surface), the surrogate the scenario names (read and checked; the one
//! its MPC would look up is part of `run`'s readiness), the
//! resource estimate against its budget, and the geometry each command
//! builds before its first step: `simulate`'s cuts along the edge and
//! `run`'s cut task, plant and controller (docs/reliability.md). A scenario
//! that one of the two refuses is valid with a comment saying why; one that
//! both refuse is not.

use shearcut_sim::resource_budget::{PLANT_NODES_BUDGET, SECTION_NODES_BUDGET, SERIES_ROWS_BUDGET};

use crate::cli::print;
use crate::closed_loop::LoopSetup;
use crate::commands::simulate;
use crate::error::{ConfigError, RunError};
use crate::scenario::{Scenario, WireSlabScenario};
use crate::surrogates::surrogate_for;

/// Loads and validates `scenario` (a path or a built-in name), opens the
/// surrogate it names (the one its MPC would look up otherwise is `run`'s
/// readiness), checks what `simulate` and `run` would build, and
/// prints the resolved values as TOML with the resource estimate and each
/// command's readiness as comments.
///
/// # Errors
/// The scenario does not load, or neither command can use it (exit 2).
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
    // A surrogate the scenario names is part of it: a bad one is bad input.
    // One the MPC would look up (none named) is `run`'s to find: a scenario
    // without one is still one `simulate` cuts, and `run --controller` runs.
    if s.controller.surrogate.is_some() {
        surrogate_for(&s).map_err(invalid)?;
    }
    let r = s.resources(s.object_extent().map_err(invalid)?);
    let readiness = match command_checks(&s) {
        (Err(a), Err(b)) => {
            return Err(RunError::Config(ConfigError::Unusable {
                path: scenario.to_string(),
                simulate: reason(&a),
                run: reason(&b),
            }));
        }
        (a, b) => format!("# simulate: {}\n# run: {}", readiness(a), readiness(b)),
    };
    print(&format!(
        "# {scenario}: valid. Resolved values (SI units):\n\
         # resources: section mesh {:.0} nodes (budget {SECTION_NODES_BUDGET}), plant meshes {:.0} nodes (budget {PLANT_NODES_BUDGET}), series {:.0} rows (budget {SERIES_ROWS_BUDGET})\n{readiness}\n{}",
        r.section_nodes,
        r.plant_nodes,
        r.series_rows,
        resolved_toml(&s)
    ))
}

/// What `simulate` and what `run` check of `s` before their first step, in
/// that order: `Ok` where the command takes it.
pub fn command_checks(s: &Scenario) -> (Result<(), RunError>, Result<(), RunError>) {
    (simulate::check(s), check_run(s))
}

/// What `run` checks before its first tick: the cut task and the object as
/// its controller sees it ([`LoopSetup`]), the plant's edge over the object
/// ([`LoopSetup::check_plant`]) and the controller.
fn check_run(s: &Scenario) -> Result<(), RunError> {
    let setup = LoopSetup::new(s, s.controller.kind)?;
    setup.check_plant(s)?;
    setup.controller(s, s.controller.kind).map(|_| ())
}

/// `ready`, or why the command refuses the scenario.
fn readiness(check: Result<(), RunError>) -> String {
    match check {
        Ok(()) => "ready".to_string(),
        Err(e) => format!("refuses it: {}", reason(&e)),
    }
}

/// Why a command refuses the scenario: the setting of a refusal (the
/// scenario is named once, on `check`'s own line), else the whole message.
fn reason(e: &RunError) -> String {
    match e {
        RunError::Config(ConfigError::Invalid { setting, .. }) => setting.to_string(),
        other => other.to_string(),
    }
}

/// The resolved scenario as TOML text.
pub fn resolved_toml(s: &Scenario) -> String {
    toml::to_string_pretty(s).expect("a resolved scenario is plain data and always serialises")
}
