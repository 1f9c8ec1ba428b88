//! The controller's view of a plant: send a command, get the measurement.

use shearcut_sim::plant::{KnifeCommand, Measurement};

/// Why a plant link stopped answering.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum LinkError {
    /// The plant's model failed (a section could not be solved or built).
    #[error("the plant model failed: {0}")]
    Model(String),
    /// The plant is gone or silent.
    #[error("lost the plant: {0}")]
    Lost(String),
}

/// A plant as the controller's side of an arm loop sees it: one command
/// per servo tick, one measurement back. Lockstep: the plant advances one
/// period per command.
pub trait PlantLink {
    /// The servo period, s.
    fn period(&self) -> f64;

    /// Sends `command` for the next tick and returns the measurement after it.
    ///
    /// # Errors
    /// The plant failed or is gone.
    fn exchange(&mut self, command: &KnifeCommand) -> Result<Measurement, LinkError>;
}
