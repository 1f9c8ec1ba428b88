//! The controller's view of a plant: send a command, get the arm's reading
//! (and, from a simulated plant, its ground truth for the runner).

use shearcut_plant::PlantTruth;
use shearcut_sim::arm::{ArmReading, KnifeCommand};

use crate::transport::StopSignal;
use crate::transport::wire::WirePlantCounts;

/// Why a plant link stopped answering.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum LinkError {
    /// The plant's model failed (a section could not be solved or built).
    #[error("the plant model failed: {0}")]
    Model(String),
    /// The plant is gone or silent.
    #[error("lost the plant: {0}")]
    Lost(String),
    /// A signal (SIGINT/SIGTERM) asked this process to stop while it
    /// waited for the plant.
    #[error("stopped by {0} while waiting for the plant")]
    Stopped(StopSignal),
}

/// One tick's answer of a plant link: the arm's reading, which the
/// controller gets, and the simulated plant's truth, which only the runner
/// sees (absent from a real arm's bridge).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LinkAnswer {
    /// What the arm and its F/T sensor report.
    pub reading: ArmReading,
    /// The simulated ground truth, if the plant is simulated.
    pub truth: Option<PlantTruth>,
}

/// A plant as the controller's side of an arm loop sees it: one command
/// per servo tick, one reading back. Lockstep: the plant advances one
/// period per command.
pub trait PlantLink {
    /// The servo period, s.
    fn period(&self) -> f64;

    /// Sends `command` for the next tick and returns the reading after it.
    ///
    /// # Errors
    /// The plant failed or is gone.
    fn exchange(&mut self, command: &KnifeCommand) -> Result<LinkAnswer, LinkError>;

    /// Work after an answer that the next [`Self::exchange`] needs done and
    /// the answer did not (a simulated plant's re-choices, when it answers
    /// first: [`InProcessPlant::answer_first`](super::InProcessPlant::answer_first));
    /// a realtime server calls it in the time left before its next tick.
    /// Nothing by default.
    ///
    /// # Errors
    /// The plant failed.
    fn settle(&mut self) -> Result<(), LinkError> {
        Ok(())
    }

    /// The simulated plant's successor counts so far; `None` for a plant
    /// without them (an arm, or a remote plant that has not published them).
    fn successor_counts(&self) -> Option<WirePlantCounts> {
        None
    }

    /// How often the simulated plant has re-chosen its moving cross
    /// sections so far (seed 000 §IV); `None` for a plant that does not
    /// say (an arm, or a plant in another process).
    fn rechoices(&self) -> Option<usize> {
        None
    }
}
