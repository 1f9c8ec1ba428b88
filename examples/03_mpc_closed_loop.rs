//! # 03: the MPC against the plant, in process
//!
//! Shows the closed loop at its plainest: the main job's scenario
//! (`loop-potato-whole-realtime`: a chef's knife through a half potato,
//! 25 mm deep with 15 mm of blade stroke) builds the MPC and the plant, and
//! one loop hands the plant's arm reading to `Controller::tick` and the
//! command it returns to `Plant::step`, once per 1 ms servo tick, until the
//! crack front is at the target depth. The MPC sees only the reading (the
//! knife's pose and twist, the F/T wrench, the arm's status); the plant's
//! ground truth (crack depth, work) is read here only to stop and report.
//! This is the loop `shearcut run` runs in process, and the same cut the
//! two processes of the main job run over iceoryx2, bit for bit.
//!
//! Prints every 50 ticks: time, crack depth, the slice-push ratio
//! ξ = v_t / v_n and the normal speed the MPC is following, and the F/T
//! sensor's y force (object on knife, N); then the ticks taken and the
//! knife's total work (the main job's `work` line).
//!
//! ```sh
//! cargo run --release --example 03_mpc_closed_loop
//! ```

use shearcut::closed_loop::LoopSetup;
use shearcut::controller_choice::ControllerChoice;
use shearcut::scenario::Scenario;
use shearcut_sim::arm::KnifeCommand;

/// What the example's cut produced.
struct Cut {
    /// Controller ticks until the crack front reached the target depth.
    ticks: usize,
    /// The knife's total work, J.
    work: f64,
}

/// Runs the MPC against the plant until the target depth (or 30 s of
/// simulated time), printing every 50th tick.
fn cut() -> Result<Cut, Box<dyn std::error::Error>> {
    let scenario = Scenario::load("loop-potato-whole-realtime")?;
    let setup = LoopSetup::new(&scenario, ControllerChoice::Mpc)?;
    let mut mpc = setup.controller(&scenario, ControllerChoice::Mpc)?;
    let mut plant = setup.plant(&scenario)?;
    let dt = setup.task.period;
    // The first exchange: the arm at rest, before the MPC has seen a reading.
    let mut step = plant.step(&KnifeCommand::default(), dt)?;
    let mut ticks = 0;
    while step.truth.crack_depth < setup.task.target_depth && step.reading.time < 30.0 {
        let command = mpc.tick(&step.reading);
        step = plant.step(&command, dt)?;
        ticks += 1;
        if ticks % 50 == 0 {
            let planned = mpc.telemetry();
            println!(
                "{:6.3} {:10.2} {:8.2} {:12.1} {:9.2}",
                step.reading.time,
                step.truth.crack_depth * 1e3,
                planned.slice_push_ratio,
                planned.normal_speed * 1e3,
                step.reading.wrench[1]
            );
        }
    }
    Ok(Cut {
        ticks,
        work: step.truth.work,
    })
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    println!(" t (s)  crack (mm)       xi  v_n (mm/s)    Fy (N)");
    let cut = cut()?;
    println!("{} ticks; work {:.4} J", cut.ticks, cut.work);
    Ok(())
}

#[cfg(test)]
mod tests {
    use shearcut::closed_loop::run_closed_loop;

    use super::*;

    /// The example's loop, printing as `main` does, is `shearcut run`'s:
    /// the same ticks and the same work to the bit (lockstep runs are
    /// deterministic).
    #[test]
    fn the_example_is_the_library_loop() {
        let cut = cut().unwrap();
        let scenario = Scenario::load("loop-potato-whole-realtime").unwrap();
        let run = run_closed_loop(&scenario, ControllerChoice::Mpc).unwrap();
        assert_eq!(cut.ticks, run.output.ticks);
        assert_eq!(cut.work.to_bits(), run.summary.work_j.to_bits());
    }
}
