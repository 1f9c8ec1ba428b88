//! The arm's side of the servo loop: the command a robot arm accepts, the
//! reading it reports each tick, and its limit reflexes.
//!
//! This is everything a knife controller may see of the world while it
//! cuts: time, the knife's pose and executed twist, the wrist force/torque
//! sensor's wrench as the sensor reports it (noisy, biased), and the arm's
//! status. What only a simulation knows (crack depth, contact length,
//! fractured sections, work, deformation, the noise-free wrench) is the
//! plant's truth and lives in the `shearcut-plant` crate, which no
//! controller depends on.

mod command;
pub mod limits;
mod reading;

pub use command::KnifeCommand;
pub use limits::{ArmLimitMonitor, ArmLimits, LimitViolation};
pub use reading::{ArmReading, ArmStatus};
