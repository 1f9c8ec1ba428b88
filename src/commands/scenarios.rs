//! `shearcut scenarios`: the built-in scenarios, one line each.

use crate::error::RunError;
use crate::scenario::{
    BUILT_IN_SCENARIOS, BUILT_IN_WIRE_SLAB_SCENARIOS, Scenario, WireSlabScenario,
};

/// Prints every built-in scenario as `name  description`, in the order of
/// [`BUILT_IN_SCENARIOS`] (seed 000's figures, then the closed loops).
pub fn run() -> Result<(), RunError> {
    crate::cli::print(&listing()?)
}

/// The listing `run` prints: one line per built-in scenario, names padded to
/// a common width.
pub fn listing() -> Result<String, RunError> {
    let width = BUILT_IN_SCENARIOS
        .iter()
        .chain(BUILT_IN_WIRE_SLAB_SCENARIOS.iter())
        .map(|(name, _)| name.len())
        .max()
        .unwrap_or(0);
    let mut out = String::new();
    for (name, text) in BUILT_IN_SCENARIOS {
        let scenario = Scenario::parse(text, name, name)?;
        out.push_str(&format!("{name:<width$}  {}\n", scenario.description));
    }
    for (name, _) in BUILT_IN_WIRE_SLAB_SCENARIOS {
        if let Some(scenario) = WireSlabScenario::load(name)? {
            out.push_str(&format!("{name:<width$}  {}\n", scenario.description));
        }
    }
    Ok(out)
}

/// The names of the built-in scenarios as `shearcut --help` lists them.
pub fn names_help() -> String {
    let names: Vec<&str> = BUILT_IN_SCENARIOS
        .iter()
        .chain(BUILT_IN_WIRE_SLAB_SCENARIOS.iter())
        .map(|(name, _)| *name)
        .collect();
    format!(
        "Built-in scenarios (SCENARIO may be one of these names or a TOML path; \
         `shearcut scenarios` describes them):\n  {}",
        names.join("\n  ")
    )
}
