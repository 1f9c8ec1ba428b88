//! How a side of the loop waits for the other.

/// Waiting strategy for commands (plant) and measurements (controller).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum WaitMode {
    /// Sleep on an iceoryx2 event until the other side notifies (a few µs
    /// of wake-up latency, no CPU burnt while waiting).
    #[default]
    Blocking,
    /// Spin on the shared-memory queue (lowest latency; burns one core).
    BusyPoll,
}
