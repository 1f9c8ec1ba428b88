//! Baseline: slicing at a constant slice-push ratio and speed.

use shearcut_sim::InvalidSetting;
use shearcut_sim::arm::{ArmReading, ArmStatus, KnifeCommand};

use super::blade_budget::BladeBudget;
use super::cut_task::CutTask;
use super::velocity_shaper::VelocityShaper;
use super::{Controller, ControllerTelemetry};

/// Moves the knife at a constant slice-push ratio ξ and speed until the
/// target depth (seed 000 §V's prescribed motions, closed only on the depth):
/// v_n = s/√(1+ξ²), v_t = ξ·v_n for a speed s along the velocity. ξ = 0 is
/// pressing.
///
/// When the remaining blade would not let the knife stop in time, the
/// tangential speed drops to 0 and the cut finishes by pressing: the contact
/// arc never leaves the edge.
#[derive(Debug, Clone)]
pub struct ConstantSlice {
    name: String,
    task: CutTask,
    normal_speed: f64,
    tangential_speed: f64,
    budget: BladeBudget,
    shaper: VelocityShaper,
    telemetry: ControllerTelemetry,
}

impl ConstantSlice {
    /// Slicing at `slice_push_ratio` (≥ 0) with knife speed `speed` (m/s,
    /// along the velocity), both capped by the task's speed limits.
    ///
    /// # Errors
    /// A non-finite or negative ratio or speed, or an invalid task.
    pub fn new(task: &CutTask, slice_push_ratio: f64, speed: f64) -> Result<Self, InvalidSetting> {
        task.validate()?;
        if !(slice_push_ratio.is_finite() && slice_push_ratio >= 0.0) {
            return Err(InvalidSetting::new(
                "slice_push_ratio",
                slice_push_ratio,
                "a finite ratio >= 0",
            ));
        }
        if !(speed.is_finite() && speed > 0.0) {
            return Err(InvalidSetting::new(
                "speed",
                speed,
                "a finite speed > 0 m/s",
            ));
        }
        let normal_speed = task.limits.normal_speed_for(speed, slice_push_ratio);
        let shaper = VelocityShaper::for_task(task)?;
        Ok(Self {
            name: if slice_push_ratio == 0.0 {
                "press".to_string()
            } else {
                format!("slice:{slice_push_ratio}")
            },
            task: task.clone(),
            normal_speed,
            tangential_speed: slice_push_ratio * normal_speed,
            budget: BladeBudget::new(task.blade_budget),
            shaper,
            telemetry: ControllerTelemetry::default(),
        })
    }

    /// Pressing (ξ = 0) at `speed` m/s.
    ///
    /// # Errors
    /// See [`ConstantSlice::new`].
    pub fn press(task: &CutTask, speed: f64) -> Result<Self, InvalidSetting> {
        Self::new(task, 0.0, speed)
    }
}

impl Controller for ConstantSlice {
    fn name(&self) -> &str {
        &self.name
    }

    fn tick(&mut self, m: &ArmReading) -> KnifeCommand {
        if matches!(m.status, ArmStatus::LimitViolation(_)) {
            self.shaper.resync(&m.velocity);
        }
        self.budget.observe(m);
        let l = &self.task.limits;
        let done = self.task.reached(self.task.edge_depth(&m.position));
        let (v_n, v_t) = if done {
            (0.0, 0.0)
        } else {
            let v_t = self
                .budget
                .allowed_speed(self.tangential_speed, l.acceleration, l.jerk);
            (self.normal_speed, v_t)
        };
        self.telemetry = ControllerTelemetry::moving(v_n, v_t, self.budget.used(), done);
        self.shaper.command(v_n, v_t)
    }

    fn telemetry(&self) -> ControllerTelemetry {
        self.telemetry
    }
}
