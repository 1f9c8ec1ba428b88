//! What one tick of the plant produces: the arm's reading, and the
//! simulated ground truth that no arm measures.

use shearcut_sim::arm::ArmReading;

use crate::wrench::Wrench;

/// What only the simulated plant knows after a tick: the cut's state and
/// the noise-free wrench. A runner uses it for its stop condition, scores,
/// records and plots; a controller never sees it (`shearcut-controllers`
/// does not depend on this crate).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PlantTruth {
    /// The noise-free, unbiased wrench at the sensor, N and N·m.
    pub wrench: Wrench,
    /// Depth of the crack front below the object's top, m: the top's height
    /// in the knife's plane less the mean height of the crack tips over the
    /// active sections (those whose plane cuts the object; 0 when none is).
    /// Under a straight edge on a flat top it is the sections' mean crack
    /// depth; on a dome it is how far below the crest the cut has gone
    /// (a flank section's tip sits at its own surface where the edge
    /// touches), so before the first fracture it is already the depth of
    /// the sections' tops in contact.
    pub crack_depth: f64,
    /// Length of edge in contact with material, m.
    pub contact_length: f64,
    /// Number of sections that have fractured.
    pub fractured_sections: usize,
    /// Cumulative knife work on the object, J.
    pub work: f64,
    /// Largest surface deformation next to the blade over the sections, m.
    pub deformation: f64,
}

/// One tick of the plant: what the arm reports, and the truth beside it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlantStep {
    /// What the arm and its F/T sensor report (the controller's input).
    pub reading: ArmReading,
    /// The simulated ground truth (the runner's).
    pub truth: PlantTruth,
}
