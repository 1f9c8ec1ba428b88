//! The plant's end of the loop over iceoryx2: owns the plant, answers each
//! command with one measurement, and behaves like an arm's servo loop:
//! lockstep (one step per command) or realtime (paced by the wall clock,
//! missed commands counted), braking after too many consecutive missed
//! commands.

use std::time::{Duration, Instant};

use iceoryx2::prelude::*;
use serde::Serialize;
use shearcut_sim::arm::{ArmReading, KnifeCommand};

use super::board::{BoardReader, BoardWriter};
use super::loop_services::{LoopServices, ServiceError};
use super::peer_watch::{ENDED_PEER_SIGNAL_WAIT, PeerFate};
use super::termination_watch::StopSignal;
use super::wait_mode::WaitMode;
use super::wire::{
    NO_SEQUENCE, WireCommand, WireFault, WireMeasurement, WirePlantCounts, WireStatus, WireTruth,
};
use crate::closed_loop::PlantLink;
use crate::scenario::ClockMode;

/// How the plant serves.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlantServerSettings {
    /// Lockstep or realtime.
    pub clock: ClockMode,
    /// Consecutive missed commands after which the plant brakes.
    pub missed_command_limit: u32,
    /// Lockstep only: a command counts as missed after this much silence
    /// (default 100 ms: the default limit of 20 brakes after 2 s, so a
    /// controller's slow tick on a loaded machine does not brake a
    /// simulation). Realtime misses are ticks without a command.
    pub lockstep_patience: Duration,
    /// Longest wait for the first command.
    pub connect_timeout: Duration,
    /// How to wait for commands.
    pub wait: WaitMode,
}

impl PlantServerSettings {
    /// The settings for `clock` and `missed_command_limit`, with the default
    /// patience (100 ms), connect timeout (30 s) and blocking waits.
    pub fn new(clock: ClockMode, missed_command_limit: u32) -> Self {
        Self {
            clock,
            missed_command_limit,
            lockstep_patience: Duration::from_millis(100),
            connect_timeout: Duration::from_secs(30),
            wait: WaitMode::Blocking,
        }
    }
}

/// Why the plant stopped serving.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum PlantEnd {
    /// The controller ended the run.
    Ended,
    /// Braked after this many consecutive missed commands.
    Braked(u32),
    /// The plant's model failed.
    ModelFailed(String),
    /// No controller sent a first command in time.
    NoController,
    /// The run's controller died before its first command (its iceoryx2
    /// node dead).
    ControllerDied,
    /// The run's controller, seen alive, ended before its first command
    /// (its iceoryx2 node gone).
    ControllerEnded,
    /// The run's controller died after its first command (its iceoryx2
    /// node dead at a look: lockstep, after a missed command; realtime,
    /// once the plant braked at its missed-command limit); the plant
    /// braked.
    ControllerDiedInLoop,
    /// The run's controller ended after its first command without ending
    /// the run (its iceoryx2 node gone at a look, as for
    /// [`PlantEnd::ControllerDiedInLoop`]); the plant braked.
    ControllerEndedInLoop,
    /// SIGINT or SIGTERM.
    Terminated(StopSignal),
}

/// What a plant's serving produced.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PlantReport {
    /// Why it stopped.
    pub end: PlantEnd,
    /// Commands answered.
    pub commands: u64,
    /// Ticks the plant advanced (commands answered plus realtime ticks
    /// stepped without a command, plus the braking step).
    pub steps: u64,
    /// Commands missed in total.
    pub missed_commands: u32,
    /// Longest run of consecutive missed commands.
    pub max_consecutive_missed: u32,
    /// Realtime: answers whose step and settling ended after the next tick
    /// was due (the plant itself late, whatever the controller did).
    pub overruns: u64,
    /// Realtime: missed commands at the tick right after an overrun (the
    /// controller had less than its period between the late answer and
    /// the tick).
    pub missed_after_overrun: u32,
}

fn iceoryx(context: &str, e: impl std::fmt::Debug) -> ServiceError {
    ServiceError::Iceoryx(format!("{context}: {e:?}"))
}

/// The plant's end of the boards: the controller's command board (opened
/// once the controller created it), its own measurement board and its
/// truth board.
struct PlantPorts<'a> {
    services: &'a LoopServices,
    commands: Option<BoardReader<WireCommand>>,
    measurements: BoardWriter<WireMeasurement>,
    truth: Option<BoardWriter<WireTruth>>,
    counts: Option<BoardWriter<WirePlantCounts>>,
    notifier: iceoryx2::port::notifier::Notifier<ipc::Service>,
    wait: WaitMode,
    /// The sequence number of the last command answered.
    answered: Option<u64>,
}

impl PlantPorts<'_> {
    /// A command not answered yet, if the controller wrote one.
    fn poll(&mut self) -> Result<Option<WireCommand>, ServiceError> {
        if self.commands.is_none() {
            match self.services.open_peer_board()? {
                Some(board) => self.commands = Some(BoardReader::new(board)?),
                None => return Ok(None),
            }
        }
        Ok(self.commands.as_ref().and_then(|board| {
            let c = board.latest();
            (c.sequence != NO_SEQUENCE && Some(c.sequence) != self.answered).then_some(c)
        }))
    }

    /// Writes the truth of the tick answering command `sequence`; before
    /// its measurement, so that a controller process that reads the
    /// measurement finds the truth beside it.
    fn record(&mut self, sequence: u64, truth: &shearcut_plant::PlantTruth) {
        if let Some(board) = &self.truth {
            board.publish(WireTruth::new(sequence, truth));
        }
    }

    /// Writes the plant's successor counts (if it has them) and `w` (the
    /// answer to command `w.sequence`), and wakes the controller.
    fn answer(&mut self, w: WireMeasurement, counts: Option<WirePlantCounts>) {
        if let (Some(board), Some(counts)) = (&self.counts, counts) {
            board.publish(counts);
        }
        self.measurements.publish(w);
        self.answered = Some(w.sequence);
        if self.wait == WaitMode::Blocking {
            let _ = self.notifier.notify();
        }
    }
}

/// Serves `plant` (any [`PlantLink`], e.g. an
/// [`InProcessPlant`](crate::closed_loop::InProcessPlant)) on `services`
/// until the controller ends the run, the plant brakes or fails, the
/// controller is gone before its first command ([`PlantEnd::ControllerDied`],
/// [`PlantEnd::ControllerEnded`]: seen by the services' peer watch within a
/// look) or after it ([`PlantEnd::ControllerDiedInLoop`],
/// [`PlantEnd::ControllerEndedInLoop`]: lockstep, a look at each missed
/// command; realtime, one look once braked at the missed-command limit, so
/// that no look falls on a tick; either, one look at the first command if
/// the peer watch never saw the controller alive, so that its node is
/// known), or a termination request arrives.
///
/// Lockstep: each command is stepped as soon as it arrives; silence longer
/// than the patience counts as a missed command. Realtime: the plant steps
/// every period by the wall clock with the command that arrived since the
/// last tick, or, missing one, with the last command (the arm keeps its
/// motion). After `missed_command_limit` consecutive misses the plant
/// commands zero velocity (the arm-limit monitor holds the knife if that
/// stop is too abrupt), answers the next command number in advance with
/// [`WireStatus::Braked`], and stops (realtime: then looks once at the
/// controller's node, and a dead or gone one is the end's cause).
///
/// Each answer goes out as soon as the plant's measurement is known; the
/// plant's work after it ([`PlantLink::settle`]) follows, before the next
/// command is looked for.
///
/// Answering a command allocates nothing after the ports are built (the
/// plant's own step aside; the look at the first command, if any,
/// allocates).
///
/// # Errors
/// iceoryx2 refused to create or open a port.
#[allow(clippy::disallowed_methods)] // Pacing and deadlines, not model time.
pub fn serve_plant(
    services: &LoopServices,
    plant: &mut dyn PlantLink,
    settings: &PlantServerSettings,
) -> Result<PlantReport, ServiceError> {
    let listener = services
        .command_ready
        .listener_builder()
        .create()
        .map_err(|e| iceoryx("listener", e))?;
    let mut ports = PlantPorts {
        services,
        commands: None,
        measurements: BoardWriter::new(&services.own_board)?,
        truth: match &services.truth_board {
            Some(board) => Some(BoardWriter::new(board)?),
            None => None,
        },
        counts: match &services.counts_board {
            Some(board) => Some(BoardWriter::new(board)?),
            None => None,
        },
        notifier: services
            .measurement_ready
            .notifier_builder()
            .create()
            .map_err(|e| iceoryx("notifier", e))?,
        wait: settings.wait,
        answered: None,
    };
    let period = plant.period();
    let realtime = settings.clock == ClockMode::Realtime;
    let window = if realtime {
        Duration::from_secs_f64(period)
    } else {
        settings.lockstep_patience
    };
    let mut report = PlantReport {
        end: PlantEnd::NoController,
        commands: 0,
        steps: 0,
        missed_commands: 0,
        max_consecutive_missed: 0,
        overruns: 0,
        missed_after_overrun: 0,
    };
    // Whether the last answer's step and settling ended after the next
    // tick was due (realtime).
    let mut overran = false;
    let mut consecutive = 0u32;
    let mut last_command = KnifeCommand::default();
    let mut last: Option<ArmReading> = None;
    let started = Instant::now();
    // Start of the current window: the last command (lockstep) or the next
    // tick (realtime); None until the first command.
    let mut window_start: Option<Instant> = None;
    let mut signals = SignalCheck::new();
    // A failure of the plant's work after its last answer
    // ([`PlantLink::settle`]), reported at the next exchange.
    let mut unsettled = None;
    loop {
        if realtime && let Some(tick) = window_start {
            // Sleep to the tick, looking for SIGINT/SIGTERM meanwhile.
            let now = Instant::now();
            if tick > now
                && let Some(signal) = services.termination_request(tick - now)
            {
                report.end = PlantEnd::Terminated(signal);
                return Ok(report);
            }
        }
        if let Some(command) = ports.poll()? {
            // The loop starts: the controller is there. The plant looks at
            // it again at a missed command (lockstep) or once braked
            // (realtime), from the node the watch saw; if the watch saw
            // none, one look now finds it alive: lockstep before the first
            // answer, realtime after it (off the answer's path; a
            // controller that dies between its first answer and that look
            // is then reported only as a braked plant).
            let look_now = window_start.is_none() && {
                services.stop_peer_watch();
                matches!(
                    services.peer_fate(),
                    PeerFate::NotSeen | PeerFate::DiedUnseen
                )
            };
            if look_now && !realtime {
                services.look_at_peer();
            }
            let look_after_answer = look_now && realtime;
            consecutive = 0;
            if command.is_end_of_run() {
                let m = last.unwrap_or_else(rest_measurement);
                ports.answer(
                    WireMeasurement::new(command.sequence, &m, report.missed_commands).stopped(
                        WireStatus::Ended,
                        WireFault::None,
                        0.0,
                    ),
                    plant.successor_counts(),
                );
                report.end = PlantEnd::Ended;
                return Ok(report);
            }
            last_command = command.knife_command();
            match unsettled
                .take()
                .map_or_else(|| plant.exchange(&last_command), Err)
            {
                Ok(answer) => {
                    if let Some(truth) = &answer.truth {
                        ports.record(command.sequence, truth);
                    }
                    ports.answer(
                        WireMeasurement::new(
                            command.sequence,
                            &answer.reading,
                            report.missed_commands,
                        ),
                        plant.successor_counts(),
                    );
                    last = Some(answer.reading);
                    // After the answer, in the time before the next tick.
                    unsettled = plant.settle().err();
                    if look_after_answer {
                        // Once, before the first tick's window is set (the
                        // window starts after it: no miss).
                        services.look_at_peer();
                    }
                }
                Err(e) => {
                    let m = last.unwrap_or_else(rest_measurement);
                    ports.answer(
                        WireMeasurement::new(command.sequence, &m, report.missed_commands).stopped(
                            WireStatus::ModelFailed,
                            WireFault::None,
                            0.0,
                        ),
                        plant.successor_counts(),
                    );
                    report.end = PlantEnd::ModelFailed(e.to_string());
                    return Ok(report);
                }
            }
            report.commands += 1;
            report.steps += 1;
            let next = match window_start {
                Some(t) if realtime => t + window,
                _ => Instant::now() + if realtime { window } else { Duration::ZERO },
            };
            overran = realtime && Instant::now() > next;
            report.overruns += u64::from(overran);
            window_start = Some(next);
            continue;
        }
        // No command waiting.
        let now = Instant::now();
        let Some(start) = window_start else {
            // Before the first command: wait for a controller, and see it go.
            match services.peer_fate() {
                PeerFate::Died => {
                    report.end = PlantEnd::ControllerDied;
                    return Ok(report);
                }
                PeerFate::Ended => {
                    report.end = match services.termination_request(ENDED_PEER_SIGNAL_WAIT) {
                        Some(signal) => PlantEnd::Terminated(signal),
                        None => PlantEnd::ControllerEnded,
                    };
                    return Ok(report);
                }
                PeerFate::NotSeen | PeerFate::Alive | PeerFate::DiedUnseen => {}
            }
            if now - started > settings.connect_timeout {
                report.end = PlantEnd::NoController;
                return Ok(report);
            }
            if let Some(signal) = listen(
                services,
                &listener,
                settings.wait,
                Duration::from_millis(5),
                &mut signals,
            ) {
                report.end = PlantEnd::Terminated(signal);
                return Ok(report);
            }
            continue;
        };
        let missed = if realtime {
            // At the tick without a command: the arm keeps its last command.
            true
        } else {
            let due = start + window;
            if now < due {
                if let Some(signal) =
                    listen(services, &listener, settings.wait, due - now, &mut signals)
                {
                    report.end = PlantEnd::Terminated(signal);
                    return Ok(report);
                }
                false
            } else {
                true
            }
        };
        if !missed {
            continue;
        }
        consecutive += 1;
        report.missed_commands += 1;
        report.missed_after_overrun += u32::from(std::mem::take(&mut overran));
        report.max_consecutive_missed = report.max_consecutive_missed.max(consecutive);
        window_start = Some(start + window);
        if !realtime {
            // Silence in lockstep: is the controller still there? (The
            // look allocates; a missed command is off the answering path.)
            let fate = services.look_at_peer();
            if fate.is_gone() {
                brake(plant, &mut report, &mut last);
                report.end = if fate == PeerFate::Died {
                    PlantEnd::ControllerDiedInLoop
                } else {
                    PlantEnd::ControllerEndedInLoop
                };
                return Ok(report);
            }
        }
        if consecutive >= settings.missed_command_limit {
            brake(plant, &mut report, &mut last);
            report.end = PlantEnd::Braked(consecutive);
            let m = last.unwrap_or_else(rest_measurement);
            // The answer a late controller's next command finds (the entry
            // stays readable after this process exits while the controller
            // holds the board open).
            let next = ports.answered.map_or(0, |s| s.wrapping_add(1));
            ports.answer(
                WireMeasurement::new(next, &m, report.missed_commands).stopped(
                    WireStatus::Braked,
                    WireFault::MissedCommands,
                    f64::from(consecutive),
                ),
                plant.successor_counts(),
            );
            if realtime {
                // Braked and answered: one look at the controller's node
                // (it allocates; the plant steps no more) tells a dead
                // controller from a slow one.
                report.end = match services.look_at_peer() {
                    PeerFate::Died => PlantEnd::ControllerDiedInLoop,
                    PeerFate::Ended => PlantEnd::ControllerEndedInLoop,
                    _ => PlantEnd::Braked(consecutive),
                };
            }
            return Ok(report);
        }
        if realtime {
            match unsettled
                .take()
                .map_or_else(|| plant.exchange(&last_command), Err)
            {
                Ok(answer) => {
                    last = Some(answer.reading);
                    unsettled = plant.settle().err();
                }
                Err(e) => {
                    report.end = PlantEnd::ModelFailed(e.to_string());
                    return Ok(report);
                }
            }
            report.steps += 1;
        }
    }
}

/// Looks for termination requests at most every 5 ms (the look is a
/// system call).
struct SignalCheck {
    next: Instant,
}

impl SignalCheck {
    #[allow(clippy::disallowed_methods)] // Pacing of a check, not model time.
    fn new() -> Self {
        Self {
            next: Instant::now(),
        }
    }

    /// The termination request that arrived, if any (looked at if due).
    #[allow(clippy::disallowed_methods)] // Pacing of a check, not model time.
    fn terminated(&mut self, services: &LoopServices) -> Option<StopSignal> {
        let now = Instant::now();
        if now < self.next {
            return None;
        }
        self.next = now + Duration::from_millis(5);
        services.termination_request(Duration::ZERO)
    }
}

/// Waits for a command notification up to `timeout` (or spins once); the
/// termination request that arrived, if any.
fn listen(
    services: &LoopServices,
    listener: &iceoryx2::port::listener::Listener<ipc::Service>,
    wait: WaitMode,
    timeout: Duration,
    signals: &mut SignalCheck,
) -> Option<StopSignal> {
    match wait {
        WaitMode::Blocking => {
            let _ = listener.timed_wait(|_| {}, timeout);
        }
        WaitMode::BusyPoll => std::hint::spin_loop(),
    }
    signals.terminated(services)
}

/// Commands zero velocity; a refused (too abrupt) stop holds the knife.
fn brake(plant: &mut dyn PlantLink, report: &mut PlantReport, last: &mut Option<ArmReading>) {
    if let Ok(answer) = plant.exchange(&KnifeCommand::default()) {
        *last = Some(answer.reading);
        report.steps += 1;
    }
}

/// The reading of a plant that has not stepped yet.
fn rest_measurement() -> ArmReading {
    ArmReading::at_rest(0.0, nalgebra::Vector3::zeros())
}
