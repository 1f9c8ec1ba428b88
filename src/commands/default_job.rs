//! What `shearcut` does with no subcommand: the main job on the built-in
//! default scenario.
//!
//! Until the closed loop lands, the main job is the open-loop simulation of
//! the default scenario (`fig7-potato`, seed 000 Fig. 7(b)): four cuts of a
//! potato cuboid by the FEM cross-section model, written to `runs/`.

use crate::commands::simulate;
use crate::error::RunError;
use crate::scenario::{DEFAULT_SCENARIO, Scenario};

/// Runs the main job on the default scenario.
pub fn run() -> Result<(), RunError> {
    let (name, text) = DEFAULT_SCENARIO;
    let s = Scenario::parse(text, name, name)?;
    println!(
        "shearcut: no command given, running `shearcut simulate {name}` (see --help for all commands)"
    );
    simulate::run_scenario(&s, None)
}
