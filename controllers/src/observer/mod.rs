//! Observers of what an arm does not measure: from the arm's readings
//! ([`ArmReading`](shearcut_sim::arm::ArmReading): time, knife pose and
//! twist, the F/T sensor's wrench with its noise and bias) and what a lab
//! knows before the cut (the knife's edge, the object's outline in the
//! knife plane, the board at y = 0, the target), each infers one thing the
//! plant's ground truth would otherwise have to tell a controller:
//!
//! - [`WrenchTare`]: the sensor's bias and noise level, in free air;
//! - [`TouchDetector`]: when and where the edge touched ([`Touch`]);
//! - [`FractureDetector`]: the first fracture ([`FirstFracture`]);
//! - [`EdgeDepth`]: the edge's depth below the touch point;
//! - [`EdgeOutline`] and [`ContactLength`]: how much edge is in the object;
//! - [`CutDone`]: whether the edge has reached its [`CutTarget`];
//! - [`CutObserver`]: all of them, fed one reading per tick.
//!
//! Each is allocation-free after construction, costs a fixed amount per
//! reading, reads no clock (time is the readings') and is deterministic.
//! How close they come to the plant's truth over the shipped loop
//! scenarios is in `docs/observers.md`.

mod contact_length;
mod cut_done;
mod cut_observer;
mod edge_depth;
mod edge_outline;
mod first_fracture;
mod setting_range;
mod touch;
mod wrench_tare;

pub use contact_length::ContactLength;
pub use cut_done::{CutDone, CutTarget};
pub use cut_observer::{CutEstimate, CutObserver, CutObserverSettings};
pub use edge_depth::EdgeDepth;
pub use edge_outline::{ContactInclination, EdgeOutline, INCLINATION_BINS};
pub use first_fracture::{FirstFracture, FractureDetector, FractureSettings};
pub use touch::{TOUCH_HISTORY, Touch, TouchDetector, TouchSettings};
pub use wrench_tare::{WrenchTare, WrenchTareSettings};
