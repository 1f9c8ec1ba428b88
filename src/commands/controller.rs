//! `shearcut controller`: the controller process of the arm-style loop. It
//! drives a plant served over iceoryx2 (`shearcut plant`, or an arm bridge
//! speaking the wire format) tick by tick, then writes the same results as
//! the in-process `shearcut run`, plus the loop's statistics.

use std::path::Path;

use serde::Serialize;

use crate::closed_loop::{LinkError, PlantLink};
use crate::closed_loop::{LoopEnd, SeriesStream, TickTimes, run_loop_recorded};
use crate::closed_loop::{LoopSetup, RunOutput};
use crate::commands::run::{Transport, print_summary, write_results};
use crate::controller_choice::ControllerChoice;
use crate::cut_record::CutSummary;
use crate::error::{ConfigError, RunError};
use crate::result_file::write_json;
use crate::run_dir::{self, Destination};
use crate::run_replica::RunReplica;
use crate::scenario::{ClockMode, Scenario, check_controller_kind};
use crate::transport::loop_services::{node_name, prefix};
use crate::transport::servo_priority::raise_servo_thread;
use crate::transport::{Iceoryx2PlantLink, LinkTimeouts, LoopServices, Role, RunNode, WaitMode};
use shearcut_sim::InvalidSetting;

/// `loop_stats.json`: how the link between the processes behaved.
#[derive(Debug, Serialize)]
struct LoopStats<'a> {
    run_id: &'a str,
    plant: &'a str,
    clock: ClockMode,
    wait: &'a str,
    /// Wall-clock command → measurement round trips.
    round_trip: TickTimes,
    /// Commands the plant reported missed (realtime clock).
    missed_commands: u32,
    /// Commands the arm refused for breaking a limit.
    limit_faults: usize,
    /// The simulated plant's successor sections found unbuilt when due and
    /// gone on without (realtime clock; `null` from a plant that does not
    /// publish its counts, e.g. an arm bridge).
    successor_deferrals: Option<u64>,
    /// The simulated plant's successor sections waited for (lockstep;
    /// `null` as above).
    successor_waits: Option<u64>,
    end: &'a LoopEnd,
}

/// The controller choice named on the command line (`--controller`,
/// within the same ranges as the scenario's `[controller] kind`), or the
/// scenario's.
pub fn controller_choice(s: &Scenario, text: Option<&str>) -> Result<ControllerChoice, RunError> {
    const KEY: &str = "--controller";
    let Some(text) = text else {
        return Ok(s.controller.kind);
    };
    let refused = |e: InvalidSetting| RunError::Config(ConfigError::Argument(e));
    let choice = text.parse::<ControllerChoice>().map_err(|e| {
        refused(InvalidSetting {
            key: KEY.to_string(),
            ..e
        })
    })?;
    check_controller_kind(KEY, choice).map_err(refused)?;
    Ok(choice)
}

/// The link's timeouts for a scenario: the plant must serve the run within
/// `[loop] connect_timeout`; lockstep waits up to 30 s for an answer (a
/// plant may rebuild a section); realtime up to the braking time
/// (missed-command limit × period) plus 1 s.
pub fn link_timeouts(s: &Scenario) -> LinkTimeouts {
    let mut t = LinkTimeouts {
        connect: std::time::Duration::from_secs_f64(s.control_loop.connect_timeout),
        ..LinkTimeouts::default()
    };
    if s.control_loop.clock == ClockMode::Realtime {
        t.response = std::time::Duration::from_secs_f64(
            1.0 + f64::from(s.control_loop.missed_command_limit) / s.control_loop.rate_hz,
        );
    }
    t
}

/// Runs the controller process: connect to run `run_id`'s plant, close the
/// loop, write the results to `out` (default `runs/<scenario>-<time>/`).
///
/// # Errors
/// Bad input (a run id a live controller serves included); the plant is
/// lost, braked or failed, or a signal stopped the run (partial results are
/// written first; exit 130/143 for a signal); writing failed.
pub fn run(
    scenario: &str,
    run_id: &str,
    controller: Option<&str>,
    wait: WaitMode,
    out: &Destination,
) -> Result<(), RunError> {
    let s = Scenario::load(scenario)?;
    // The node before the directory: a run id a live controller serves is
    // refused at once, and leaves no directory.
    let node = RunNode::create(Role::Controller, run_id, &prefix())
        .map_err(|e| RunError::service(&node_name(Role::Controller, run_id), e))?;
    let dir = run_dir::claim(&s.name, out, &crate::commands::check::resolved_toml(&s))?;
    serve(&s, node, controller, wait, &dir).inspect_err(|_| run_dir::abandon(&dir))
}

/// The controller process once its result directory `dir` is claimed.
fn serve(
    s: &Scenario,
    node: RunNode,
    controller: Option<&str>,
    wait: WaitMode,
    dir: &Path,
) -> Result<(), RunError> {
    let run_id = node.run_id.clone();
    let run_id = run_id.as_str();
    let choice = controller_choice(s, controller)?;
    let setup = LoopSetup::new(s, choice)?;
    let task = setup.task.clone();
    let mut ctl = setup.controller(s, choice)?;
    // The series writer's thread starts here, before the servo thread's
    // priority is raised (a thread inherits its creator's scheduling).
    let mut stream = SeriesStream::create(dir)?;
    // The MPC's planner thread has started (with the controller) at normal
    // priority; only this, the servo thread, is raised.
    raise_servo_thread(s.control_loop.servo_priority)
        .map_err(|e| RunError::Loop(format!("controller/{run_id}: {e}")))?;
    // The knife's start, as the plant process builds it (same scenario and
    // direction), labels the samples exactly as the in-process loop does.
    let cut = setup.cut(s);
    let services = LoopServices::on(node)
        .map_err(|e| RunError::service(&node_name(Role::Controller, run_id), e))?;
    let max_ticks = (cut.max_duration / task.period).ceil() as usize + 2;
    let mut link = Iceoryx2PlantLink::new(
        services,
        task.period,
        link_timeouts(s),
        wait,
        max_ticks.min(1 << 22),
    )
    .map_err(|e| RunError::Loop(e.to_string()))?;
    link.wait_for_plant().map_err(|e| match e {
        LinkError::Stopped(signal) => RunError::Signalled {
            signal,
            message: format!("controller/{run_id}: {e}"),
        },
        e => RunError::Loop(e.to_string()),
    })?;
    let output = run_loop_recorded(&mut link, ctl.as_mut(), &cut, &mut stream);
    // The end of the run goes to the plant at once: a realtime plant that
    // waited for it through the series' last flush would step on without a
    // command and count a miss.
    if !matches!(output.end, LoopEnd::Failed(_))
        && let Err(e) = link.finish()
    {
        tracing::warn!("{e}");
    }
    let dropped = stream.finish()?;
    let summary = CutSummary::from_samples(&output.samples, task.target_depth);
    let run = RunOutput {
        controller: ctl.name().to_string(),
        output,
        summary,
        target_depth_m: task.target_depth,
        replica: RunReplica::NOMINAL,
    };
    write_results(s, &run, Transport::Iceoryx2, dropped, dir)?;
    let round_trip = link.round_trips();
    // The plant writes its counts before each answer: after the end of the
    // run's acknowledgement they are final.
    let successors = link.successor_counts();
    write_json(
        &dir.join("loop_stats.json"),
        &LoopStats {
            run_id,
            plant: link.plant_name(),
            clock: s.control_loop.clock,
            wait: match wait {
                WaitMode::Blocking => "blocking",
                WaitMode::BusyPoll => "busy-poll",
            },
            round_trip,
            missed_commands: link.missed_commands(),
            limit_faults: run.output.limit_faults,
            successor_deferrals: successors.map(|c| c.successor_deferrals),
            successor_waits: successors.map(|c| c.successor_waits),
            end: &run.output.end,
        },
    )?;
    tracing::info!("results written to {}/", dir.display());
    print_summary(s, &run)?;
    crate::outln!(
        "loop over iceoryx2 (run {run_id}, {:?} clock): round trip median {:.1} us, p99 {:.1} us, max {:.1} us; missed commands {}",
        s.control_loop.clock,
        round_trip.median_us,
        round_trip.p99_us,
        round_trip.max_us,
        link.missed_commands()
    )?;
    crate::outln!(
        "results: {}/ (timeseries.csv, controller.csv, summary.json, loop_stats.json, scenario.toml, forces_work.svg/.png, controller.svg/.png)",
        dir.display()
    )?;
    run.output.end.exit(dir)
}
