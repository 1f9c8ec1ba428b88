//! Baseline: a PI loop that holds the vertical force at a setpoint.

use serde::{Deserialize, Serialize};
use shearcut_sim::InvalidSetting;
use shearcut_sim::arm::{ArmReading, ArmStatus, KnifeCommand};

use super::blade_budget::BladeBudget;
use super::cut_task::CutTask;
use super::velocity_shaper::VelocityShaper;
use super::{Controller, ControllerTelemetry};

/// Gains of [`ForceFeedback`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ForceFeedbackGains {
    /// Proportional gain, (m/s)/N: normal speed per newton of force below
    /// the setpoint.
    pub proportional: f64,
    /// Integral gain, (m/s)/(N·s).
    pub integral: f64,
}

impl ForceFeedbackGains {
    /// Gains scaled to a setpoint: full `speed` at zero force from the
    /// proportional term (k_p = speed / setpoint) and an integral time of
    /// 2 s (k_i = k_p / 2 s). Before it fractures the material is close to a
    /// spring in depth (F = k·d), an integrating plant for a speed command:
    /// the loop s² + k·k_p·s + k·k_i is critically damped or better when
    /// k·k_p·T_i ≥ 4, i.e. for any stiffness above 2·setpoint/speed.
    pub fn for_setpoint(setpoint: f64, speed: f64) -> Self {
        let proportional = speed / setpoint;
        Self {
            proportional,
            integral: proportional / 2.0,
        }
    }
}

/// Relative distance from the setpoint within which the integral runs.
pub const INTEGRAL_BAND: f64 = 0.1;

/// Holds the measured vertical force (the F/T sensor's f_y, object on knife)
/// at a setpoint by commanding the normal speed, at a constant slice-push
/// ratio ξ (default 0: pressing), until the target depth:
///
/// v_n = clamp(k_p·e + k_i·∫e dt, −v_max, v_max),   e = F* − F_y,
/// v_t = ξ·max(v_n, 0).
///
/// Above the setpoint the knife backs off (v_n < 0, no tangential motion),
/// as an arm's force loop does. The integral runs only within
/// [`INTEGRAL_BAND`] of the setpoint (integral separation: far from it the
/// proportional term moves the knife, and an integral charged during the
/// approach would only overshoot), and stops while the output is saturated
/// and the error would push it further (no wind-up). The material is rate
/// independent in the model, so once the knife cuts steadily the force is
/// set by the material, not the speed: the loop then only limits force peaks
/// and otherwise runs at v_max. The blade budget is kept as
/// [`super::ConstantSlice`] keeps it.
#[derive(Debug, Clone)]
pub struct ForceFeedback {
    name: String,
    task: CutTask,
    setpoint: f64,
    gains: ForceFeedbackGains,
    slice_push_ratio: f64,
    max_normal_speed: f64,
    integral: f64,
    budget: BladeBudget,
    shaper: VelocityShaper,
    telemetry: ControllerTelemetry,
}

impl ForceFeedback {
    /// A force loop at `setpoint` N with `gains`, slicing at
    /// `slice_push_ratio`, never faster than `max_speed` m/s along the
    /// knife's velocity (and the task's limits).
    ///
    /// # Errors
    /// A non-finite or non-positive setpoint, gain or speed, a negative
    /// ratio, or an invalid task.
    pub fn new(
        task: &CutTask,
        setpoint: f64,
        gains: ForceFeedbackGains,
        slice_push_ratio: f64,
        max_speed: f64,
    ) -> Result<Self, InvalidSetting> {
        task.validate()?;
        for (key, value) in [
            ("force_setpoint", setpoint),
            ("gains.proportional", gains.proportional),
            ("speed", max_speed),
        ] {
            if !(value.is_finite() && value > 0.0) {
                return Err(InvalidSetting::new(key, value, "a finite number > 0"));
            }
        }
        if !(gains.integral.is_finite() && gains.integral >= 0.0) {
            return Err(InvalidSetting::new(
                "gains.integral",
                gains.integral,
                "a finite number >= 0",
            ));
        }
        if !(slice_push_ratio.is_finite() && slice_push_ratio >= 0.0) {
            return Err(InvalidSetting::new(
                "slice_push_ratio",
                slice_push_ratio,
                "a finite ratio >= 0",
            ));
        }
        let max_normal_speed = task.limits.normal_speed_for(max_speed, slice_push_ratio);
        let shaper = VelocityShaper::for_task(task)?;
        Ok(Self {
            name: format!("force:{setpoint}"),
            task: task.clone(),
            setpoint,
            gains,
            slice_push_ratio,
            max_normal_speed,
            integral: 0.0,
            budget: BladeBudget::new(task.blade_budget),
            shaper,
            telemetry: ControllerTelemetry::default(),
        })
    }
}

impl Controller for ForceFeedback {
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
            let force = if m.wrench[1].is_finite() {
                m.wrench[1]
            } else {
                self.setpoint
            };
            let error = self.setpoint - force;
            let unclamped = self.gains.proportional * error + self.gains.integral * self.integral;
            let v_max = self.max_normal_speed;
            let v_n = unclamped.clamp(-v_max, v_max);
            let saturated_high = unclamped >= v_max && error > 0.0;
            let saturated_low = unclamped <= -v_max && error < 0.0;
            if !(saturated_high || saturated_low) && error.abs() <= INTEGRAL_BAND * self.setpoint {
                self.integral += error * self.task.period;
            }
            let v_t =
                self.budget
                    .allowed_speed(self.slice_push_ratio * v_n, l.acceleration, l.jerk);
            (v_n, v_t)
        };
        self.telemetry = ControllerTelemetry::moving(v_n, v_t, self.budget.used(), done);
        self.shaper.command(v_n, v_t)
    }

    fn telemetry(&self) -> ControllerTelemetry {
        self.telemetry
    }
}
