//! What the controller did each tick, and how long its ticks took.

use serde::Serialize;
use shearcut_controllers::controller::{ControllerTelemetry, CutPhase};
use shearcut_sim::arm::KnifeCommand;

/// One tick of the controller (`controller.csv`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ControlSample {
    /// Time of the reading the controller answered, s.
    pub time_s: f64,
    /// Planned slice-push ratio ξ = v_t / v_n.
    pub xi_plan: f64,
    /// Planned normal speed (down), m/s.
    pub normal_speed_plan_m_s: f64,
    /// Planned tangential speed (towards the tip), m/s.
    pub tangential_speed_plan_m_s: f64,
    /// Commanded knife velocity, y component (up), m/s.
    pub command_vy_m_s: f64,
    /// Commanded knife velocity, z component (towards the tip), m/s.
    pub command_vz_m_s: f64,
    /// Tangential blade travel used, m.
    pub blade_travel_m: f64,
    /// Whether the controller considers the cut done.
    pub phase: CutPhase,
    /// Estimated toughness factor (R_c multiplier; 1 without an estimator).
    pub scale_toughness: f64,
    /// Estimated stiffness factor (E multiplier).
    pub scale_stiffness: f64,
    /// Estimated friction factor (μ multiplier).
    pub scale_friction: f64,
}

impl ControlSample {
    /// The record of a tick at `time` that planned `t` and commanded `c`.
    pub fn new(time: f64, t: &ControllerTelemetry, c: &KnifeCommand) -> Self {
        Self {
            time_s: time,
            xi_plan: t.slice_push_ratio,
            normal_speed_plan_m_s: t.normal_speed,
            tangential_speed_plan_m_s: t.tangential_speed,
            command_vy_m_s: c.velocity.y,
            command_vz_m_s: c.velocity.z,
            blade_travel_m: t.blade_travel,
            phase: t.phase,
            scale_toughness: t.scale[0],
            scale_stiffness: t.scale[1],
            scale_friction: t.scale[2],
        }
    }
}

/// Wall-clock durations of the controller's ticks (statistics only; never
/// part of the deterministic time series).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TickTimes {
    /// Median, µs.
    pub median_us: f64,
    /// 99th percentile, µs.
    pub p99_us: f64,
    /// Largest, µs.
    pub max_us: f64,
}

impl TickTimes {
    /// Statistics of `durations_us` (sorted in place); zeros when empty.
    pub fn from_durations(durations_us: &mut [f64]) -> Self {
        if durations_us.is_empty() {
            return Self {
                median_us: 0.0,
                p99_us: 0.0,
                max_us: 0.0,
            };
        }
        durations_us.sort_by(f64::total_cmp);
        let at = |q: f64| {
            let i = ((durations_us.len() - 1) as f64 * q).round() as usize;
            durations_us[i]
        };
        Self {
            median_us: at(0.5),
            p99_us: at(0.99),
            max_us: durations_us[durations_us.len() - 1],
        }
    }
}
