//! The arm-style loop across processes: the wire format and the iceoryx2
//! shared-memory link between a controller process and a plant process.

pub mod board;
pub mod iceoryx2_link;
pub mod loop_services;
pub mod peer_watch;
pub mod plant_server;
pub mod run_node;
pub mod run_supervisor;
pub mod servo_priority;
pub mod termination_watch;
pub mod wait_mode;
pub mod wire;

pub use iceoryx2_link::{Iceoryx2PlantLink, LinkTimeouts};
pub use loop_services::{LoopServices, PeerState, Role, ServiceError};
pub use peer_watch::{PeerFate, PeerWatch};
pub use plant_server::{PlantEnd, PlantReport, PlantServerSettings, serve_plant};
pub use run_node::RunNode;
pub use termination_watch::{StopSignal, TerminationWatch};
pub use wait_mode::WaitMode;
