//! `#[repr(C)]` mirror of the simulated plant's ground truth
//! (`shearcut_plant::PlantTruth`): for a simulation's stop condition,
//! scoring and records, never for control (a controller gets only the
//! reading).

use nalgebra::Vector3;
use shearcut_plant::{PlantTruth, Wrench};

/// What only the simulated plant knows after a step.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ShearcutTruth {
    /// The noise-free, unbiased force at the sensor [fx, fy, fz], N, world
    /// axes: the object on the knife (fy > 0 pushes the knife up).
    pub force: [f64; 3],
    /// The noise-free torque about the sensor [tx, ty, tz], N·m.
    pub torque: [f64; 3],
    /// Depth of the crack front below the object's top, m.
    pub crack_depth: f64,
    /// Length of edge in contact with material, m.
    pub contact_length: f64,
    /// Number of sections that have fractured.
    pub fractured_sections: u64,
    /// Cumulative knife work on the object, J.
    pub work: f64,
    /// Largest surface deformation next to the blade over the sections, m.
    pub deformation: f64,
}

impl From<&PlantTruth> for ShearcutTruth {
    #[inline]
    fn from(t: &PlantTruth) -> Self {
        Self {
            force: t.wrench.force.into(),
            torque: t.wrench.torque.into(),
            crack_depth: t.crack_depth,
            contact_length: t.contact_length,
            fractured_sections: t.fractured_sections as u64,
            work: t.work,
            deformation: t.deformation,
        }
    }
}

impl From<&ShearcutTruth> for PlantTruth {
    #[inline]
    fn from(t: &ShearcutTruth) -> Self {
        Self {
            wrench: Wrench {
                force: Vector3::from(t.force),
                torque: Vector3::from(t.torque),
            },
            crack_depth: t.crack_depth,
            contact_length: t.contact_length,
            fractured_sections: usize::try_from(t.fractured_sections).unwrap_or(usize::MAX),
            work: t.work,
            deformation: t.deformation,
        }
    }
}
