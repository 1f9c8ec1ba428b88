//! A process's iceoryx2 node in one run (`plant/<run-id>` or
//! `controller/<run-id>`), created before anything else the process builds:
//! from then on the other side can tell the process is there, and see it go
//! if it ends before serving. A run id that a live node of the same role
//! already serves is refused at creation.
//!
//! iceoryx2's own cleanups of dead nodes (on a node's creation, on a
//! service's opening) are off under shearcut's configuration
//! ([`config`](super::loop_services::config)): they would remove a peer's
//! dead node before this process could see it die. The node's creation
//! cleans instead, and tells whether the peer it removed was alive just
//! before.

use std::time::Duration;

use iceoryx2::identifiers::UniqueNodeId;
use iceoryx2::node::NodeView;
use iceoryx2::prelude::*;

use super::loop_services::{PeerState, Role, ServiceError, config, is_name, node_name};
use super::peer_watch::{PeerFate, PeerWatch};
use super::termination_watch::TerminationWatch;

/// How long a cleanup waits for a concurrent cleaner of the same dead node.
const CLEANUP_WAIT: Duration = Duration::from_millis(100);

/// The age (from its creation, by iceoryx2's node id) up to which a dead
/// peer node that this process never saw alive is taken for this run's
/// peer, which died before this process looked: two processes of a run are
/// started within seconds of each other. An older dead node is an earlier
/// run's under the same run id, cleaned and ignored. (A run with the same
/// id killed within this age of its start and started again at once, the
/// process that finds the dead node first, takes it for its peer.)
pub const RECENT_PEER: Duration = Duration::from_secs(5);

/// One process's node in run `run_id`.
#[derive(Debug)]
pub struct RunNode {
    /// The node.
    pub node: Node<ipc::Service>,
    /// The run id.
    pub run_id: String,
    /// The configuration (prefix) in force.
    pub config: Config,
    /// This process's role.
    pub role: Role,
    /// SIGINT/SIGTERM, watched from before the node's creation.
    pub watch: TerminationWatch,
    /// The other role's node in this run, watched from this node's
    /// creation until the loop starts.
    pub peer: PeerWatch,
}

impl RunNode {
    /// Creates `role`'s node for run `run_id` under `prefix`, cleaning the
    /// resources of dead nodes under that prefix, and starts watching the
    /// peer's node: a peer alive just before the creation and dead at its
    /// cleanup died ([`PeerFate::Died`]), and so did a peer found dead
    /// without having been seen alive whose node is at most
    /// [`RECENT_PEER`] old, unless a live one appears within the watch's
    /// grace ([`PeerFate::DiedUnseen`]); an older dead one is an earlier
    /// run's, and is not seen.
    ///
    /// # Errors
    /// The run id or prefix is not allowed; another live process of this
    /// role serves `run_id` ([`ServiceError::RunIdInUse`]); iceoryx2
    /// refused.
    pub fn create(role: Role, run_id: &str, prefix: &str) -> Result<Self, ServiceError> {
        if !is_name(run_id, 64) {
            return Err(ServiceError::RunId(run_id.to_string()));
        }
        let config = config(prefix)?;
        let watch = TerminationWatch::new();
        let own = node_name(role, run_id);
        let peer = node_name(role.peer(), run_id);
        let (_, peer_before) = look(&config, &peer, None, None);
        let name =
            NodeName::new(&own).map_err(|e| ServiceError::Iceoryx(format!("node name: {e:?}")))?;
        let node = NodeBuilder::new()
            .name(&name)
            .config(&config)
            .create::<ipc::Service>()
            .map_err(|e| ServiceError::Iceoryx(format!("node: {e:?}")))?;
        // Stale resources of killed processes under this prefix.
        let dead_peers = cleanup_dead_nodes(&config, &peer);
        if node_state(&config, &own, Some(node.id())) == PeerState::Alive {
            return Err(ServiceError::RunIdInUse {
                run_id: run_id.to_string(),
                role,
            });
        }
        // A dead peer node other than the one seen alive is an earlier
        // run's, unless it is recent (it died before it could be seen).
        let initial = match peer_before {
            Some(id) if dead_peers.contains(&id) => PeerFate::Died,
            Some(_) => PeerFate::Alive,
            None if dead_peers.iter().any(is_recent) => PeerFate::DiedUnseen,
            None => PeerFate::NotSeen,
        };
        let peer = PeerWatch::start(
            config.clone(),
            peer,
            initial,
            peer_before,
            creation_time(node.id()),
        );
        Ok(Self {
            node,
            run_id: run_id.to_string(),
            config,
            role,
            watch,
            peer,
        })
    }
}

/// When the node `id` was created, on the host's monotonic clock its id was
/// stamped with (nanosecond resolution); `None` if the id does not say.
pub fn creation_time(id: &UniqueNodeId) -> Option<Duration> {
    id.creation_time::<ipc::Service>()
        .ok()
        .map(|t| t.as_duration())
}

/// Whether the node `id` was created at most [`RECENT_PEER`] ago (the
/// monotonic clock its id was stamped with is the host's).
fn is_recent(id: &UniqueNodeId) -> bool {
    id.creation_time::<ipc::Service>()
        .ok()
        .and_then(|created| created.elapsed().ok())
        .is_some_and(|age| age <= RECENT_PEER)
}

/// Removes the stale resources of every dead node under `config` (waiting
/// up to [`CLEANUP_WAIT`] for a concurrent cleaner of each); the ids of the
/// dead nodes named `peer` among them.
fn cleanup_dead_nodes(config: &Config, peer: &str) -> Vec<UniqueNodeId> {
    let mut dead_peers = Vec::new();
    let _ = Node::<ipc::Service>::list(config, |n| {
        if let NodeState::Dead(dead) = n {
            if dead
                .details()
                .as_ref()
                .is_some_and(|d| d.name().as_str() == peer)
            {
                dead_peers.push(*dead.id());
            }
            let _ = dead.blocking_remove_stale_resources(CLEANUP_WAIT);
        }
        CallbackProgression::Continue
    });
    dead_peers
}

/// A look at the nodes named `name` under `config`: with `seen`, the state
/// of that node (alive, dead, or absent: gone); without, alive and its id
/// if one of them is alive, else dead and its id if one of them died that
/// was created after `born_after` (a peer started after the looking
/// process's node, and killed before any look saw it alive), else absent
/// (a dead one created earlier is an earlier run's, or died unseen). Lists
/// every node of the prefix (it allocates): keep it off the tick path.
pub fn look(
    config: &Config,
    name: &str,
    seen: Option<UniqueNodeId>,
    born_after: Option<Duration>,
) -> (PeerState, Option<UniqueNodeId>) {
    let mut found = (PeerState::Absent, seen);
    let _ = Node::<ipc::Service>::list(config, |n| {
        let (id, details, alive) = match &n {
            NodeState::Alive(v) => (*v.id(), v.details(), true),
            NodeState::Dead(v) => (*v.id(), v.details(), false),
            _ => return CallbackProgression::Continue,
        };
        if details.as_ref().is_none_or(|d| d.name().as_str() != name) {
            return CallbackProgression::Continue;
        }
        match seen {
            Some(s) if s == id => {
                found.0 = if alive {
                    PeerState::Alive
                } else {
                    PeerState::Dead
                };
                CallbackProgression::Stop
            }
            None if alive => {
                found = (PeerState::Alive, Some(id));
                CallbackProgression::Stop
            }
            None if born_after
                .zip(creation_time(&id))
                .is_some_and(|(after, created)| created > after) =>
            {
                // Keep listing: a live node of the name wins.
                found = (PeerState::Dead, Some(id));
                CallbackProgression::Continue
            }
            _ => CallbackProgression::Continue,
        }
    });
    found
}

/// The state of the nodes named `name` under `config` other than `except`:
/// alive if one is, else dead if one died without cleaning up, else
/// absent. Lists every node of the prefix (it allocates): keep it
/// off the tick path.
pub fn node_state(config: &Config, name: &str, except: Option<&UniqueNodeId>) -> PeerState {
    let mut state = PeerState::Absent;
    let _ = Node::<ipc::Service>::list(config, |n| {
        let (id, details, alive) = match &n {
            NodeState::Alive(v) => (*v.id(), v.details().clone(), true),
            NodeState::Dead(v) => (*v.id(), v.details().clone(), false),
            _ => return CallbackProgression::Continue,
        };
        if Some(&id) == except {
            return CallbackProgression::Continue;
        }
        match details {
            Some(d) if d.name().as_str() == name => {
                if alive {
                    state = PeerState::Alive;
                    CallbackProgression::Stop
                } else {
                    state = PeerState::Dead;
                    CallbackProgression::Continue
                }
            }
            _ => CallbackProgression::Continue,
        }
    });
    state
}
