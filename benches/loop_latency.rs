//! Round-trip latency of the loop over iceoryx2 (controller → plant →
//! controller), in one process with the plant served from a second thread:
//! 100 000 ticks against an echo plant with busy polling and with blocking
//! waits; then the real plant (loop-potato-cuboid, `slice:0.75`, lockstep) closed by
//! the real controller, with its real-time factor; then the main job's
//! scenario (`loop-potato-whole-realtime`, MPC, lockstep) in process and
//! over iceoryx2, with their real-time factors (the transport's share is
//! their difference), and the same cut on the reference discretisation
//! (`loop-potato-whole`) in process.
//!
//! `cargo bench -p shearcut --bench loop_latency` (add `-- --ticks N` to
//! change the echo tick count, `-- --skip-default` to leave out the main
//! job's scenario). Timings on a shared VM are noisy: repeat.
#![allow(clippy::disallowed_methods)] // A benchmark reads the wall clock.

#[path = "../tests/support/echo_plant.rs"]
mod echo_plant;

use std::time::{Duration, Instant};

use echo_plant::{EchoPlant, remove_shm_files};

use nalgebra::Vector3;
use shearcut::closed_loop::LoopSetup;
use shearcut::closed_loop::{InProcessPlant, LoopEnd, PlantLink, TickTimes, run_loop};
use shearcut::commands::default_job::DEFAULT_JOB_SCENARIO;
use shearcut::controller_choice::ControllerChoice;
use shearcut::scenario::{ClockMode, Scenario};
use shearcut::transport::{
    Iceoryx2PlantLink, LinkTimeouts, LoopServices, PlantServerSettings, Role, WaitMode, serve_plant,
};
use shearcut_sim::arm::KnifeCommand;

fn prefix(tag: &str) -> String {
    format!("scb{}{tag}_", std::process::id())
}

/// Serves `make_plant()` on run `id` from a thread; returns the thread.
fn spawn_plant<P: PlantLink + 'static>(
    id: &'static str,
    prefix: String,
    wait: WaitMode,
    make_plant: impl FnOnce() -> P + Send + 'static,
) -> std::thread::JoinHandle<()> {
    std::thread::spawn(move || {
        let mut plant = make_plant();
        let services = LoopServices::open(Role::Plant, id, &prefix).expect("plant services");
        let mut settings = PlantServerSettings::new(ClockMode::Lockstep, 20);
        settings.wait = wait;
        serve_plant(&services, &mut plant, &settings).expect("plant serves");
    })
}

fn connect(id: &str, prefix: &str, wait: WaitMode, ticks: usize) -> Iceoryx2PlantLink {
    let services = LoopServices::open(Role::Controller, id, prefix).expect("controller services");
    let mut link = Iceoryx2PlantLink::new(services, 1e-3, LinkTimeouts::default(), wait, ticks + 2)
        .expect("link");
    link.wait_for_plant().expect("a plant");
    link
}

fn report(what: &str, t: &TickTimes, n: usize) {
    println!(
        "{what:<44} n = {n:>6}: median {:>8.2} us, p99 {:>8.2} us, max {:>10.2} us",
        t.median_us, t.p99_us, t.max_us
    );
}

fn echo(wait: WaitMode, ticks: usize) {
    let (id, tag) = match wait {
        WaitMode::BusyPoll => ("echo-busy", "b"),
        WaitMode::Blocking => ("echo-block", "w"),
    };
    let p = prefix(tag);
    let server = spawn_plant(id, p.clone(), wait, EchoPlant::new);
    let mut link = connect(id, &p, wait, ticks);
    let command = KnifeCommand {
        velocity: Vector3::new(0.0, -0.00625, 0.0047),
    };
    for _ in 0..ticks {
        link.exchange(&command).expect("echo answers");
    }
    link.finish().expect("echo ends");
    server.join().unwrap();
    report(&format!("echo plant, {wait:?}"), &link.round_trips(), ticks);
}

/// One closed loop of `scenario` under `choice` in lockstep, its plant
/// served over iceoryx2 from a second thread (`Some(wait)`) or called in
/// process (`None`); prints the round trips (iceoryx2) and the real-time
/// factor of the loop (plant and controller built before the clock starts).
fn closed_loop(scenario: &str, choice: &str, transport: Option<WaitMode>, tag: &str) {
    let s = Scenario::load(scenario).unwrap();
    let choice: ControllerChoice = choice.parse().unwrap();
    let setup = LoopSetup::new(&s, choice).unwrap();
    let period = setup.task.period;
    let plant = setup.plant(&s).unwrap();
    let cut = setup.cut(&s);
    let mut controller = setup.controller(&s, choice).unwrap();
    let what = format!(
        "{} {choice} lockstep, {}",
        s.name,
        transport.map_or("in process".to_string(), |w| format!("iceoryx2 {w:?}"))
    );
    let (out, wall) = match transport {
        None => {
            let mut link = InProcessPlant::new(plant, period);
            let started = Instant::now();
            let out = run_loop(&mut link, controller.as_mut(), &cut);
            (out, started.elapsed())
        }
        Some(wait) => {
            let p = prefix(tag);
            let server = spawn_plant("real", p.clone(), wait, move || {
                InProcessPlant::new(plant, period)
            });
            let max_ticks = (cut.max_duration / period) as usize;
            let mut link = connect("real", &p, wait, max_ticks);
            let started = Instant::now();
            let out = run_loop(&mut link, controller.as_mut(), &cut);
            let wall = started.elapsed();
            // A failed loop is reported below; its plant brakes by itself.
            if !matches!(out.end, LoopEnd::Failed(_)) {
                link.finish().expect("plant ends");
            }
            server.join().unwrap();
            report(&what, &link.round_trips(), out.ticks + 1);
            (out, wall)
        }
    };
    let simulated = out.ticks as f64 * period;
    println!(
        "{what:<44} end {:?}; {:.3} s simulated in {:.3} s wall: real-time factor {:.3} (simulated/wall)",
        out.end,
        simulated,
        wall.as_secs_f64(),
        simulated / wall.as_secs_f64().max(1e-9)
    );
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let ticks = args
        .iter()
        .position(|a| a == "--ticks")
        .and_then(|i| args.get(i + 1))
        .and_then(|v| v.parse().ok())
        .unwrap_or(100_000);
    // Give the other benches' processes a moment to leave the cores.
    std::thread::sleep(Duration::from_millis(100));
    echo(WaitMode::BusyPoll, ticks);
    echo(WaitMode::Blocking, ticks);
    closed_loop(
        "loop-potato-cuboid",
        "slice:0.75",
        Some(WaitMode::BusyPoll),
        "rb",
    );
    closed_loop(
        "loop-potato-cuboid",
        "slice:0.75",
        Some(WaitMode::Blocking),
        "rw",
    );
    if !args.iter().any(|a| a == "--skip-default") {
        // The main job's scenario (about a minute in all): in process, then
        // over iceoryx2 with blocking waits as `shearcut run` uses them.
        closed_loop(DEFAULT_JOB_SCENARIO, "mpc", None, "");
        closed_loop(DEFAULT_JOB_SCENARIO, "mpc", Some(WaitMode::Blocking), "dw");
        // The same cut on the reference discretisation, in process.
        closed_loop("loop-potato-whole", "mpc", None, "");
    }
    // Each prefix keeps a 16-byte management file by design: remove ours.
    remove_shm_files(&format!("scb{}", std::process::id()));
}
