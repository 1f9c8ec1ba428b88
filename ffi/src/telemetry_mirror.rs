//! `#[repr(C)]` mirror of what a controller planned in its last tick
//! (`shearcut_controllers::controller::ControllerTelemetry`).

use shearcut_controllers::controller::{ControllerTelemetry, CutPhase};

/// `ShearcutTelemetry::phase`: moving towards the target depth.
pub const SHEARCUT_PHASE_CUTTING: u32 = 0;
/// `ShearcutTelemetry::phase`: the target depth is reached; the knife is
/// brought to rest.
pub const SHEARCUT_PHASE_DONE: u32 = 1;

/// What the controller's last tick planned, for logs and plots.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ShearcutTelemetry {
    /// Planned slice-push ratio ξ = v_t / v_n (seed 000 §III).
    pub slice_push_ratio: f64,
    /// Planned normal speed v_n (down into the object), m/s.
    pub normal_speed: f64,
    /// Planned tangential speed v_t (towards the tip), m/s.
    pub tangential_speed: f64,
    /// Tangential blade travel used so far, m.
    pub blade_travel: f64,
    /// `SHEARCUT_PHASE_CUTTING` or `SHEARCUT_PHASE_DONE`.
    pub phase: u32,
    /// Whether this tick took up a new plan (the MPC; statistics only).
    pub planned: bool,
    /// Plans so far that fell back to the previous plan.
    pub fallbacks: u64,
    /// The material scale factors the controller believes [toughness,
    /// stiffness, friction] (1 for controllers without a model).
    pub scale: [f64; 3],
}

impl From<&ControllerTelemetry> for ShearcutTelemetry {
    #[inline]
    fn from(t: &ControllerTelemetry) -> Self {
        Self {
            slice_push_ratio: t.slice_push_ratio,
            normal_speed: t.normal_speed,
            tangential_speed: t.tangential_speed,
            blade_travel: t.blade_travel,
            phase: match t.phase {
                CutPhase::Cutting => SHEARCUT_PHASE_CUTTING,
                CutPhase::Done => SHEARCUT_PHASE_DONE,
            },
            planned: t.planned,
            fallbacks: t.fallbacks,
            scale: t.scale,
        }
    }
}
