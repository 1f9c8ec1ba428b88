//! Input, settings, statuses and errors of the trajectory generator.

use serde::{Deserialize, Serialize};

use super::brake::Limits;
use super::dof::Dof;

/// What the target prescribes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ControlInterface {
    /// Reach the target position, velocity and acceleration (default).
    #[default]
    Position,
    /// Reach the target velocity and acceleration; the position is free and velocity limits are
    /// not enforced (only acceleration and jerk limits).
    Velocity,
}

/// How the DoFs are coordinated.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Synchronization {
    /// All DoFs finish at the same time: the minimal common duration, outside every DoF's
    /// blocked intervals (default).
    #[default]
    Time,
    /// Straight-line motion (every DoF a scaled copy of one scalar profile) when start and target
    /// are collinear; otherwise falls back to [`Synchronization::Time`].
    Phase,
    /// Every DoF moves time-optimally on its own.
    None,
}

/// Whether the common duration is rounded up to whole control cycles.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum DurationDiscretization {
    /// Any duration (default).
    #[default]
    Continuous,
    /// The duration is a whole multiple of [`TrajectorySettings::cycle_time`].
    Discrete,
}

/// Settings of a [`super::TrajectoryGenerator`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct TrajectorySettings {
    /// Control cycle of [`super::TrajectoryGenerator::update`] in seconds (default: 0.001, the
    /// 1 kHz servo rate of an arm).
    pub cycle_time: f64,
}

impl TrajectorySettings {
    /// Default control cycle (s).
    pub const DEFAULT_CYCLE_TIME: f64 = 0.001;

    /// Sets the control cycle (s).
    #[must_use]
    pub fn with_cycle_time(mut self, cycle_time: f64) -> Self {
        self.cycle_time = cycle_time;
        self
    }

    /// Checks the settings, naming the offending key.
    pub fn validate(&self) -> Result<(), TrajectoryError> {
        if !(self.cycle_time.is_finite() && self.cycle_time > 0.0) {
            return Err(TrajectoryError::InvalidSetting {
                key: "cycle_time",
                reason: "must be finite and > 0",
            });
        }
        Ok(())
    }
}

impl Default for TrajectorySettings {
    fn default() -> Self {
        Self {
            cycle_time: Self::DEFAULT_CYCLE_TIME,
        }
    }
}

/// One calculation request for `N` degrees of freedom, with ruckig's field names.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TrajectoryInput<const N: usize> {
    /// Position or velocity interface (default: position).
    pub interface: ControlInterface,
    /// DoF coordination (default: time).
    pub synchronization: Synchronization,
    /// Rounding of the duration to control cycles (default: continuous).
    pub duration_discretization: DurationDiscretization,
    /// Current position of each DoF (m or rad).
    pub current_position: [f64; N],
    /// Current velocity (m/s or rad/s).
    pub current_velocity: [f64; N],
    /// Current acceleration (m/s² or rad/s²).
    pub current_acceleration: [f64; N],
    /// Target position (ignored by the velocity interface).
    pub target_position: [f64; N],
    /// Target velocity.
    pub target_velocity: [f64; N],
    /// Target acceleration.
    pub target_acceleration: [f64; N],
    /// Velocity limit, ≥ 0 (default 1).
    pub max_velocity: [f64; N],
    /// Acceleration limit, ≥ 0 (default 1).
    pub max_acceleration: [f64; N],
    /// Jerk limit, ≥ 0 (default 1).
    pub max_jerk: [f64; N],
    /// Lower velocity limit, ≤ 0 (default: `−max_velocity`).
    pub min_velocity: Option<[f64; N]>,
    /// Lower acceleration limit, ≤ 0 (default: `−max_acceleration`).
    pub min_acceleration: Option<[f64; N]>,
}

impl<const N: usize> Default for TrajectoryInput<N> {
    fn default() -> Self {
        Self {
            interface: ControlInterface::Position,
            synchronization: Synchronization::Time,
            duration_discretization: DurationDiscretization::Continuous,
            current_position: [0.0; N],
            current_velocity: [0.0; N],
            current_acceleration: [0.0; N],
            target_position: [0.0; N],
            target_velocity: [0.0; N],
            target_acceleration: [0.0; N],
            max_velocity: [1.0; N],
            max_acceleration: [1.0; N],
            max_jerk: [1.0; N],
            min_velocity: None,
            min_acceleration: None,
        }
    }
}

impl<const N: usize> TrajectoryInput<N> {
    /// The one-DoF problem of DoF `i` from the start state `(p0, v0, a0)`
    /// (the current one, or the end of a braking prefix) to its target,
    /// under the limits `l`.
    pub(crate) fn dof_from(&self, i: usize, (p0, v0, a0): (f64, f64, f64), l: &Limits) -> Dof {
        Dof {
            p0,
            v0,
            a0,
            pf: self.target_position[i],
            vf: self.target_velocity[i],
            af: self.target_acceleration[i],
            v_max: l.v_max,
            v_min: l.v_min,
            a_max: l.a_max,
            a_min: l.a_min,
            j: l.j,
        }
    }

    /// The one-DoF problem of DoF `i` from its current state to its target,
    /// under the limits `l`.
    pub(crate) fn current_dof(&self, i: usize, l: &Limits) -> Dof {
        let start = (
            self.current_position[i],
            self.current_velocity[i],
            self.current_acceleration[i],
        );
        self.dof_from(i, start, l)
    }

    /// The solver limits of DoF `i`.
    pub(crate) fn limits(&self, i: usize) -> Limits {
        Limits {
            v_max: self.max_velocity[i],
            v_min: self.min_velocity.map_or(-self.max_velocity[i], |m| m[i]),
            a_max: self.max_acceleration[i],
            a_min: self
                .min_acceleration
                .map_or(-self.max_acceleration[i], |m| m[i]),
            j: self.max_jerk[i],
        }
    }

    /// Checks finiteness, signs of the limits and reachability of the target state.
    pub fn validate(&self) -> Result<(), TrajectoryError> {
        for dof in 0..N {
            // One branch-free test for the common case; the field is named only on failure.
            if !self
                .finite_fields(dof)
                .iter()
                .fold(true, |ok, (_, x)| ok & x.is_finite())
            {
                self.first_non_finite(dof)?;
            }
            self.validate_limits_and_target(dof)?;
        }
        Ok(())
    }

    /// The state and limit fields of DoF `dof` that must be finite, with their names.
    #[inline(always)]
    fn finite_fields(&self, dof: usize) -> [(&'static str, f64); 9] {
        [
            ("current_position", self.current_position[dof]),
            ("current_velocity", self.current_velocity[dof]),
            ("current_acceleration", self.current_acceleration[dof]),
            ("target_position", self.target_position[dof]),
            ("target_velocity", self.target_velocity[dof]),
            ("target_acceleration", self.target_acceleration[dof]),
            ("max_velocity", self.max_velocity[dof]),
            ("max_acceleration", self.max_acceleration[dof]),
            ("max_jerk", self.max_jerk[dof]),
        ]
    }

    /// The error naming the first non-finite state or limit field of DoF `dof`, if any.
    fn first_non_finite(&self, dof: usize) -> Result<(), TrajectoryError> {
        for (field, x) in self.finite_fields(dof) {
            if !x.is_finite() {
                return Err(TrajectoryError::NonFinite { dof, field });
            }
        }
        Ok(())
    }

    /// Signs of the limits and reachability of the target state of DoF `dof` (whose fields
    /// are finite).
    fn validate_limits_and_target(&self, dof: usize) -> Result<(), TrajectoryError> {
        let l = self.limits(dof);
        let checks: [(&'static str, f64, bool); 5] = [
            ("max_velocity", l.v_max, l.v_max >= 0.0),
            ("max_acceleration", l.a_max, l.a_max >= 0.0),
            ("max_jerk", l.j, l.j >= 0.0),
            ("min_velocity", l.v_min, l.v_min <= 0.0),
            ("min_acceleration", l.a_min, l.a_min <= 0.0),
        ];
        for (field, x, ok) in checks {
            if !x.is_finite() {
                return Err(TrajectoryError::NonFinite { dof, field });
            }
            if !ok {
                return Err(TrajectoryError::InvalidLimit { dof, field });
            }
        }
        let (vf, af) = (self.target_velocity[dof], self.target_acceleration[dof]);
        let tol = |x: f64| 1e-12 * x.abs().max(1.0);
        if af > l.a_max + tol(l.a_max) || af < l.a_min - tol(l.a_min) {
            return Err(TrajectoryError::TargetOutsideLimits {
                dof,
                field: "target_acceleration",
            });
        }
        if self.interface == ControlInterface::Position {
            if vf > l.v_max + tol(l.v_max) || vf < l.v_min - tol(l.v_min) {
                return Err(TrajectoryError::TargetOutsideLimits {
                    dof,
                    field: "target_velocity",
                });
            }
            // The target must be reachable from within the limits: arriving with af > 0 means
            // the velocity rose by at least af²/(2J) just before.
            if l.j > 0.0 {
                let reach = af * af / (2.0 * l.j);
                if (af > 0.0 && vf - reach < l.v_min - tol(l.v_min))
                    || (af < 0.0 && vf + reach > l.v_max + tol(l.v_max))
                {
                    return Err(TrajectoryError::TargetOutsideLimits {
                        dof,
                        field: "target_acceleration",
                    });
                }
            }
        }
        Ok(())
    }
}

/// Outcome of a successful calculation or update.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum TrajectoryStatus {
    /// On the way to the target; every limit is respected.
    Working,
    /// The start state made a limit violation unavoidable (a limit already exceeded, or an
    /// acceleration too large to stop before exceeding a velocity limit). The trajectory begins
    /// with a time-optimal braking pre-phase that returns inside the limits, then goes to the
    /// target. Reported while the pre-phase runs (and by `calculate`).
    BrakingThenTarget,
    /// The target has been reached.
    Finished,
}

/// Errors of a calculation. `Copy`, no allocation.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
pub enum TrajectoryError {
    /// A state or limit is NaN or infinite.
    #[error("dof {dof}: {field} is not finite")]
    NonFinite {
        /// DoF index.
        dof: usize,
        /// Input field name.
        field: &'static str,
    },
    /// A limit has the wrong sign (max limits must be ≥ 0, min limits ≤ 0).
    #[error("dof {dof}: {field} has the wrong sign")]
    InvalidLimit {
        /// DoF index.
        dof: usize,
        /// Input field name.
        field: &'static str,
    },
    /// The target state cannot be reached within the limits.
    #[error("dof {dof}: {field} is outside the limits")]
    TargetOutsideLimits {
        /// DoF index.
        dof: usize,
        /// Input field name.
        field: &'static str,
    },
    /// No profile satisfies the limits (e.g. a zero limit while motion is required).
    #[error("dof {dof}: no trajectory satisfies the limits")]
    NoProfile {
        /// DoF index.
        dof: usize,
    },
    /// The DoFs could not be brought to a common duration.
    #[error("no common duration found for the synchronisation of dof {dof}")]
    Synchronization {
        /// The first DoF that could not be stretched.
        dof: usize,
    },
    /// A setting is invalid.
    #[error("setting {key}: {reason}")]
    InvalidSetting {
        /// Settings key.
        key: &'static str,
        /// What is wrong.
        reason: &'static str,
    },
}
