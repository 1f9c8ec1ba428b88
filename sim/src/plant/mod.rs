//! The plant: a whole knife cutting a whole object (seed 000 §IV–V), driven
//! tick by tick like a robot arm, reporting what an F/T sensor would read.
//!
//! Files: `crack_front` (the quadratic crack front fitted over the sections'
//! crack tips), `wrench` (section forces summed into force and torque at the
//! sensor), `ft_sensor`
//! (noise, bias and sample rate of the F/T signal), `successor` (successor
//! sections built ahead of their re-choices on a worker thread).

pub mod contact_arc;
pub mod crack_front;
pub mod ft_sensor;
#[allow(clippy::module_inception)]
pub mod plant;
pub mod section_shape;
mod successor;
pub mod wrench;

pub use crate::arm::{ArmLimitMonitor, ArmLimits, KnifeCommand, LimitViolation};
pub use contact_arc::{EdgeSegment, contact_arc, knife_plane_silhouette, segments};
pub use crack_front::CrackFront;
pub use ft_sensor::{FtSensor, FtSensorSettings};
pub use plant::{Measurement, Plant, PlantError, PlantSettings, PlantStatus};
pub use wrench::{SegmentLoad, Wrench, wrench_at};
