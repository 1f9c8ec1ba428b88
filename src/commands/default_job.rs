//! What `shearcut` does with no subcommand: the main job on the built-in
//! default scenario.
//!
//! The main job is the arm-style closed loop: the MPC cutting a whole half
//! potato with the chef's knife, controller and plant in two processes over
//! iceoryx2 shared memory, in lockstep at 1 kHz
//! (`shearcut run loop-potato-whole-realtime --controller mpc --transport
//! iceoryx2`), written to `runs/`. Its scenario is `loop-potato-whole` on a
//! plant discretised to keep up with real time (coarser section mesh,
//! sections re-chosen every 2 mm of slide; the scenario file gives the
//! fidelity it costs).

use crate::commands::run;
use crate::error::RunError;
use crate::run_dir::Destination;
use crate::run_replica::RunReplica;

/// The default scenario of the main job.
pub const DEFAULT_JOB_SCENARIO: &str = "loop-potato-whole-realtime";

/// Runs the main job on the default scenario.
pub fn run() -> Result<(), RunError> {
    crate::outln!(
        "shearcut: no command given, running `shearcut run {DEFAULT_JOB_SCENARIO} --controller mpc --transport iceoryx2` (see --help for all commands)"
    )?;
    run::run(
        DEFAULT_JOB_SCENARIO,
        Some("mpc"),
        run::Transport::Iceoryx2,
        RunReplica::NOMINAL,
        &Destination::default(),
    )
}
