//! `shearcut check`: validate a scenario and print it with presets resolved.

use crate::error::RunError;
use crate::scenario::{Scenario, WireSlabScenario};

/// Loads and validates `scenario` (a path or a built-in name) and prints the
/// resolved values as TOML.
pub fn run(scenario: &str) -> Result<(), RunError> {
    if let Some(s) = WireSlabScenario::load(scenario)? {
        println!("# {scenario}: valid. Resolved values (SI units):");
        print!(
            "{}",
            toml::to_string_pretty(&s)
                .expect("a resolved scenario is plain data and always serialises")
        );
        return Ok(());
    }
    let s = Scenario::load(scenario)?;
    println!("# {scenario}: valid. Resolved values (SI units):");
    print!("{}", resolved_toml(&s));
    Ok(())
}

/// The resolved scenario as TOML text.
pub fn resolved_toml(s: &Scenario) -> String {
    toml::to_string_pretty(s).expect("a resolved scenario is plain data and always serialises")
}
