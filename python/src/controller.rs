//! `shearcut.Controller`: the knife controller, ticked from Python.

use pyo3::prelude::*;
use shearcut_controllers::controller::Controller as KnifeController;
use shearcut_ffi::{CutSetup, ShearcutCommand, ShearcutTelemetry};

use crate::arm_types::{Command, Reading};
use crate::errors::to_py;
use crate::scenario::Scenario;
use crate::telemetry::Telemetry;

/// The scenario's controller, as ``shearcut run`` builds it (the MPC plans
/// on its own thread; with the default lockstep planner a plan arrives a
/// fixed number of ticks after its request, so runs are bit-identical).
#[pyclass(module = "shearcut._shearcut", unsendable)]
pub(crate) struct Controller {
    setup: CutSetup,
    controller: Box<dyn KnifeController>,
}

#[pymethods]
impl Controller {
    #[new]
    fn new(scenario: &Scenario) -> PyResult<Self> {
        let controller = scenario.setup.controller().map_err(to_py)?;
        Ok(Self {
            setup: scenario.setup.clone(),
            controller,
        })
    }

    /// One servo tick: the arm's latest reading in, the command for the
    /// next tick out.
    fn tick(&mut self, reading: &Reading) -> Command {
        let command = self.controller.tick(&reading.to_arm());
        Command {
            inner: ShearcutCommand::from(&command),
        }
    }

    /// What the last tick planned.
    fn telemetry(&self) -> Telemetry {
        Telemetry {
            inner: ShearcutTelemetry::from(&self.controller.telemetry()),
        }
    }

    /// The controller's short name (``"mpc"``, ``"slice:0.75"``, ...).
    #[getter]
    fn name(&self) -> &str {
        self.controller.name()
    }

    /// A fresh controller from the same scenario, as before its first tick.
    fn reset(&mut self) -> PyResult<()> {
        self.controller = self.setup.controller().map_err(to_py)?;
        Ok(())
    }
}
