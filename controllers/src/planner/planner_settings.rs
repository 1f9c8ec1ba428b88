//! `[controller.planner]`: how plans reach the servo tick.

use serde::{Deserialize, Serialize};
use shearcut_sim::InvalidSetting;

use super::{LatencyPolicy, MAX_LOCKSTEP_TICKS};

/// The latency policy by name, as written in config.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum LatencyMode {
    /// [`LatencyPolicy::Lockstep`] with `lockstep_ticks`.
    #[default]
    Lockstep,
    /// [`LatencyPolicy::Realtime`].
    Realtime,
    /// [`LatencyPolicy::Inline`].
    Inline,
}

/// Settings of a [`super::Planner`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct PlannerSettings {
    /// `"lockstep"` | `"realtime"` | `"inline"` (default `"lockstep"`):
    /// plans visible a fixed number of ticks after their request
    /// (deterministic), as soon as they are ready (a real arm's loop), or
    /// at once, planned on the tick.
    pub latency: LatencyMode,
    /// Plan latency under `"lockstep"`, servo ticks (default 1, in
    /// 1..=10000): the plan for the request of tick t is used from tick
    /// t + `lockstep_ticks`. Ignored by the other modes.
    pub lockstep_ticks: u32,
}

impl Default for PlannerSettings {
    fn default() -> Self {
        Self {
            latency: LatencyMode::Lockstep,
            lockstep_ticks: 1,
        }
    }
}

impl PlannerSettings {
    /// The policy these settings name, after checking every value.
    pub fn policy(&self) -> Result<LatencyPolicy, InvalidSetting> {
        let policy = match self.latency {
            LatencyMode::Lockstep => LatencyPolicy::Lockstep {
                ticks: self.lockstep_ticks,
            },
            LatencyMode::Realtime => LatencyPolicy::Realtime,
            LatencyMode::Inline => LatencyPolicy::Inline,
        };
        validate(policy)?;
        Ok(policy)
    }
}

/// Checks a policy's latency range, naming the settings key.
pub(super) fn validate(policy: LatencyPolicy) -> Result<(), InvalidSetting> {
    match policy {
        LatencyPolicy::Lockstep { ticks } if !(1..=MAX_LOCKSTEP_TICKS).contains(&ticks) => {
            Err(InvalidSetting::new(
                "lockstep_ticks",
                ticks,
                format!("in 1..={MAX_LOCKSTEP_TICKS}"),
            ))
        }
        _ => Ok(()),
    }
}
