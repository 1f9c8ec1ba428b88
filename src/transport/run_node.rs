//! A process's iceoryx2 node in one run (`plant/<run-id>` or
//! `controller/<run-id>`), created before anything else the process builds:
//! from then on the other side can tell the process is there, and see it go
//! if it ends before serving. A run id that a live node of the same role
//! already serves is refused at creation.

use std::time::Duration;

use iceoryx2::identifiers::UniqueNodeId;
use iceoryx2::node::NodeView;
use iceoryx2::prelude::*;

use super::loop_services::{PeerState, Role, ServiceError, config, is_name, node_name};
use super::termination_watch::TerminationWatch;

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
}

impl RunNode {
    /// Creates `role`'s node for run `run_id` under `prefix`, cleaning the
    /// resources of dead nodes under that prefix.
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
        let name =
            NodeName::new(&own).map_err(|e| ServiceError::Iceoryx(format!("node name: {e:?}")))?;
        let node = NodeBuilder::new()
            .name(&name)
            .config(&config)
            .create::<ipc::Service>()
            .map_err(|e| ServiceError::Iceoryx(format!("node: {e:?}")))?;
        // Stale resources of killed processes under this prefix; the node
        // creation already tried, this waits for a concurrent cleaner.
        let _ = node.blocking_cleanup_dead_nodes(Duration::from_millis(100));
        if node_state(&config, &own, Some(node.id())) == PeerState::Alive {
            return Err(ServiceError::RunIdInUse {
                run_id: run_id.to_string(),
                role,
            });
        }
        Ok(Self {
            node,
            run_id: run_id.to_string(),
            config,
            role,
            watch,
        })
    }
}

/// The state of the nodes named `name` under `config` other than `except`:
/// alive if one is, else dead if one died without cleaning up, else
/// absent. Lists every node of the prefix (about 1.2k allocations): keep it
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
