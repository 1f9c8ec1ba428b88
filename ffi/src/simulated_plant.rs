//! The simulated plant as an embedding program steps it: one command per
//! servo period, the arm's reading and the plant's truth back.

use shearcut_plant::{Plant, PlantStep};
use shearcut_sim::arm::KnifeCommand;

use crate::cut_setup::EmbedError;

/// A [`Plant`] advanced one servo period per command, as `shearcut run
/// --transport inproc` advances it (`InProcessPlant`).
///
/// # Memory allocation
/// Construction allocates the sections and starts the plant's section
/// builder thread; [`SimulatedPlant::step`] allocates nothing on the
/// caller's thread (the plant's own guarantee) unless it fails.
#[derive(Debug, Clone)]
pub struct SimulatedPlant {
    plant: Plant,
    period: f64,
}

impl SimulatedPlant {
    /// Wraps `plant`, stepped every `period` seconds.
    pub fn new(plant: Plant, period: f64) -> Self {
        Self { plant, period }
    }

    /// The servo period, s.
    pub fn period(&self) -> f64 {
        self.period
    }

    /// The plant.
    pub fn plant(&self) -> &Plant {
        &self.plant
    }

    /// Executes `command` for one servo period: the arm checks it against
    /// its limits (a refused command leaves the knife still and says so in
    /// the reading's status), the sections advance, and the F/T sensor is
    /// sampled.
    ///
    /// # Errors
    /// [`EmbedError::Model`] if a section cannot be solved or built.
    pub fn step(&mut self, command: &KnifeCommand) -> Result<PlantStep, EmbedError> {
        self.plant
            .step(command, self.period)
            .map_err(|e| EmbedError::Model(format!("the plant model failed: {e}")))
    }
}
