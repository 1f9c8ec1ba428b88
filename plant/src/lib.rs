//! The plant: a whole knife cutting a whole object (seed 000 §IV–V), driven
//! tick by tick like a robot arm, reporting what an F/T sensor would read.
//!
//! Files: `plant` (the plant and its tick), with `plant/segment_section` (a
//! segment of the edge with its section and plane), `plant/placement` (the
//! first sections placed where the edge arrives) and `plant/rechoice` (the
//! moving sections re-chosen as their segments slide off their planes);
//! `plant_settings`, `plant_spec` (what a plant is built from), `plant_error`,
//! `plant_step` (what a tick returns), `crack_front` (the quadratic crack front fitted over the sections'
//! crack tips), `wrench` (section forces summed into force and torque at the
//! sensor), `ft_sensor`
//! (noise, bias and sample rate of the F/T signal), `successor` (successor
//! sections built ahead of their re-choices on a worker thread), `tick_list`
//! (the lists a tick fills, allocated once for their most entries).

pub mod crack_front;
pub mod ft_sensor;
#[allow(clippy::module_inception)]
pub mod plant;
mod plant_error;
mod plant_settings;
mod plant_spec;
mod plant_step;
mod section_stepper;
mod successor;
mod successor_policy;
mod tick_list;
pub mod wrench;

pub use crack_front::CrackFront;
pub use ft_sensor::{FtSensor, FtSensorSettings};
pub use plant::Plant;
pub use plant_error::PlantError;
pub use plant_settings::{MAX_SEGMENTS, PlantSettings};
pub use plant_spec::PlantSpec;
pub use plant_step::{PlantStep, PlantTruth};
pub use shearcut_sim::arm::{ArmLimitMonitor, ArmLimits, KnifeCommand, LimitViolation};
pub use shearcut_sim::arm::{ArmReading, ArmStatus};
pub use shearcut_sim::knife_plane::{EdgeSegment, contact_arc, knife_plane_silhouette, segments};
pub use successor_policy::SuccessorPolicy;
pub use wrench::{SegmentLoad, Wrench, wrench_at};
