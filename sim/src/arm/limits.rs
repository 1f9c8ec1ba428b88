//! An arm's reflexes: commanded motion checked by finite differences against
//! velocity, acceleration and jerk limits (libfranka checks 1 ms differences).

use nalgebra::Vector3;
use serde::{Deserialize, Serialize};

use crate::invalid_setting::{InvalidSetting, positive};

/// Cartesian translation limits of the arm (defaults: Franka FR3).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ArmLimits {
    /// Maximum speed, m/s (default 3.0).
    pub velocity: f64,
    /// Maximum acceleration, m/s² (default 9.0).
    pub acceleration: f64,
    /// Maximum jerk, m/s³ (default 4500).
    pub jerk: f64,
}

impl Default for ArmLimits {
    fn default() -> Self {
        Self {
            velocity: 3.0,
            acceleration: 9.0,
            jerk: 4500.0,
        }
    }
}

impl ArmLimits {
    /// Checks every limit is finite and positive.
    pub fn validate(&self) -> Result<(), InvalidSetting> {
        positive("velocity", self.velocity)?;
        positive("acceleration", self.acceleration)?;
        positive("jerk", self.jerk)
    }
}

/// Which limit a command broke, with the finite-difference value.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
pub enum LimitViolation {
    /// |v| above the velocity limit, m/s.
    #[error("velocity {0:.6} m/s exceeds the limit")]
    Velocity(f64),
    /// |Δv/Δt| above the acceleration limit, m/s².
    #[error("acceleration {0:.6} m/s^2 exceeds the limit")]
    Acceleration(f64),
    /// |Δa/Δt| above the jerk limit, m/s³.
    #[error("jerk {0:.6} m/s^3 exceeds the limit")]
    Jerk(f64),
    /// A non-finite command or a non-positive period.
    #[error("the command is not finite")]
    NotFinite,
}

/// Checks a stream of commanded velocities; remembers the last accepted
/// velocity and acceleration. A rejected command changes nothing (the arm
/// keeps its previous command). Starts at rest.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ArmLimitMonitor {
    limits: ArmLimits,
    velocity: Vector3<f64>,
    acceleration: Vector3<f64>,
}

/// Relative slack on the limits: commands computed to sit exactly on a limit
/// are accepted despite rounding.
const SLACK: f64 = 1e-9;

impl ArmLimitMonitor {
    /// A monitor at rest.
    pub fn new(limits: ArmLimits) -> Self {
        Self {
            limits,
            velocity: Vector3::zeros(),
            acceleration: Vector3::zeros(),
        }
    }

    /// The last accepted velocity, m/s.
    pub fn velocity(&self) -> Vector3<f64> {
        self.velocity
    }

    /// The acceleration of the last accepted step, m/s².
    pub fn acceleration(&self) -> Vector3<f64> {
        self.acceleration
    }

    /// Checks `velocity` commanded `dt` seconds after the previous one and,
    /// if within the limits, accepts it.
    pub fn check(&mut self, velocity: Vector3<f64>, dt: f64) -> Result<(), LimitViolation> {
        if !(dt.is_finite() && dt > 0.0 && velocity.iter().all(|v| v.is_finite())) {
            return Err(LimitViolation::NotFinite);
        }
        let l = &self.limits;
        let speed = velocity.norm();
        if speed > l.velocity * (1.0 + SLACK) {
            return Err(LimitViolation::Velocity(speed));
        }
        let acc = (velocity - self.velocity) / dt;
        if acc.norm() > l.acceleration * (1.0 + SLACK) {
            return Err(LimitViolation::Acceleration(acc.norm()));
        }
        let jerk = (acc - self.acceleration) / dt;
        if jerk.norm() > l.jerk * (1.0 + SLACK) {
            return Err(LimitViolation::Jerk(jerk.norm()));
        }
        self.velocity = velocity;
        self.acceleration = acc;
        Ok(())
    }

    /// Forget the history: the arm is at rest (after braking).
    pub fn reset(&mut self) {
        self.velocity = Vector3::zeros();
        self.acceleration = Vector3::zeros();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn step_to_cutting_speed_is_a_jerk_violation() {
        let mut m = ArmLimitMonitor::new(ArmLimits::default());
        // 0 → 6.25 mm/s in one 1 ms tick: a = 6.25 m/s² (< 9) but jerk 6250 m/s³ (> 4500).
        let e = m.check(Vector3::new(0.0, -0.00625, 0.0), 1e-3).unwrap_err();
        assert!(matches!(e, LimitViolation::Jerk(j) if (j - 6250.0).abs() < 1e-6));
        // A rejected command changes nothing.
        assert_eq!(m.velocity(), Vector3::zeros());
    }

    #[test]
    fn jerk_limited_ramp_is_accepted() {
        let mut m = ArmLimitMonitor::new(ArmLimits::default());
        let dt = 1e-3;
        // Jerk 4000 m/s³ for 2 ticks then −4000 for 2 ticks.
        let (mut v, mut a) = (0.0, 0.0);
        for k in 0..4 {
            let j = if k < 2 { 4000.0 } else { -4000.0 };
            a += j * dt;
            v += a * dt;
            m.check(Vector3::new(0.0, -v, 0.0), dt).unwrap();
        }
        assert!(m.acceleration().norm() < 1e-9);
    }

    #[test]
    fn speed_and_nan_are_refused() {
        let mut m = ArmLimitMonitor::new(ArmLimits {
            velocity: 0.001,
            acceleration: 1e9,
            jerk: 1e12,
        });
        assert!(matches!(
            m.check(Vector3::new(0.0, 0.002, 0.0), 1e-3),
            Err(LimitViolation::Velocity(_))
        ));
        assert_eq!(
            m.check(Vector3::new(f64::NAN, 0.0, 0.0), 1e-3),
            Err(LimitViolation::NotFinite)
        );
    }
}
