//! `shearcut.Plant`: the simulated plant, stepped from Python.

use pyo3::prelude::*;
use shearcut_ffi::{CutSetup, ShearcutReading, ShearcutTruth, SimulatedPlant};

use crate::arm_types::{Command, Reading};
use crate::errors::to_py;
use crate::scenario::Scenario;
use crate::truth::Truth;

/// The simulated plant of a scenario: the arm (its limits checked on every
/// command by finite differences), the F/T sensor and the object, the
/// knife at rest above it. Raises ``RuntimeError`` if the model fails.
#[pyclass(module = "shearcut._shearcut", unsendable)]
pub(crate) struct Plant {
    setup: CutSetup,
    plant: SimulatedPlant,
}

#[pymethods]
impl Plant {
    #[new]
    fn new(scenario: &Scenario) -> PyResult<Self> {
        let plant = scenario.setup.plant().map_err(to_py)?;
        Ok(Self {
            setup: scenario.setup.clone(),
            plant,
        })
    }

    /// Executes ``command`` for one servo period (``Scenario.period``) and
    /// returns the arm's reading and the simulated truth after it.
    fn step(&mut self, command: &Command) -> PyResult<(Reading, Truth)> {
        let step = self.plant.step(&(&command.inner).into()).map_err(to_py)?;
        Ok((
            Reading {
                inner: ShearcutReading::from(&step.reading),
            },
            Truth {
                inner: ShearcutTruth::from(&step.truth),
            },
        ))
    }

    /// The knife back at its start, the object intact, the sensor's noise
    /// restarted from the scenario's seed.
    fn reset(&mut self) -> PyResult<()> {
        self.plant = self.setup.plant().map_err(to_py)?;
        Ok(())
    }
}
