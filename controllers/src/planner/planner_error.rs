//! Failures of building a planner.

use shearcut_sim::InvalidSetting;

/// Why a [`super::Planner`] could not be built.
#[derive(Debug, thiserror::Error)]
pub enum PlannerError {
    /// The latency policy is out of range.
    #[error("planner: {0}")]
    Setting(#[from] InvalidSetting),
    /// The operating system refused the planner thread.
    #[error("planner: cannot start the planner thread: {0}")]
    Spawn(#[from] std::io::Error),
}
