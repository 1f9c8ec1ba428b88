//! `#[repr(C)]` mirror of the cut a setup gives its controller
//! (`shearcut_controllers::controller::CutTask`), with what a simulated
//! loop needs to stop as `shearcut run` does.

use crate::cut_setup::CutSetup;

/// The cut, as the controller is told it, and the simulated loop's limits.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ShearcutTask {
    /// Servo period, s (1 / `[loop] rate_hz`; 0.001 at 1 kHz).
    pub period: f64,
    /// Depth of the cut below the object's top, m: a simulated run
    /// completes when the plant's crack depth (`ShearcutTruth::crack_depth`)
    /// reaches it.
    pub target_depth: f64,
    /// The knife origin's height y when its edge first meets the object's
    /// top, m (on a real cell: a touch-off).
    pub touch_height: f64,
    /// Tangential blade travel available, m.
    pub blade_budget: f64,
    /// Largest normal (downward) speed the controller plans, m/s.
    pub normal_speed_limit: f64,
    /// Largest tangential speed the controller plans, m/s.
    pub tangential_speed_limit: f64,
    /// Largest acceleration per axis the controller plans, m/s².
    pub acceleration_limit: f64,
    /// Largest jerk per axis the controller plans, m/s³.
    pub jerk_limit: f64,
    /// Most ticks of a simulated run before it stops as timed out
    /// (⌈`[controller] max_duration` / period⌉).
    pub max_ticks: u64,
    /// Where the simulated plant starts the knife's origin [x, y, z], m.
    pub start_position: [f64; 3],
}

impl From<&CutSetup> for ShearcutTask {
    fn from(setup: &CutSetup) -> Self {
        let task = setup.task();
        let start = setup.cut().start;
        Self {
            period: task.period,
            target_depth: task.target_depth,
            touch_height: task.outline.touch_height(start.z).unwrap_or(f64::NAN),
            blade_budget: task.blade_budget,
            normal_speed_limit: task.limits.normal_speed,
            tangential_speed_limit: task.limits.tangential_speed,
            acceleration_limit: task.limits.acceleration,
            jerk_limit: task.limits.jerk,
            max_ticks: setup.max_ticks(),
            start_position: start.into(),
        }
    }
}
