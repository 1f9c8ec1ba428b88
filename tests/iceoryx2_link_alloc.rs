//! A round trip over iceoryx2 (the controller's `exchange` and the plant
//! server's answer) allocates nothing after construction, on either side,
//! with busy polling and with blocking waits: the workspace's counting
//! allocator (its own test binary) counts every thread's allocations while
//! measuring, and the controller's thread's on their own; the plant is
//! served from a second thread of this process.

#[path = "../controllers/tests/support/counting_allocator.rs"]
mod counting_allocator;
#[path = "support/echo_plant.rs"]
mod echo_plant;

use std::sync::atomic::Ordering;
use std::time::Duration;

use counting_allocator::{ALLOCATIONS, Counting, TRACK_ALL, thread_allocations};
use echo_plant::{EchoPlant, remove_shm_files};
use nalgebra::Vector3;
use shearcut::closed_loop::PlantLink;
use shearcut::scenario::ClockMode;
use shearcut::transport::{
    Iceoryx2PlantLink, LinkTimeouts, LoopServices, PlantServerSettings, Role, WaitMode, serve_plant,
};
use shearcut_sim::arm::KnifeCommand;

#[global_allocator]
static GLOBAL: Counting = Counting;

const WARM_UP: usize = 500;
const MEASURED: usize = 5000;

/// Allocations (all threads, controller's thread) in `MEASURED` round trips
/// after `WARM_UP` ones.
fn measure(wait: WaitMode, tag: &str) -> (usize, usize) {
    let prefix = format!("sca{}{tag}_", std::process::id());
    let plant_prefix = prefix.clone();
    let server = std::thread::spawn(move || {
        let services = LoopServices::open(Role::Plant, "alloc", &plant_prefix).unwrap();
        let mut settings = PlantServerSettings::new(ClockMode::Lockstep, 20);
        settings.wait = wait;
        // A loaded machine's stall must not count as a missed command here.
        settings.lockstep_patience = Duration::from_secs(5);
        serve_plant(&services, &mut EchoPlant::new(), &settings).unwrap()
    });
    let services = LoopServices::open(Role::Controller, "alloc", &prefix).unwrap();
    // A round trip slower than `check_every` asks iceoryx2's node list
    // whether the plant died, and that allocates (about 1200 allocations a
    // call, measured); on this shared 2-core machine a scheduling stall can
    // exceed the default 5 ms, so the check interval is lengthened here:
    // the measured path is the answer arriving in time.
    let timeouts = LinkTimeouts {
        check_every: Duration::from_secs(2),
        ..LinkTimeouts::default()
    };
    let mut link =
        Iceoryx2PlantLink::new(services, 1e-3, timeouts, wait, WARM_UP + MEASURED + 2).unwrap();
    link.wait_for_plant().unwrap();
    let command = KnifeCommand {
        velocity: Vector3::new(0.0, -0.005, 0.004),
    };
    for _ in 0..WARM_UP {
        link.exchange(&command).unwrap();
    }
    ALLOCATIONS.store(0, Ordering::SeqCst);
    TRACK_ALL.store(true, Ordering::SeqCst);
    let controller_before = thread_allocations();
    let mut last_time = 0.0;
    for _ in 0..MEASURED {
        last_time = link.exchange(&command).unwrap().reading.time;
    }
    let controller_after = thread_allocations();
    TRACK_ALL.store(false, Ordering::SeqCst);
    let counts = (
        ALLOCATIONS.load(Ordering::SeqCst),
        controller_after - controller_before,
    );
    link.finish().unwrap();
    let report = server.join().unwrap();
    remove_shm_files(&prefix);
    // Lockstep: one step per command, answers matched to their commands.
    assert_eq!(report.commands, (WARM_UP + MEASURED) as u64);
    assert_eq!(report.missed_commands, 0);
    let expected = (WARM_UP + MEASURED) as f64 * EchoPlant::new().period();
    assert!(
        (last_time - expected).abs() < 1e-9,
        "{last_time} vs {expected}"
    );
    counts
}

#[test]
fn round_trips_allocate_nothing_after_construction() {
    for (wait, tag) in [(WaitMode::BusyPoll, "b"), (WaitMode::Blocking, "w")] {
        let (all, controller) = measure(wait, tag);
        assert_eq!(
            (all, controller),
            (0, 0),
            "{wait:?}: {all} allocations in {MEASURED} round trips, {controller} on the controller's side"
        );
    }
}
