//! The controller's iceoryx2 link against a plant served from a thread of
//! this process: answers are matched to their commands by sequence number,
//! a late answer to a command given up on is discarded, and the run still
//! ends cleanly; the end of the run is acknowledged even when the plant
//! leaves right after answering; a second plant for a served run is refused;
//! a realtime plant counts the answers it gave after its next tick was due.

#[path = "support/echo_plant.rs"]
mod echo_plant;

use std::time::Duration;

use echo_plant::{EchoPlant, remove_shm_files};
use nalgebra::Vector3;
use shearcut::closed_loop::{LinkAnswer, LinkError, PlantLink};
use shearcut::scenario::ClockMode;
use shearcut::transport::{
    Iceoryx2PlantLink, LinkTimeouts, LoopServices, PlantEnd, PlantReport, PlantServerSettings,
    Role, WaitMode, serve_plant,
};
use shearcut_sim::arm::KnifeCommand;

/// The echo plant, stalling `stall` on its command number `slow`.
struct Stalling {
    echo: EchoPlant,
    count: usize,
    slow: usize,
    stall: Duration,
}

impl PlantLink for Stalling {
    fn period(&self) -> f64 {
        self.echo.period()
    }

    fn exchange(&mut self, command: &KnifeCommand) -> Result<LinkAnswer, LinkError> {
        if self.count == self.slow {
            std::thread::sleep(self.stall);
        }
        self.count += 1;
        self.echo.exchange(command)
    }
}

/// Serves run `run` under `prefix` from a new thread with the echo plant
/// stalling `stall` on its command number `slow`.
fn serve_stalling(
    prefix: &str,
    run: &'static str,
    settings: PlantServerSettings,
    slow: usize,
    stall: Duration,
) -> std::thread::JoinHandle<PlantReport> {
    let prefix = prefix.to_string();
    std::thread::spawn(move || {
        let services = LoopServices::open(Role::Plant, run, &prefix).unwrap();
        let mut plant = Stalling {
            echo: EchoPlant::new(),
            count: 0,
            slow,
            stall,
        };
        serve_plant(&services, &mut plant, &settings).unwrap()
    })
}

#[test]
fn a_late_answer_is_discarded_and_the_run_still_ends_cleanly() {
    for wait in [WaitMode::Blocking, WaitMode::BusyPoll] {
        let prefix = format!("scl{}{wait:?}_", std::process::id());
        let mut settings = PlantServerSettings::new(ClockMode::Lockstep, 20);
        settings.wait = wait;
        let server = serve_stalling(&prefix, "late", settings, 2, Duration::from_millis(300));
        let services = LoopServices::open(Role::Controller, "late", &prefix).unwrap();
        let timeouts = LinkTimeouts {
            response: Duration::from_millis(50),
            check_every: Duration::from_millis(10),
            ..LinkTimeouts::default()
        };
        let mut link = Iceoryx2PlantLink::new(services, 1e-3, timeouts, wait, 16).unwrap();
        link.wait_for_plant().unwrap();
        let command = KnifeCommand {
            velocity: Vector3::new(0.0, -0.005, 0.004),
        };
        for tick in 1..=2 {
            let answer = link.exchange(&command).unwrap();
            let m = answer.reading;
            assert!((m.time - tick as f64 * 1e-3).abs() < 1e-12, "{wait:?}");
            assert_eq!(m.velocity, command.velocity);
            // The plant's truth crosses on its own board, for this tick.
            assert!(answer.truth.is_some(), "{wait:?}");
        }
        // Command 2 stalls past the response timeout.
        match link.exchange(&command) {
            Err(LinkError::Lost(why)) => assert!(
                why.contains("plant/late") && why.contains("did not answer command 2"),
                "{wait:?}: {why}"
            ),
            other => panic!("{wait:?}: {other:?}"),
        }
        // Let the late answer to command 2 arrive: it is not taken for the
        // answer to the end of the run (command 3).
        std::thread::sleep(Duration::from_millis(500));
        link.finish().unwrap();
        let report = server.join().unwrap();
        remove_shm_files(&prefix);
        assert_eq!(report.end, PlantEnd::Ended, "{wait:?}");
        assert_eq!(report.commands, 3, "{wait:?}");
    }
}

#[test]
fn a_realtime_plant_counts_its_own_overruns() {
    // A realtime plant whose fourth step takes 5 ms answers after its next
    // tick was due: one overrun at least (steps of the echo plant take
    // microseconds; a stalled machine could add more), none under the
    // lockstep clock, which has no ticks to overrun. A miss counted after
    // an overrun is one of the misses.
    for clock in [ClockMode::Realtime, ClockMode::Lockstep] {
        let prefix = format!("sco{}{clock:?}_", std::process::id());
        let settings = PlantServerSettings::new(clock, 1000);
        let server = serve_stalling(&prefix, "overrun", settings, 3, Duration::from_millis(5));
        let services = LoopServices::open(Role::Controller, "overrun", &prefix).unwrap();
        let mut link = Iceoryx2PlantLink::new(
            services,
            1e-3,
            LinkTimeouts::default(),
            WaitMode::Blocking,
            64,
        )
        .unwrap();
        link.wait_for_plant().unwrap();
        let command = KnifeCommand {
            velocity: Vector3::new(0.0, -0.005, 0.0),
        };
        for _ in 0..8 {
            link.exchange(&command).unwrap();
        }
        link.finish().unwrap();
        let report = server.join().unwrap();
        remove_shm_files(&prefix);
        assert_eq!(report.end, PlantEnd::Ended, "{clock:?}");
        match clock {
            ClockMode::Realtime => assert!(report.overruns >= 1, "{report:?}"),
            ClockMode::Lockstep => assert_eq!(report.overruns, 0, "{report:?}"),
        }
        assert!(
            report.missed_after_overrun <= report.missed_commands,
            "{report:?}"
        );
        assert!(report.overruns <= report.commands, "{report:?}");
    }
}

/// The plant exits as soon as it has acknowledged the end of the run. A
/// controller that looks at the plant's liveness between two reads of the
/// board may find it gone although its answer is there; the answer (with the
/// plant's final count of missed commands) must still be taken. Liveness is
/// checked on every wait here (`check_every` zero) to make that interleaving
/// likely; repeated because it is a race.
#[test]
fn the_end_of_the_run_is_acknowledged_even_when_the_plant_leaves_at_once() {
    for wait in [WaitMode::Blocking, WaitMode::BusyPoll] {
        for round in 0..10 {
            let prefix = format!("sce{}{wait:?}{round}_", std::process::id());
            let plant_prefix = prefix.clone();
            let server = std::thread::spawn(move || {
                let services = LoopServices::open(Role::Plant, "leave", &plant_prefix).unwrap();
                let mut settings = PlantServerSettings::new(ClockMode::Lockstep, 20);
                settings.wait = wait;
                let mut plant = EchoPlant::new();
                // The services (and the plant's node) are dropped on return.
                serve_plant(&services, &mut plant, &settings).unwrap()
            });
            let services = LoopServices::open(Role::Controller, "leave", &prefix).unwrap();
            let timeouts = LinkTimeouts {
                check_every: Duration::ZERO,
                ..LinkTimeouts::default()
            };
            let mut link = Iceoryx2PlantLink::new(services, 1e-3, timeouts, wait, 16).unwrap();
            link.wait_for_plant().unwrap();
            link.exchange(&KnifeCommand {
                velocity: Vector3::new(0.0, -0.005, 0.0),
            })
            .unwrap();
            let finished = link.finish();
            let report = server.join().unwrap();
            remove_shm_files(&prefix);
            assert!(finished.is_ok(), "{wait:?}, round {round}: {finished:?}");
            assert_eq!(report.end, PlantEnd::Ended, "{wait:?}");
            assert_eq!(link.missed_commands(), report.missed_commands);
        }
    }
}

#[test]
fn a_second_plant_for_the_same_run_is_refused() {
    let prefix = format!("scd{}_", std::process::id());
    let first = LoopServices::open(Role::Plant, "twice", &prefix).unwrap();
    let second = LoopServices::open(Role::Plant, "twice", &prefix);
    match second {
        Err(e) => assert!(
            e.to_string()
                .contains("run id \"twice\" is in use: a plant of it is running"),
            "{e}"
        ),
        Ok(_) => panic!("two plants serve run 'twice'"),
    }
    // The first still serves: a controller finds its board.
    let controller = LoopServices::open(Role::Controller, "twice", &prefix).unwrap();
    assert!(controller.open_peer_board().unwrap().is_some());
    drop((controller, first));
    remove_shm_files(&prefix);
}
