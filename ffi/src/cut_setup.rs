//! One cut as an embedding program sets it up: a scenario, the controller
//! chosen for it, and everything `shearcut run` builds from the two.
//!
//! [`CutSetup`] is the safe core behind the C ABI's `ShearcutSetup` handle
//! and the Python package's `Scenario`. It builds the controller and the
//! simulated plant exactly as `shearcut run --transport inproc` does
//! ([`LoopSetup`]), so a loop driven from another language with the same
//! lockstep semantics (the first command is the arm at rest; then reading →
//! `tick` → command → plant step, one servo period per command) reproduces
//! the Rust loop's numbers bit for bit.

use shearcut::closed_loop::LoopCut;
use shearcut::closed_loop::LoopSetup;
use shearcut::controller_choice::ControllerChoice;
use shearcut::error::RunError;
use shearcut::scenario::{Scenario, check_controller_kind};
use shearcut_controllers::controller::{Controller, CutTask};

use crate::simulated_plant::SimulatedPlant;

/// Why a setup, a controller or a plant could not be made, or a plant step
/// failed. The message is one line naming the problem.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum EmbedError {
    /// The scenario or the controller choice is unusable (a file that
    /// cannot be read, a key out of range, an unknown controller).
    #[error("{0}")]
    Config(String),
    /// The model failed (a section could not be built or solved).
    #[error("{0}")]
    Model(String),
}

impl From<RunError> for EmbedError {
    fn from(e: RunError) -> Self {
        match e {
            RunError::Config(c) => Self::Config(c.to_string()),
            other => Self::Model(other.to_string()),
        }
    }
}

/// A scenario with its controller choice and the loop setup built from
/// them (the MPC's view of the object included: building it runs the
/// section model, so a setup takes from milliseconds to about a second).
#[derive(Debug, Clone)]
pub struct CutSetup {
    scenario: Scenario,
    choice: ControllerChoice,
    setup: LoopSetup,
}

impl CutSetup {
    /// Loads `scenario` (a TOML path, or the name of a built-in scenario)
    /// and sets it up for `controller` (`mpc`, `press`, `slice:XI`,
    /// `force:N`; `None`: the scenario's `[controller] kind`).
    ///
    /// # Errors
    /// [`EmbedError::Config`] naming the file, key, value and what is
    /// allowed; [`EmbedError::Model`] if the MPC's view of the object
    /// cannot be built.
    pub fn load(scenario: &str, controller: Option<&str>) -> Result<Self, EmbedError> {
        let scenario = Scenario::load(scenario).map_err(|e| EmbedError::Config(e.to_string()))?;
        let choice = match controller {
            Some(text) => text
                .parse::<ControllerChoice>()
                .and_then(|c| check_controller_kind("controller", c).map(|()| c))
                .map_err(|e| EmbedError::Config(e.to_string()))?,
            None => scenario.controller.kind,
        };
        let setup = LoopSetup::new(&scenario, choice)?;
        Ok(Self {
            scenario,
            choice,
            setup,
        })
    }

    /// The scenario, presets resolved.
    pub fn scenario(&self) -> &Scenario {
        &self.scenario
    }

    /// The controller chosen.
    pub fn choice(&self) -> ControllerChoice {
        self.choice
    }

    /// What the controller is told about the cut (target depth, touch
    /// height, servo period, blade budget, limits).
    pub fn task(&self) -> &CutTask {
        &self.setup.task
    }

    /// Most servo ticks a simulated run takes before it stops as timed out:
    /// ⌈`[controller] max_duration` / period⌉, as `shearcut run` counts.
    pub fn max_ticks(&self) -> u64 {
        (self.scenario.controller.max_duration / self.setup.task.period).ceil() as u64
    }

    /// The loop's labels and stop conditions as `shearcut run` uses them:
    /// where the knife starts, its gap to the object, the target depth.
    pub fn cut(&self) -> LoopCut {
        self.setup.cut(&self.scenario)
    }

    /// A fresh controller, as `shearcut run` builds it.
    ///
    /// # Errors
    /// [`EmbedError::Config`] if the scenario's controller settings do not
    /// make a controller for this task.
    pub fn controller(&self) -> Result<Box<dyn Controller>, EmbedError> {
        Ok(self.setup.controller(&self.scenario, self.choice)?)
    }

    /// A fresh simulated plant, the knife at its start above the object.
    ///
    /// # Errors
    /// [`EmbedError::Config`] if the plant's settings are out of range or
    /// the knife never meets the object; [`EmbedError::Model`] if a first
    /// section cannot be built.
    pub fn plant(&self) -> Result<SimulatedPlant, EmbedError> {
        let plant = self.setup.plant(&self.scenario)?;
        Ok(SimulatedPlant::new(plant, self.setup.task.period))
    }
}
