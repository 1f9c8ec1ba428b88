//! # 05: a controller process over iceoryx2, for an arm bridge
//!
//! Shows the controller's side of the arm-style loop as a process of its
//! own: it opens run ID's services under the iceoryx2 prefix in force
//! (`SHEARCUT_IPC_PREFIX`, default `shearcut_`), waits for whatever serves
//! that run's measurement board — `shearcut plant` or an arm bridge that
//! speaks docs/wire_format.md — and then, once per servo tick, writes the
//! MPC's command and reads the arm's answer (blocking waits, in lockstep
//! with the plant). It stops when the MPC has finished its cut and the arm
//! is at rest, or, against the simulated plant, when the plant's crack
//! front reaches the target depth (as `shearcut controller` does); then it
//! ends the run, and the plant or bridge stops serving.
//!
//! The scenario (default `loop-potato-whole-realtime`, the main job's)
//! gives the MPC its task: knife, sensor mount, the object's outline, the
//! target depth and blade stroke, the servo period. Against `shearcut
//! plant` on the same scenario the cut is the main job's, bit for bit.
//!
//! Prints when the plant answers, then every 100 ticks: time, the knife's
//! height and position along the edge (m), the slice-push ratio the MPC
//! follows and the sensor's y force (N); then the ticks taken, why the run
//! ended, the round trips' median and p99, and the knife's work when the
//! plant is simulated.
//!
//! ```sh
//! cargo run --release -- plant --scenario loop-potato-whole-realtime --run-id demo &
//! cargo run --release --example 05_controller_over_iceoryx2 -- demo
//! ```

use std::process::ExitCode;

use shearcut::closed_loop::LoopSetup;
use shearcut::closed_loop::{PlantLink, TickTimes};
use shearcut::commands::controller::link_timeouts;
use shearcut::controller_choice::ControllerChoice;
use shearcut::scenario::Scenario;
use shearcut::transport::loop_services::prefix;
use shearcut::transport::{Iceoryx2PlantLink, LoopServices, Role, WaitMode};
use shearcut_controllers::controller::CutPhase;
use shearcut_sim::arm::KnifeCommand;

/// The arm is at rest below this speed, m/s.
const AT_REST: f64 = 1e-9;

/// How a drive ended.
#[derive(Debug)]
struct Drive {
    /// Controller ticks sent after the first (at-rest) command.
    ticks: usize,
    /// Whether the MPC ended its cut (rather than the simulated plant's
    /// crack front reaching the target depth).
    controller_done: bool,
    /// The knife's work, J, when the plant reports its ground truth.
    work: Option<f64>,
    /// Wall-clock command → measurement round trips.
    round_trip: TickTimes,
}

/// Drives run `run_id`'s plant (under the iceoryx2 prefix `ipc_prefix`)
/// with the MPC of `scenario`, printing every 100th tick when `print` is
/// set.
fn drive(
    scenario: &Scenario,
    run_id: &str,
    ipc_prefix: &str,
    print: bool,
) -> Result<Drive, Box<dyn std::error::Error>> {
    let setup = LoopSetup::new(scenario, ControllerChoice::Mpc)?;
    let mut mpc = setup.controller(scenario, ControllerChoice::Mpc)?;
    let services = LoopServices::open(Role::Controller, run_id, ipc_prefix)?;
    let max_ticks = (scenario.controller.max_duration / setup.task.period).ceil() as usize;
    let mut link = Iceoryx2PlantLink::new(
        services,
        setup.task.period,
        link_timeouts(scenario),
        WaitMode::Blocking,
        max_ticks + 2,
    )?;
    link.wait_for_plant()?;
    if print {
        println!("{} answers run {run_id}", link.plant_name());
        println!(" t (s)   height (m)   along (m)      xi    Fy (N)");
    }
    // The first command: the arm at rest, before the MPC has seen a reading.
    let mut answer = link.exchange(&KnifeCommand::default())?;
    let mut ticks = 0;
    let controller_done = loop {
        let command = mpc.tick(&answer.reading);
        answer = link.exchange(&command)?;
        ticks += 1;
        let r = &answer.reading;
        if print && ticks % 100 == 0 {
            println!(
                "{:6.3} {:12.5} {:11.5} {:7.2} {:9.2}",
                r.time,
                r.position.y,
                r.position.z,
                mpc.telemetry().slice_push_ratio,
                r.wrench[1]
            );
        }
        if answer
            .truth
            .is_some_and(|t| t.crack_depth >= setup.task.target_depth)
        {
            break false;
        }
        if mpc.telemetry().phase == CutPhase::Done && r.velocity.norm() < AT_REST {
            break true;
        }
        if ticks >= max_ticks {
            return Err(format!("no end after {ticks} ticks").into());
        }
    };
    // Tell the plant or bridge that the run is over.
    link.finish()?;
    Ok(Drive {
        ticks,
        controller_done,
        work: answer.truth.map(|t| t.work),
        round_trip: link.round_trips(),
    })
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (run_id, scenario) = match args.as_slice() {
        [id] => (id.as_str(), "loop-potato-whole-realtime"),
        [id, scenario] => (id.as_str(), scenario.as_str()),
        _ => {
            eprintln!("usage: 05_controller_over_iceoryx2 RUN_ID [SCENARIO]");
            return ExitCode::from(2);
        }
    };
    let scenario = match Scenario::load(scenario) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    };
    match drive(&scenario, run_id, &prefix(), true) {
        Ok(d) => {
            println!(
                "{} ticks; ended by the {}; round trip median {:.1} us, p99 {:.1} us",
                d.ticks,
                if d.controller_done {
                    "MPC (cut done, at rest)"
                } else {
                    "plant (crack front at the target depth)"
                },
                d.round_trip.median_us,
                d.round_trip.p99_us
            );
            if let Some(work) = d.work {
                println!("work {work:.4} J");
            }
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}

#[cfg(test)]
mod tests {
    use std::time::Duration;

    use shearcut::closed_loop::InProcessPlant;
    use shearcut::closed_loop::run_closed_loop;
    use shearcut::transport::{PlantEnd, PlantServerSettings, serve_plant};

    use super::*;

    /// Against the scenario's simulated plant served from another thread,
    /// the example's drive is the in-process loop's cut: the same ticks and
    /// the same work to the bit (lockstep is deterministic), ended by the
    /// plant's depth; and the plant stops serving when the drive ends.
    #[test]
    fn the_drive_is_the_main_job_cut() {
        let name = "loop-potato-whole-realtime";
        let scenario = Scenario::load(name).unwrap();
        let ipc_prefix = format!("sc05_{}_", std::process::id());
        let plant_prefix = ipc_prefix.clone();
        let plant_scenario = scenario.clone();
        let server = std::thread::spawn(move || {
            let s = plant_scenario;
            let setup = LoopSetup::new(&s, ControllerChoice::Mpc).unwrap();
            let mut plant = InProcessPlant::new(setup.plant(&s).unwrap(), setup.task.period);
            let services = LoopServices::open(Role::Plant, "ex05", &plant_prefix).unwrap();
            let mut settings =
                PlantServerSettings::new(s.control_loop.clock, s.control_loop.missed_command_limit);
            // A loaded machine's stall must not count as a missed command.
            settings.lockstep_patience = Duration::from_secs(5);
            serve_plant(&services, &mut plant, &settings).unwrap()
        });
        let drive = drive(&scenario, "ex05", &ipc_prefix, false);
        let report = server.join().unwrap();
        if let Ok(entries) = std::fs::read_dir("/dev/shm") {
            for e in entries.flatten() {
                if e.file_name().to_string_lossy().starts_with(&ipc_prefix) {
                    std::fs::remove_file(e.path()).ok();
                }
            }
        }
        let drive = drive.unwrap();
        assert_eq!(report.end, PlantEnd::Ended);
        let run = run_closed_loop(&scenario, ControllerChoice::Mpc).unwrap();
        assert!(!drive.controller_done);
        assert_eq!(drive.ticks, run.output.ticks);
        assert_eq!(
            drive.work.map(f64::to_bits),
            Some(run.summary.work_j.to_bits())
        );
    }
}
