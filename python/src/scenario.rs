//! `shearcut.Scenario`: a scenario set up for one controller.

use pyo3::prelude::*;
use shearcut_ffi::{CutSetup, ShearcutTask};

use crate::errors::to_py;

/// A scenario (a TOML path or a built-in name such as
/// ``"loop-potato-whole-realtime"``) set up for a controller (``"mpc"``,
/// ``"press"``, ``"slice:XI"``, ``"force:N"``; ``None``: the scenario's
/// ``[controller] kind``). Plants and controllers are made from it.
///
/// Raises ``ValueError`` (one line naming the file, key, value and what is
/// allowed) if the scenario or the controller is unusable.
#[pyclass(module = "shearcut._shearcut", frozen)]
pub(crate) struct Scenario {
    pub(crate) setup: CutSetup,
    task: ShearcutTask,
}

#[pymethods]
impl Scenario {
    #[new]
    #[pyo3(signature = (scenario, controller=None))]
    fn new(scenario: &str, controller: Option<&str>) -> PyResult<Self> {
        let setup = CutSetup::load(scenario, controller).map_err(to_py)?;
        let task = ShearcutTask::from(&setup);
        Ok(Self { setup, task })
    }

    /// The scenario's name.
    #[getter]
    fn name(&self) -> &str {
        &self.setup.scenario().name
    }

    /// The controller chosen (``"mpc"``, ``"slice:0.75"``, ...).
    #[getter]
    fn controller(&self) -> String {
        self.setup.choice().to_string()
    }

    /// Servo period, s (0.001 at 1 kHz).
    #[getter]
    fn period(&self) -> f64 {
        self.task.period
    }

    /// Depth of the cut below the object's top, m: a simulated run
    /// completes when ``Truth.crack_depth`` reaches it.
    #[getter]
    fn target_depth(&self) -> f64 {
        self.task.target_depth
    }

    /// The knife origin's height when its edge first meets the object, m.
    #[getter]
    fn touch_height(&self) -> f64 {
        self.task.touch_height
    }

    /// Tangential blade travel available, m.
    #[getter]
    fn blade_budget(&self) -> f64 {
        self.task.blade_budget
    }

    /// Most ticks of a simulated run before it stops as timed out.
    #[getter]
    fn max_ticks(&self) -> u64 {
        self.task.max_ticks
    }

    /// Where the simulated plant starts the knife's origin (x, y, z), m.
    #[getter]
    fn start_position(&self) -> (f64, f64, f64) {
        let p = self.task.start_position;
        (p[0], p[1], p[2])
    }

    fn __repr__(&self) -> String {
        format!(
            "Scenario({:?}, controller={:?})",
            self.setup.scenario().name,
            self.setup.choice().to_string()
        )
    }
}
