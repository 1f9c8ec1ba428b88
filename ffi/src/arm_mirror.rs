//! `#[repr(C)]` mirrors of the arm's side of the servo loop: the reading a
//! controller gets each tick and the command it answers with
//! (`shearcut_sim::arm::{ArmReading, KnifeCommand}`, docs/arm_interface.md).
//!
//! World frame: origin on the cutting board, y up; the knife moves in its
//! own plane (y, z), +z along the edge from the heel towards the tip. The
//! conversions are exact (every `f64` copied bit for bit), so a foreign
//! loop and the Rust loop see the same numbers.

use nalgebra::Vector3;
use shearcut_sim::arm::{ArmReading, ArmStatus, KnifeCommand, LimitViolation};

/// `ShearcutReading::status`: the arm executed the last command.
pub const SHEARCUT_ARM_MOVING: u32 = 0;
/// `ShearcutReading::status`: the last command was refused, its speed
/// `violation` (m/s) above the arm's limit; the knife holds still.
pub const SHEARCUT_ARM_VELOCITY_LIMIT: u32 = 1;
/// `ShearcutReading::status`: refused, the acceleration by finite
/// differences `violation` (m/s²) above the limit.
pub const SHEARCUT_ARM_ACCELERATION_LIMIT: u32 = 2;
/// `ShearcutReading::status`: refused, the jerk by finite differences
/// `violation` (m/s³) above the limit.
pub const SHEARCUT_ARM_JERK_LIMIT: u32 = 3;
/// `ShearcutReading::status`: refused, the command was not finite.
pub const SHEARCUT_ARM_NOT_FINITE: u32 = 4;

/// One servo tick's reading: only what a real arm with a wrist F/T sensor
/// reports.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ShearcutReading {
    /// Time of the reading, s (the arm's clock).
    pub time: f64,
    /// Knife frame origin (heel end of the edge) in the world frame
    /// [x, y, z], m.
    pub position: [f64; 3],
    /// Knife velocity the arm executed over the last tick [vx, vy, vz], m/s.
    pub velocity: [f64; 3],
    /// F/T sensor wrench [fx, fy, fz, tx, ty, tz] in the sensor frame, N
    /// and N·m: the force and torque the object exerts on the knife, as the
    /// sensor reports it (noise and bias included).
    pub wrench: [f64; 6],
    /// The arm's status: `SHEARCUT_ARM_MOVING` or the limit that refused
    /// the last command (`SHEARCUT_ARM_*`).
    pub status: u32,
    /// The refused command's value of the broken limit (m/s, m/s² or
    /// m/s³ by `status`); 0 while moving or for a non-finite command.
    pub violation: f64,
}

/// A knife motion command: a Cartesian twist, translation only.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ShearcutCommand {
    /// Knife velocity in the world frame [vx, vy, vz], m/s (vx is 0: the
    /// knife moves in its own plane).
    pub velocity: [f64; 3],
}

impl From<&ArmReading> for ShearcutReading {
    #[inline]
    fn from(r: &ArmReading) -> Self {
        let (status, violation) = match r.status {
            ArmStatus::Moving => (SHEARCUT_ARM_MOVING, 0.0),
            ArmStatus::LimitViolation(LimitViolation::Velocity(v)) => {
                (SHEARCUT_ARM_VELOCITY_LIMIT, v)
            }
            ArmStatus::LimitViolation(LimitViolation::Acceleration(a)) => {
                (SHEARCUT_ARM_ACCELERATION_LIMIT, a)
            }
            ArmStatus::LimitViolation(LimitViolation::Jerk(j)) => (SHEARCUT_ARM_JERK_LIMIT, j),
            ArmStatus::LimitViolation(LimitViolation::NotFinite) => (SHEARCUT_ARM_NOT_FINITE, 0.0),
        };
        Self {
            time: r.time,
            position: r.position.into(),
            velocity: r.velocity.into(),
            wrench: r.wrench,
            status,
            violation,
        }
    }
}

impl ShearcutReading {
    /// The reading as the controllers take it, or the unknown status code.
    #[inline]
    pub fn to_arm(&self) -> Result<ArmReading, u32> {
        let status = match self.status {
            SHEARCUT_ARM_MOVING => ArmStatus::Moving,
            SHEARCUT_ARM_VELOCITY_LIMIT => {
                ArmStatus::LimitViolation(LimitViolation::Velocity(self.violation))
            }
            SHEARCUT_ARM_ACCELERATION_LIMIT => {
                ArmStatus::LimitViolation(LimitViolation::Acceleration(self.violation))
            }
            SHEARCUT_ARM_JERK_LIMIT => {
                ArmStatus::LimitViolation(LimitViolation::Jerk(self.violation))
            }
            SHEARCUT_ARM_NOT_FINITE => ArmStatus::LimitViolation(LimitViolation::NotFinite),
            other => return Err(other),
        };
        Ok(ArmReading {
            time: self.time,
            position: Vector3::from(self.position),
            velocity: Vector3::from(self.velocity),
            wrench: self.wrench,
            status,
        })
    }
}

impl From<&KnifeCommand> for ShearcutCommand {
    #[inline]
    fn from(c: &KnifeCommand) -> Self {
        Self {
            velocity: c.velocity.into(),
        }
    }
}

impl From<&ShearcutCommand> for KnifeCommand {
    #[inline]
    fn from(c: &ShearcutCommand) -> Self {
        Self {
            velocity: Vector3::from(c.velocity),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn readings_cross_both_ways_bit_for_bit() {
        let statuses = [
            ArmStatus::Moving,
            ArmStatus::LimitViolation(LimitViolation::Velocity(3.25)),
            ArmStatus::LimitViolation(LimitViolation::Acceleration(-0.0)),
            ArmStatus::LimitViolation(LimitViolation::Jerk(6250.000000000001)),
            ArmStatus::LimitViolation(LimitViolation::NotFinite),
        ];
        for status in statuses {
            let r = ArmReading {
                time: 0.1 + 0.2,
                position: Vector3::new(0.0, 0.035_000_000_000_000_01, -1e-300),
                velocity: Vector3::new(0.0, -0.02, f64::MIN_POSITIVE),
                wrench: [1.0, -2.5, 1e-17, 0.3, -0.0, 7.0],
                status,
            };
            let back = ShearcutReading::from(&r).to_arm().unwrap();
            assert_eq!(back, r);
            assert_eq!(back.velocity.y.to_bits(), r.velocity.y.to_bits());
        }
    }

    #[test]
    fn an_unknown_status_code_is_refused() {
        let r = ShearcutReading {
            status: 9,
            ..ShearcutReading::default()
        };
        assert_eq!(r.to_arm(), Err(9));
    }
}
