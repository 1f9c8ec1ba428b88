//! The plant in the controller's process, stepped in lockstep.

use shearcut_plant::Plant;
use shearcut_sim::arm::KnifeCommand;

use super::plant_link::{LinkAnswer, LinkError, PlantLink};
use crate::transport::wire::WirePlantCounts;

/// A [`Plant`] stepped directly: each command advances it one period.
#[derive(Debug, Clone)]
pub struct InProcessPlant {
    plant: Plant,
    period: f64,
    /// Answer before the re-choices ([`Self::answer_first`]).
    answer_first: bool,
}

impl InProcessPlant {
    /// Wraps `plant`, stepped every `period` seconds.
    pub fn new(plant: Plant, period: f64) -> Self {
        Self {
            plant,
            period,
            answer_first: false,
        }
    }

    /// Answers each command as soon as its measurement is known, leaving
    /// the plant's re-choices and placements ([`Plant::settle`]) to
    /// [`PlantLink::settle`] or the next exchange: for a realtime server,
    /// which settles after answering. Results are bit-identical.
    pub fn answer_first(&mut self) {
        self.answer_first = true;
    }

    /// The plant.
    pub fn plant(&self) -> &Plant {
        &self.plant
    }
}

impl PlantLink for InProcessPlant {
    fn period(&self) -> f64 {
        self.period
    }

    fn exchange(&mut self, command: &KnifeCommand) -> Result<LinkAnswer, LinkError> {
        let step = if self.answer_first {
            self.plant.step_measured(command, self.period)
        } else {
            self.plant.step(command, self.period)
        }
        .map_err(|e| LinkError::Model(e.to_string()))?;
        Ok(LinkAnswer {
            reading: step.reading,
            truth: Some(step.truth),
        })
    }

    fn settle(&mut self) -> Result<(), LinkError> {
        self.plant
            .settle()
            .map_err(|e| LinkError::Model(e.to_string()))
    }

    fn successor_counts(&self) -> Option<WirePlantCounts> {
        Some(WirePlantCounts {
            successor_deferrals: self.plant.successor_deferrals() as u64,
            successor_waits: self.plant.successor_waits() as u64,
        })
    }

    fn rechoices(&self) -> Option<usize> {
        Some(self.plant.rechoices())
    }
}
