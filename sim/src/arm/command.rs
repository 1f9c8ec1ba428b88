//! The command an arm accepts each servo tick.

use nalgebra::Vector3;

/// A knife motion command: a Cartesian twist (translation only).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct KnifeCommand {
    /// Knife velocity in the world frame, m/s (the x component must be 0:
    /// the knife moves in its own plane).
    pub velocity: Vector3<f64>,
}
