//! `shearcut plant`: the plant process of the arm-style loop. It builds the
//! scenario's plant and serves it over iceoryx2 to one controller
//! (`shearcut controller`) until the run ends, the plant brakes after too
//! many missed commands, or SIGINT/SIGTERM.

use std::io::Write;

use crate::closed_loop::InProcessPlant;
use crate::closed_loop::LoopSetup;
use crate::commands::controller::controller_choice;
use crate::error::RunError;
use crate::scenario::{ClockMode, Scenario};
use crate::transport::loop_services::{node_name, prefix};
use crate::transport::peer_watch::{
    ENDED_PEER_SIGNAL_WAIT, PeerFate, gone_before_loop, gone_in_loop,
};
use crate::transport::servo_priority::raise_servo_thread;
use crate::transport::{
    LoopServices, PlantEnd, PlantServerSettings, Role, RunNode, ServiceError, WaitMode, serve_plant,
};
use shearcut_plant::SuccessorPolicy;

/// Runs the plant process for run `run_id`. `controller` names the
/// controller whose nominal direction the plant's sections are planned for
/// (assumption A2; default: the scenario's).
///
/// # Errors
/// Bad input (a run id a live plant serves included); the plant braked,
/// failed, saw no controller or was stopped (exit 130/143).
pub fn run(
    scenario: &str,
    run_id: &str,
    controller: Option<&str>,
    wait: WaitMode,
) -> Result<(), RunError> {
    let s = Scenario::load(scenario)?;
    let choice = controller_choice(&s, controller)?;
    let name = node_name(Role::Plant, run_id);
    // The node first: a controller waiting for this plant sees it there
    // while the plant builds, and sees it go if the build fails or the
    // process dies.
    let node =
        RunNode::create(Role::Plant, run_id, &prefix()).map_err(|e| RunError::service(&name, e))?;
    let setup = LoopSetup::new(&s, choice)?;
    let task = setup.task.clone();
    let mut plant = setup.plant(&s)?;
    if s.control_loop.clock == ClockMode::Realtime {
        // A tick that waited for a section build would miss its period;
        // the first sections are built before the first tick.
        plant.set_successor_policy(SuccessorPolicy::KeepCurrent);
        plant.build_ordered_sections();
    }
    // The thread that steps and answers runs at the servo priority, as an
    // arm's servo loop does; the successor workers and the node's watch
    // thread have started at normal priority (a thread inherits its
    // creator's scheduling only when it is created). The section-stepping
    // helpers start again from here, to step at the same priority.
    raise_servo_thread(s.control_loop.servo_priority)
        .map_err(|e| RunError::Loop(format!("{name}: {e}")))?;
    if s.control_loop.servo_priority > 0 && plant.stepping_threads() > 1 {
        plant.restart_stepping_threads();
    }
    let mut link = InProcessPlant::new(plant, task.period);
    if s.control_loop.clock == ClockMode::Realtime {
        // Answer first, re-choose in the time before the next tick.
        link.answer_first();
    }
    // A stop asked while it built: it never serves (its controller sees
    // its node go before serving). A controller that exited meanwhile may
    // have been stopped by the same signal (a supervisor's stop).
    let pending = if node.peer.fate() == PeerFate::Ended {
        node.watch.requested_within(ENDED_PEER_SIGNAL_WAIT)
    } else {
        node.watch.requested()
    };
    if let Some(signal) = pending {
        return Err(RunError::service(&name, ServiceError::Stopped(signal)));
    }
    let services = LoopServices::on(node).map_err(|e| RunError::service(&name, e))?;
    let mut settings =
        PlantServerSettings::new(s.control_loop.clock, s.control_loop.missed_command_limit);
    settings.wait = wait;
    let report = serve_plant(&services, &mut link, &settings)
        .map_err(|e| RunError::Loop(format!("{name}: {e}")))?;
    tracing::info!(
        "the plant re-chose its moving sections {} times over the cut",
        link.plant().rechoices()
    );
    // A realtime plant's own lateness: answers that ended after the next
    // tick was due, and the misses right after them.
    let overruns = if s.control_loop.clock == ClockMode::Realtime {
        format!(
            "; {} right after one of the plant's {} overruns",
            report.missed_after_overrun, report.overruns
        )
    } else {
        String::new()
    };
    let counts = format!(
        "{} commands answered, {} steps, {} missed commands (longest run {}{overruns}), {} successor deferrals, {} successor waits",
        report.commands,
        report.steps,
        report.missed_commands,
        report.max_consecutive_missed,
        link.plant().successor_deferrals(),
        link.plant().successor_waits()
    );
    match report.end {
        PlantEnd::Ended => {
            // A closed stderr (a supervisor gone) leaves the exit code.
            let _ = writeln!(
                std::io::stderr(),
                "{name}: the controller ended the run; {counts}"
            );
            Ok(())
        }
        PlantEnd::Braked(n) => Err(RunError::Loop(format!(
            "{name}: braked after {n} consecutive missed commands (missed_command_limit = {}); {counts}",
            s.control_loop.missed_command_limit
        ))),
        PlantEnd::ModelFailed(why) => Err(RunError::Loop(format!(
            "{name}: the plant model failed: {why}; {counts}"
        ))),
        PlantEnd::NoController => Err(RunError::Loop(format!(
            "{name}: no controller sent a command within {:?}",
            settings.connect_timeout
        ))),
        PlantEnd::ControllerDied => Err(RunError::Loop(format!(
            "{name}: lost the controller: {}",
            gone_before_loop(Role::Controller, run_id, PeerFate::Died)
        ))),
        PlantEnd::ControllerEnded => Err(RunError::Loop(format!(
            "{name}: lost the controller: {}",
            gone_before_loop(Role::Controller, run_id, PeerFate::Ended)
        ))),
        PlantEnd::ControllerDiedInLoop => Err(RunError::Loop(format!(
            "{name}: lost the controller: {}; braked; {counts}",
            gone_in_loop(Role::Controller, run_id, PeerFate::Died, report.commands)
        ))),
        PlantEnd::ControllerEndedInLoop => Err(RunError::Loop(format!(
            "{name}: lost the controller: {}; braked; {counts}",
            gone_in_loop(Role::Controller, run_id, PeerFate::Ended, report.commands)
        ))),
        PlantEnd::Terminated(signal) => Err(RunError::Signalled {
            signal,
            message: format!("{name}: stopped by {signal}; {counts}"),
        }),
    }
}
