//! What an arm and its wrist force/torque sensor report each servo tick.

use nalgebra::Vector3;

use super::limits::LimitViolation;

/// The arm's own status after a tick.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ArmStatus {
    /// The command was executed.
    Moving,
    /// The command broke an arm limit and was refused: the knife holds still.
    LimitViolation(LimitViolation),
}

/// One servo tick's reading: only what a real arm with a wrist F/T sensor
/// reports (DESIGN §4, §5). World frame: origin on the cutting board, y up;
/// the knife moves in its own plane (y, z).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ArmReading {
    /// Time of the reading, s (the arm's clock).
    pub time: f64,
    /// Knife frame origin (heel end of the edge) in the world frame, m.
    pub position: Vector3<f64>,
    /// Knife velocity the arm executed over the last tick, m/s.
    pub velocity: Vector3<f64>,
    /// F/T sensor wrench [fx, fy, fz, tx, ty, tz] in the sensor frame, N and
    /// N·m: the force and torque the object exerts on the knife, as the
    /// sensor reports it (with its noise and bias).
    pub wrench: [f64; 6],
    /// The arm's status.
    pub status: ArmStatus,
}

impl ArmReading {
    /// The reading of an arm at rest at `position` (m) at `time` (s), with
    /// no load on the sensor.
    pub fn at_rest(time: f64, position: Vector3<f64>) -> Self {
        Self {
            time,
            position,
            velocity: Vector3::zeros(),
            wrench: [0.0; 6],
            status: ArmStatus::Moving,
        }
    }
}
