//! Controllers of the knife: the [`Controller`] trait and the baselines.
//!
//! A controller sees what an arm and its force/torque sensor report each
//! servo tick (an [`ArmReading`]) and what a lab knows before the cut (the
//! [`CutTask`]), and answers with the knife twist for the
//! next tick (a [`KnifeCommand`]), as a controller embedded in an arm's
//! 1 kHz loop does. Every controller here plans a knife velocity
//! (normal speed v_n down into the object and tangential speed v_t along
//! the edge, towards the tip) and hands it to a [`VelocityShaper`], our
//! jerk-limited trajectory generator's velocity interface, which turns it
//! into commands the arm accepts (its limits checked by finite differences).
//!
//! ## Conventions
//! World frame as in the plant: y up, the knife moves in its plane (y, z),
//! +z along the edge towards the tip. A plan (v_n, v_t) is the twist
//! (0, −v_n, v_t); its slice-push ratio is ξ = v_t / v_n (seed 000 §III,
//! ξ = tan α for a straight edge).
//!
//! ## Baselines
//! - [`ConstantSlice`]: constant ξ at a constant speed (ξ = 0 is pressing),
//!   within a blade-travel budget.
//! - [`ForceFeedback`]: a PI loop on the measured vertical force.

mod blade_budget;
mod constant_slice;
mod cut_task;
mod force_feedback;
mod sawing_stroke;
mod velocity_shaper;

pub use blade_budget::{BladeBudget, stopping_distance, stopping_duration};
pub use constant_slice::ConstantSlice;
pub use cut_task::{CutTask, MotionLimits};
pub use force_feedback::{ForceFeedback, ForceFeedbackGains, INTEGRAL_BAND};
pub use sawing_stroke::{SawingStroke, StrokePhase};
pub use velocity_shaper::VelocityShaper;

use shearcut_sim::arm::{ArmReading, KnifeCommand};

/// Where a controller is in the cut.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum CutPhase {
    /// Moving towards the target depth.
    #[default]
    Cutting,
    /// The target depth is reached: the knife is brought to rest.
    Done,
}

/// What a controller planned in its last tick (for logs and plots).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ControllerTelemetry {
    /// Planned slice-push ratio ξ = v_t / v_n.
    pub slice_push_ratio: f64,
    /// Planned normal speed v_n (down into the object), m/s.
    pub normal_speed: f64,
    /// Planned tangential speed v_t (towards the tip), m/s.
    pub tangential_speed: f64,
    /// Tangential blade travel used so far, m.
    pub blade_travel: f64,
    /// The phase.
    pub phase: CutPhase,
    /// Whether this tick planned (solved an optimisation); for statistics.
    pub planned: bool,
    /// Plans so far that fell back to the previous plan.
    pub fallbacks: u64,
    /// The material scale factors the controller currently believes
    /// (toughness, stiffness, friction; 1 for controllers without a model).
    pub scale: [f64; 3],
}

impl ControllerTelemetry {
    /// The telemetry of a tick that commands (v_n, v_t) (m/s), with
    /// `blade_travel` (m) used so far, `done` once the target depth is
    /// reached; not planning, no fallbacks, nominal scale factors (a
    /// planner overwrites those fields).
    pub fn moving(normal_speed: f64, tangential_speed: f64, blade_travel: f64, done: bool) -> Self {
        Self {
            slice_push_ratio: if normal_speed > 0.0 {
                tangential_speed / normal_speed
            } else {
                0.0
            },
            normal_speed,
            tangential_speed,
            blade_travel,
            phase: if done {
                CutPhase::Done
            } else {
                CutPhase::Cutting
            },
            ..Self::default()
        }
    }
}

impl Default for ControllerTelemetry {
    fn default() -> Self {
        Self {
            slice_push_ratio: 0.0,
            normal_speed: 0.0,
            tangential_speed: 0.0,
            blade_travel: 0.0,
            phase: CutPhase::Cutting,
            planned: false,
            fallbacks: 0,
            scale: [1.0; 3],
        }
    }
}

/// A knife controller in an arm's servo loop.
///
/// Construction may allocate; [`Controller::tick`] allocates nothing, takes
/// no lock and never panics: a controller that cannot plan falls back to a
/// safe command and says so in its telemetry (the MPC solves on its own
/// planner thread; `controllers/tests/controller_alloc.rs` counts every
/// allocation of the tick).
///
/// A controller of one's own, driven by a reading (in a real cell the
/// arm's; [`ConstantSlice`] and [`crate::mpc::Mpc`] are this crate's):
///
/// ```
/// use nalgebra::Vector3;
/// use shearcut_controllers::controller::{Controller, ControllerTelemetry};
/// use shearcut_sim::arm::{ArmReading, ArmStatus, KnifeCommand};
///
/// /// Presses the knife down at 5 mm/s until its origin is at 20 mm.
/// struct PressTo20mm;
///
/// impl Controller for PressTo20mm {
///     fn name(&self) -> &str {
///         "press-to-20mm"
///     }
///     fn tick(&mut self, reading: &ArmReading) -> KnifeCommand {
///         let down = if reading.position.y > 0.02 { -0.005 } else { 0.0 };
///         KnifeCommand { velocity: Vector3::new(0.0, down, 0.0) }
///     }
///     fn telemetry(&self) -> ControllerTelemetry {
///         ControllerTelemetry::default()
///     }
/// }
///
/// let reading = ArmReading {
///     time: 0.0,
///     position: Vector3::new(0.0, 0.05, 0.0),
///     velocity: Vector3::zeros(),
///     wrench: [0.0; 6],
///     status: ArmStatus::Moving,
/// };
/// let mut c = PressTo20mm;
/// assert_eq!(c.tick(&reading).velocity.y, -0.005);
/// ```
pub trait Controller {
    /// A short name for tables and logs (e.g. `slice:0.75`).
    fn name(&self) -> &str;

    /// One servo tick: the arm's latest reading in, the command for the
    /// next tick out. The reading is all a controller sees of the world:
    /// the simulated plant's ground truth lives in `shearcut-plant`, which
    /// this crate does not depend on.
    fn tick(&mut self, reading: &ArmReading) -> KnifeCommand;

    /// What the last tick planned.
    fn telemetry(&self) -> ControllerTelemetry;

    /// How long each plan took off the tick so far, µs of wall clock, in
    /// the order made (a controller with a planner thread; empty by
    /// default). A copy, for after a run: never called on a tick.
    fn solve_times_us(&self) -> Vec<f64> {
        Vec::new()
    }
}
