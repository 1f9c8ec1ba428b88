//! The controller's end of the loop over iceoryx2: a [`PlantLink`] whose
//! plant runs in another process (`shearcut plant`, or an arm bridge).

use std::time::{Duration, Instant};

use iceoryx2::port::{listener::Listener, notifier::Notifier};
use iceoryx2::prelude::*;
use shearcut_sim::arm::KnifeCommand;

use super::board::{BoardReader, BoardWriter};
use super::loop_services::{LoopServices, PeerState, Role, node_name};
use super::peer_watch::gone_before_loop;
use super::wait_mode::WaitMode;
use super::wire::{WireCommand, WireError, WireMeasurement, WirePlantCounts, WireTruth};
use crate::closed_loop::{LinkAnswer, LinkError, PlantLink, TickTimes};

/// How long the controller waits for the plant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LinkTimeouts {
    /// Longest wait for a plant to serve the run before the first command.
    pub connect: Duration,
    /// Longest wait for the answer to one command.
    pub response: Duration,
    /// How often, while waiting, the plant's liveness (iceoryx2 dead-node
    /// detection) and termination requests are checked.
    pub check_every: Duration,
}

impl Default for LinkTimeouts {
    /// Connect 10 s, response 30 s (a lockstep plant may wait for a section
    /// build: far less than this, docs/benchmarks.md; a dead plant is still
    /// detected within a check), checks every 5 ms.
    fn default() -> Self {
        Self {
            connect: Duration::from_secs(10),
            response: Duration::from_secs(30),
            check_every: Duration::from_millis(5),
        }
    }
}

/// A plant in another process, reached over iceoryx2 shared memory: per
/// servo tick the controller writes one command to the run's command board
/// and waits until the measurement board holds the answer with the same
/// sequence number (older entries are the previous answer and are skipped).
/// After construction a round trip allocates nothing
/// (`tests/iceoryx2_link_alloc.rs`) as long as the answer comes within
/// [`LinkTimeouts::check_every`]; a longer wait asks iceoryx2's node list
/// whether the plant died, which allocates.
#[derive(Debug)]
pub struct Iceoryx2PlantLink {
    // Ports drop before the services (fields drop in order).
    commands: BoardWriter<WireCommand>,
    /// The plant's measurement board, once the plant serves the run.
    measurements: Option<BoardReader<WireMeasurement>>,
    /// The simulated plant's truth board, if it has one (an arm bridge
    /// does not): recorded, never given to the controller.
    truth: Option<BoardReader<WireTruth>>,
    /// The simulated plant's successor counts board, if it has one.
    counts: Option<BoardReader<WirePlantCounts>>,
    notifier: Notifier<ipc::Service>,
    listener: Listener<ipc::Service>,
    period: f64,
    sequence: u64,
    last_time: f64,
    timeouts: LinkTimeouts,
    wait: WaitMode,
    round_trips_us: Vec<f64>,
    missed_commands: u32,
    plant: String,
    /// When to look for a termination request next (they are also checked
    /// while a round trip waits).
    next_signal_check: Option<Instant>,
    services: LoopServices,
}

impl Iceoryx2PlantLink {
    /// The controller's ports on `services`, for a plant stepped every
    /// `period` seconds; room for `expected_ticks` latency records before
    /// the record grows.
    ///
    /// # Errors
    /// iceoryx2 refused to create a port.
    pub fn new(
        services: LoopServices,
        period: f64,
        timeouts: LinkTimeouts,
        wait: WaitMode,
        expected_ticks: usize,
    ) -> Result<Self, LinkError> {
        let lost = |what: &str, e: &dyn std::fmt::Debug| {
            LinkError::Lost(format!("cannot create the controller's {what}: {e:?}"))
        };
        let commands =
            BoardWriter::new(&services.own_board).map_err(|e| lost("command board writer", &e))?;
        let notifier = services
            .command_ready
            .notifier_builder()
            .create()
            .map_err(|e| lost("notifier", &e))?;
        let listener = services
            .measurement_ready
            .listener_builder()
            .create()
            .map_err(|e| lost("listener", &e))?;
        let plant = node_name(Role::Plant, &services.run_id);
        Ok(Self {
            commands,
            measurements: None,
            truth: None,
            counts: None,
            notifier,
            listener,
            period,
            sequence: 0,
            last_time: 0.0,
            timeouts,
            wait,
            round_trips_us: Vec::with_capacity(expected_ticks),
            missed_commands: 0,
            plant,
            next_signal_check: None,
            services,
        })
    }

    /// Waits until a plant serves the run (its measurement board exists)
    /// and opens its board. A plant that dies before it serves (its node
    /// dead), or whose node was seen and is gone (it ended while starting),
    /// is reported within a look of the services' peer watch
    /// ([`PEER_LOOK`](super::peer_watch::PEER_LOOK)), which ends here.
    ///
    /// # Errors
    /// No plant within the connect timeout, the plant ended before serving,
    /// a termination request, or iceoryx2 refused to open the plant's board.
    pub fn wait_for_plant(&mut self) -> Result<(), LinkError> {
        let waited = self.wait_for_board();
        self.services.stop_peer_watch();
        waited
    }

    /// [`Self::wait_for_plant`] but for the end of the peer watch.
    #[allow(clippy::disallowed_methods)] // Timeouts, not model time.
    fn wait_for_board(&mut self) -> Result<(), LinkError> {
        let started = Instant::now();
        loop {
            let board = self
                .services
                .open_peer_board()
                .map_err(|e| LinkError::Lost(format!("the plant '{}'s board: {e}", self.plant)))?;
            if let Some(board) = board {
                let lost = |e| LinkError::Lost(format!("the plant '{}'s board: {e}", self.plant));
                self.measurements = Some(BoardReader::new(board).map_err(lost)?);
                // A simulated plant creates its truth board before its
                // measurement board: it exists now, or never.
                if let Some(truth) = self.services.open_truth_board().map_err(lost)? {
                    self.truth = Some(BoardReader::new(truth).map_err(lost)?);
                }
                if let Some(counts) = self.services.open_counts_board().map_err(lost)? {
                    self.counts = Some(BoardReader::new(counts).map_err(lost)?);
                }
                return Ok(());
            }
            if let Some(signal) = self.services.termination_request(Duration::from_millis(1)) {
                return Err(LinkError::Stopped(signal));
            }
            // Dead nodes were cleaned when this process's node was created:
            // a dead plant node died since.
            let fate = self.services.peer_fate();
            if fate.is_gone() {
                return Err(LinkError::Lost(gone_before_loop(
                    Role::Plant,
                    &self.services.run_id,
                    fate,
                )));
            }
            if started.elapsed() > self.timeouts.connect {
                return Err(LinkError::Lost(format!(
                    "no plant or arm bridge served run '{}' within {:.1} s ([loop] connect_timeout)",
                    self.services.run_id,
                    self.timeouts.connect.as_secs_f64()
                )));
            }
        }
    }

    /// Wall-clock round trips (command sent → measurement received) so far.
    pub fn round_trips(&self) -> TickTimes {
        TickTimes::from_durations(&mut self.round_trips_us.clone())
    }

    /// Commands the plant reported missed (realtime clock) so far; after
    /// [`finish`](Self::finish), the plant's total.
    pub fn missed_commands(&self) -> u32 {
        self.missed_commands
    }

    /// The plant's node name (`plant/<run-id>`).
    pub fn plant_name(&self) -> &str {
        &self.plant
    }

    /// Tells the plant the run is over and waits for its acknowledgement.
    ///
    /// # Errors
    /// The plant did not acknowledge.
    pub fn finish(&mut self) -> Result<(), LinkError> {
        let command = WireCommand::end_of_run(self.sequence, self.last_time);
        let answer = self.round_trip(command)?;
        // The plant's final count, misses after the last command included.
        self.missed_commands = answer.missed_commands;
        match answer.reading() {
            Err(WireError::Ended) => Ok(()),
            other => Err(LinkError::Lost(format!(
                "the plant '{}' did not acknowledge the end of the run: {other:?}",
                self.plant
            ))),
        }
    }

    /// Why the plant has not answered, if it is gone.
    fn check_plant(&self) -> Result<(), LinkError> {
        if let Some(signal) = self.services.termination_request(Duration::ZERO) {
            return Err(LinkError::Stopped(signal));
        }
        let state = self.services.peer_state(Role::Plant);
        // The run's supervisor stops the controller before the plant, but a
        // Ctrl-C in a terminal signals the whole process group at once, and
        // the plant may leave before the controller's handler has run: give
        // the signal a moment before calling the plant lost.
        if state != PeerState::Alive
            && let Some(signal) = self.services.termination_request(TERMINATION_GRACE)
        {
            return Err(LinkError::Stopped(signal));
        }
        match state {
            PeerState::Alive => Ok(()),
            PeerState::Dead => Err(LinkError::Lost(format!(
                "the plant '{}' died (iceoryx2 dead-node detection)",
                self.plant
            ))),
            PeerState::Absent => Err(LinkError::Lost(format!(
                "the plant '{}' is gone",
                self.plant
            ))),
        }
    }

    /// Sends `command` and waits for its answer.
    #[allow(clippy::disallowed_methods)] // Deadlines and latency statistics, not model time.
    fn round_trip(&mut self, command: WireCommand) -> Result<WireMeasurement, LinkError> {
        let started = Instant::now();
        // SIGINT/SIGTERM between fast round trips: look every `check_every`.
        if self.next_signal_check.is_none_or(|t| started >= t) {
            if let Some(signal) = self.services.termination_request(Duration::ZERO) {
                return Err(LinkError::Stopped(signal));
            }
            self.next_signal_check = Some(started + self.timeouts.check_every);
        }
        let Some(measurements) = &self.measurements else {
            return Err(LinkError::Lost(format!(
                "not connected to the plant '{}' (wait_for_plant first)",
                self.plant
            )));
        };
        self.commands.publish(command);
        // Every command sent takes a new number, answered or not: a late
        // answer to a command given up on never passes for the next one's.
        self.sequence = command.sequence.wrapping_add(1);
        if self.wait == WaitMode::Blocking {
            let _ = self.notifier.notify();
        }
        let mut next_check = self.timeouts.check_every;
        let mut spins = 0u32;
        // Set when the plant was found gone; the board is read once more
        // before giving up, since a plant answers before it leaves (it exits
        // right after acknowledging the end of the run) and may have done so
        // since the last read.
        let mut lost = None;
        loop {
            // The entry holds the previous answer until the plant writes
            // this command's.
            let m = measurements.latest();
            if m.sequence == command.sequence {
                self.round_trips_us
                    .push(started.elapsed().as_secs_f64() * 1e6);
                return Ok(m);
            }
            if let Some(lost) = lost {
                return Err(lost);
            }
            match self.wait {
                WaitMode::Blocking => {
                    let slice = next_check.saturating_sub(started.elapsed());
                    let _ = self.listener.timed_wait(|_| {}, slice);
                }
                WaitMode::BusyPoll => {
                    spins = spins.wrapping_add(1);
                    if !spins.is_multiple_of(1024) {
                        std::hint::spin_loop();
                        continue;
                    }
                }
            }
            let elapsed = started.elapsed();
            if elapsed >= next_check {
                if let Err(e) = self.check_plant() {
                    lost = Some(e);
                    continue;
                }
                next_check = elapsed + self.timeouts.check_every;
                if elapsed > self.timeouts.response {
                    return Err(LinkError::Lost(format!(
                        "the plant '{}' did not answer command {} within {:?}",
                        self.plant, command.sequence, self.timeouts.response
                    )));
                }
            }
        }
    }
}

/// How long a controller that finds the plant gone waits for a termination
/// request before reporting the plant lost.
const TERMINATION_GRACE: Duration = Duration::from_millis(50);

impl PlantLink for Iceoryx2PlantLink {
    fn period(&self) -> f64 {
        self.period
    }

    fn exchange(&mut self, command: &KnifeCommand) -> Result<LinkAnswer, LinkError> {
        let wire = WireCommand::new(self.sequence, self.last_time, command);
        let answer = self.round_trip(wire)?;
        self.missed_commands = answer.missed_commands;
        let reading = answer.reading().map_err(|e| match e {
            WireError::ModelFailed => LinkError::Model(format!("in the plant '{}'", self.plant)),
            e => LinkError::Lost(format!("the plant '{}': {e}", self.plant)),
        })?;
        self.last_time = reading.time;
        // The plant writes the tick's truth before its measurement.
        let truth = self
            .truth
            .as_ref()
            .map(BoardReader::latest)
            .filter(|t| t.sequence == answer.sequence)
            .map(|t| t.truth());
        Ok(LinkAnswer { reading, truth })
    }

    fn successor_counts(&self) -> Option<WirePlantCounts> {
        self.counts.as_ref().map(BoardReader::latest)
    }
}
