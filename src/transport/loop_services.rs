//! The iceoryx2 services of one run: two one-entry blackboards carrying the
//! latest command and measurement, and two event services waking the side
//! that waits (`shearcut/<run-id>/command`, `…/measurement`,
//! `…/command-ready`, `…/measurement-ready`). Each board is created by its
//! writer (the controller creates the command board, the plant the
//! measurement board) and opened by the other side once it exists. A
//! simulated plant also writes its ground truth on a third board
//! (`…/truth`), which the controller process may record but never passes
//! to a controller; an arm bridge does not create it. The simulated plant
//! also writes its successor counts (`…/plant-counts`,
//! [`WirePlantCounts`]) for the controller's `loop_stats.json`. All live
//! under one iceoryx2 prefix (default [`DEFAULT_PREFIX`], or the
//! environment's [`PREFIX_ENV`]): the next node created under the prefix
//! cleans what killed processes left behind, and the run id in the names
//! keeps concurrent runs apart.

use std::time::Duration;

use iceoryx2::prelude::*;
use iceoryx2::service::builder::blackboard::{BlackboardCreateError, BlackboardOpenError};
use iceoryx2::service::port_factory::event;

use super::board::{Board, ENTRY_KEY};
use super::peer_watch::{PEER_LOOK, PeerFate, PeerWatch, gone_before_loop};
use super::run_node::{RunNode, node_state};
use super::termination_watch::{StopSignal, TerminationWatch};
use super::wire::{WireCommand, WireMeasurement, WirePlantCounts, WireTruth};

/// The iceoryx2 prefix of every shearcut run (files under `/dev/shm` and
/// `/tmp/iceoryx2` start with it).
pub const DEFAULT_PREFIX: &str = "shearcut_";

/// Environment variable overriding [`DEFAULT_PREFIX`] (tests isolate
/// themselves with a unique one).
pub const PREFIX_ENV: &str = "SHEARCUT_IPC_PREFIX";

/// Why the services could not be set up.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ServiceError {
    /// The run id is not usable in service and node names.
    #[error(
        "run id {0:?} is not allowed: use 1 to 64 characters among letters, digits, '-', '_' and '.'"
    )]
    RunId(String),
    /// The prefix is not a valid file name start.
    #[error(
        "iceoryx2 prefix {0:?} (from {PREFIX_ENV} or the default) is not allowed: use 1 to 32 characters among letters, digits, '-', '_' and '.'"
    )]
    Prefix(String),
    /// A live process of the same role already serves the run id.
    #[error(
        "run id {run_id:?} is in use: a {} of it is running (iceoryx2 node {}/{run_id})",
        role.as_str(),
        role.as_str()
    )]
    RunIdInUse {
        /// The run id.
        run_id: String,
        /// The role of the process that serves it.
        role: Role,
    },
    /// iceoryx2 refused.
    #[error("iceoryx2: {0}")]
    Iceoryx(String),
    /// SIGINT or SIGTERM arrived while the services were being set up.
    #[error("stopped by {0} while starting")]
    Stopped(StopSignal),
    /// The other side died or ended before the services were set up (a
    /// service it was creating may be left half made): the line of
    /// [`gone_before_loop`].
    #[error("lost the {}: {line}", peer.as_str())]
    PeerGone {
        /// The other side's role.
        peer: Role,
        /// How it went, on one line.
        line: String,
    },
}

fn iceoryx(context: &str, e: impl std::fmt::Debug) -> ServiceError {
    ServiceError::Iceoryx(format!("{context}: {e:?}"))
}

pub(super) fn is_name(s: &str, max: usize) -> bool {
    !s.is_empty()
        && s.len() <= max
        && s.chars()
            .all(|c| c.is_ascii_alphanumeric() || matches!(c, '-' | '_' | '.'))
}

/// Which side of the loop a process is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Role {
    /// The plant (or an arm bridge): answers commands.
    Plant,
    /// The controller: sends commands.
    Controller,
}

impl Role {
    /// `plant` or `controller`.
    pub fn as_str(self) -> &'static str {
        match self {
            Role::Plant => "plant",
            Role::Controller => "controller",
        }
    }

    /// The other side.
    pub fn peer(self) -> Role {
        match self {
            Role::Plant => Role::Controller,
            Role::Controller => Role::Plant,
        }
    }
}

/// The board `role` writes: `command` (controller) or `measurement` (plant).
fn board_name(role: Role) -> &'static str {
    match role {
        Role::Controller => "command",
        Role::Plant => "measurement",
    }
}

/// The simulated plant's truth board.
const TRUTH_BOARD: &str = "truth";

/// The simulated plant's successor counts board.
const COUNTS_BOARD: &str = "plant-counts";

/// Creates `role`'s board `name` holding `empty` (its `what`: `command`,
/// `measurement`, `truth` or `plant-counts`). A board left by a killed
/// process of an earlier run under the same run id is being removed by the
/// dead-node cleanup: retry for up to a second, looking at `watch` between
/// tries.
///
/// # Errors
/// The board stays taken; iceoryx2 refused; SIGINT or SIGTERM arrived
/// ([`ServiceError::Stopped`]).
fn create_board<T: Copy + ZeroCopySend + std::fmt::Debug + 'static>(
    node: &Node<ipc::Service>,
    watch: &TerminationWatch,
    name: &ServiceName,
    role: Role,
    what: &str,
    empty: T,
) -> Result<Board, ServiceError> {
    let mut last = None;
    for _ in 0..100 {
        let builder = node
            .service_builder(name)
            .blackboard_creator::<u64>()
            .add::<T>(ENTRY_KEY, empty);
        match builder.create() {
            Ok(board) => return Ok(board),
            Err(
                e @ (BlackboardCreateError::AlreadyExists
                | BlackboardCreateError::IsBeingCreatedByAnotherInstance),
            ) => {
                last = Some(e);
                let _ = node.try_cleanup_dead_nodes();
                if let Some(signal) = watch.requested_within(Duration::from_millis(10)) {
                    return Err(ServiceError::Stopped(signal));
                }
            }
            Err(e) => return Err(iceoryx(&format!("{what} board"), e)),
        }
    }
    Err(ServiceError::Iceoryx(format!(
        "{what} board '{}': {last:?} (is another {} serving this run id?)",
        name.as_str(),
        role.as_str()
    )))
}

/// The node name of `role` in run `run_id` (`plant/<run-id>`).
pub fn node_name(role: Role, run_id: &str) -> String {
    format!("{}/{run_id}", role.as_str())
}

/// The prefix in force: the environment's [`PREFIX_ENV`] or [`DEFAULT_PREFIX`].
pub fn prefix() -> String {
    std::env::var(PREFIX_ENV).unwrap_or_else(|_| DEFAULT_PREFIX.to_string())
}

/// The iceoryx2 configuration of `prefix`: the defaults, with iceoryx2's
/// cleanups of dead nodes on a node's creation and a service's opening
/// off ([`RunNode::create`] cleans, and sees which peer it removed).
///
/// # Errors
/// The prefix is not allowed.
pub fn config(prefix: &str) -> Result<Config, ServiceError> {
    if !is_name(prefix, 32) {
        return Err(ServiceError::Prefix(prefix.to_string()));
    }
    let mut cfg = Config::default();
    cfg.global.prefix =
        FileName::new(prefix.as_bytes()).map_err(|_| ServiceError::Prefix(prefix.to_string()))?;
    cfg.global.node.cleanup_dead_nodes_on_creation = false;
    cfg.global.service.cleanup_dead_nodes_on_open = false;
    Ok(cfg)
}

/// One process's node and the run's services.
#[derive(Debug)]
pub struct LoopServices {
    /// The process's node (`plant/<run-id>` or `controller/<run-id>`).
    pub node: Node<ipc::Service>,
    /// The board this role writes, created by it: the command board
    /// (controller) or the measurement board (plant).
    pub own_board: Board,
    /// The simulated plant's truth board, created by the plant (`None` for
    /// the controller).
    pub truth_board: Option<Board>,
    /// The simulated plant's successor counts board, created by the plant
    /// (`None` for the controller).
    pub counts_board: Option<Board>,
    /// Notifications "a command is waiting" (controller → plant).
    pub command_ready: event::PortFactory<ipc::Service>,
    /// Notifications "a measurement is waiting" (plant → controller).
    pub measurement_ready: event::PortFactory<ipc::Service>,
    /// The run id.
    pub run_id: String,
    /// The configuration (prefix) in force.
    pub config: Config,
    /// This process's role.
    pub role: Role,
    /// SIGINT/SIGTERM, watched from before the node's creation.
    watch: TerminationWatch,
    /// The other role's node, watched until the loop starts.
    peer: PeerWatch,
}

impl LoopServices {
    /// Creates `role`'s node for run `run_id` under `prefix` (cleaning the
    /// resources of dead nodes under that prefix) and opens or creates the
    /// run's services: [`RunNode::create`], then [`LoopServices::on`].
    ///
    /// # Errors
    /// The run id or prefix is not allowed, the run id is in use, or
    /// iceoryx2 refused.
    pub fn open(role: Role, run_id: &str, prefix: &str) -> Result<Self, ServiceError> {
        Self::on(RunNode::create(role, run_id, prefix)?)
    }

    /// Opens or creates the run's services on `node`, the process's node
    /// created earlier.
    ///
    /// # Errors
    /// The other side is gone ([`ServiceError::PeerGone`]: found before, or
    /// within two looks of its watch after a step failed); iceoryx2 refused
    /// (or another process of this role serves the run: its board exists);
    /// a signal arrived.
    pub fn on(node: RunNode) -> Result<Self, ServiceError> {
        let gone = |fate: PeerFate| ServiceError::PeerGone {
            peer: node.role.peer(),
            line: gone_before_loop(node.role.peer(), &node.run_id, fate),
        };
        let fate = node.peer.fate();
        if fate.is_gone() {
            return Err(gone(fate));
        }
        let made = match RunServices::create(&node) {
            Ok(made) => made,
            Err(e @ ServiceError::Stopped(_)) => return Err(e),
            Err(e) => {
                return Err(match node.peer.gone_within(2 * PEER_LOOK) {
                    Some(fate) => gone(fate),
                    None => e,
                });
            }
        };
        let RunNode {
            node,
            run_id,
            config,
            role,
            watch,
            peer,
        } = node;
        Ok(Self {
            node,
            own_board: made.own_board,
            truth_board: made.truth_board,
            counts_board: made.counts_board,
            command_ready: made.command_ready,
            measurement_ready: made.measurement_ready,
            run_id,
            config,
            role,
            watch,
            peer,
        })
    }

    /// The other role's board, once that side has created it (`None`
    /// before).
    ///
    /// A board still being set up can read as corrupted for an instant in
    /// iceoryx2 0.10 (its static config written, its segments not yet):
    /// two runs starting at once hit it. It counts as not there yet, like
    /// one that hangs in creation; the caller's connect timeout bounds the
    /// wait, and a board left corrupted by a killed process is removed by
    /// the dead-node cleanup when the next run's node starts.
    ///
    /// # Errors
    /// The board exists but iceoryx2 refused to open it.
    pub fn open_peer_board(&self) -> Result<Option<Board>, ServiceError> {
        self.open_board(board_name(self.role.peer()))
    }

    /// Opens the simulated plant's truth board (`None` while it does not
    /// exist; an arm bridge never creates it).
    ///
    /// # Errors
    /// iceoryx2 failed for another reason.
    pub fn open_truth_board(&self) -> Result<Option<Board>, ServiceError> {
        self.open_board(TRUTH_BOARD)
    }

    /// Opens the simulated plant's successor counts board (`None` while it
    /// does not exist; an arm bridge never creates it).
    ///
    /// # Errors
    /// iceoryx2 failed for another reason.
    pub fn open_counts_board(&self) -> Result<Option<Board>, ServiceError> {
        self.open_board(COUNTS_BOARD)
    }

    fn open_board(&self, what: &str) -> Result<Option<Board>, ServiceError> {
        let name = ServiceName::new(&format!("shearcut/{}/{what}", self.run_id))
            .map_err(|e| iceoryx("service name", e))?;
        match self
            .node
            .service_builder(&name)
            .blackboard_opener::<u64>()
            .open()
        {
            Ok(board) => Ok(Some(board)),
            Err(
                BlackboardOpenError::DoesNotExist
                | BlackboardOpenError::IsMarkedForDestruction
                | BlackboardOpenError::HangsInCreation
                | BlackboardOpenError::ServiceInCorruptedState,
            ) => Ok(None),
            Err(e) => Err(iceoryx(&format!("{what} board"), e)),
        }
    }

    /// The signal (SIGINT/SIGTERM) that asked this process to stop, if one
    /// has arrived within `grace` (returns as soon as one has; `ZERO` only
    /// looks).
    pub fn termination_request(&self, grace: Duration) -> Option<StopSignal> {
        if grace.is_zero() {
            self.watch.requested()
        } else {
            self.watch.requested_within(grace)
        }
    }

    /// What this process knows of the other role's process since its node
    /// was created (one atomic load; the last look before
    /// [`stop_peer_watch`](Self::stop_peer_watch)).
    pub fn peer_fate(&self) -> PeerFate {
        self.peer.fate()
    }

    /// Ends the watch of the other role's node: the loop starts, and the
    /// watch's looks allocate.
    pub fn stop_peer_watch(&self) {
        self.peer.stop();
    }

    /// One look at the other role's node now, on this thread
    /// ([`PeerWatch::look_now`]: it allocates, off any tick path).
    pub fn look_at_peer(&self) -> PeerFate {
        self.peer.look_now()
    }

    /// The state of `role`'s node in this run: alive, dead (its process died
    /// without cleaning up) or absent.
    pub fn peer_state(&self, role: Role) -> PeerState {
        node_state(&self.config, &node_name(role, &self.run_id), None)
    }
}

/// The services a process of one run creates or opens on its node.
struct RunServices {
    own_board: Board,
    truth_board: Option<Board>,
    counts_board: Option<Board>,
    command_ready: event::PortFactory<ipc::Service>,
    measurement_ready: event::PortFactory<ipc::Service>,
}

impl RunServices {
    /// Opens or creates the run's services on `run`'s node.
    fn create(run: &RunNode) -> Result<Self, ServiceError> {
        let (node, watch, role) = (&run.node, &run.watch, run.role);
        let service_name = |what: &str| {
            ServiceName::new(&format!("shearcut/{}/{what}", run.run_id))
                .map_err(|e| iceoryx("service name", e))
        };
        let command_ready = node
            .service_builder(&service_name("command-ready")?)
            .event()
            .open_or_create()
            .map_err(|e| iceoryx("command-ready service", e))?;
        let measurement_ready = node
            .service_builder(&service_name("measurement-ready")?)
            .event()
            .open_or_create()
            .map_err(|e| iceoryx("measurement-ready service", e))?;
        let own_name = service_name(board_name(role))?;
        let (own_board, truth_board, counts_board) = match role {
            Role::Controller => (
                create_board(
                    node,
                    watch,
                    &own_name,
                    role,
                    "command",
                    WireCommand::empty(),
                )?,
                None,
                None,
            ),
            Role::Plant => {
                // The truth and counts boards first: a controller that
                // finds the measurement board finds them beside it.
                let truth = create_board(
                    node,
                    watch,
                    &service_name(TRUTH_BOARD)?,
                    role,
                    TRUTH_BOARD,
                    WireTruth::empty(),
                )?;
                let counts = create_board(
                    node,
                    watch,
                    &service_name(COUNTS_BOARD)?,
                    role,
                    COUNTS_BOARD,
                    WirePlantCounts::default(),
                )?;
                let own = create_board(
                    node,
                    watch,
                    &own_name,
                    role,
                    "measurement",
                    WireMeasurement::empty(),
                )?;
                (own, Some(truth), Some(counts))
            }
        };
        Ok(Self {
            own_board,
            truth_board,
            counts_board,
            command_ready,
            measurement_ready,
        })
    }
}

/// What iceoryx2's node list says about the other side.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PeerState {
    /// Its process runs.
    Alive,
    /// Its process died without cleaning up (iceoryx2 dead-node detection).
    Dead,
    /// No such node.
    Absent,
}
