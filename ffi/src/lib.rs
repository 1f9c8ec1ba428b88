//! shearcut's C ABI: the knife controller and the simulated plant for
//! loops written in C, C++ or any language with a C FFI
//! (`include/shearcut.h`, generated from this crate by cbindgen;
//! `include/shearcut.hpp`, a header-only C++ wrapper; docs/embedding.md).
//!
//! ## The surface
//! - `shearcut_version`, `shearcut_last_error`;
//! - `shearcut_setup_new/task/free`: a scenario (file or built-in name) set
//!   up for a controller choice;
//! - `shearcut_controller_new/tick/telemetry/name/reset/free`;
//! - `shearcut_plant_new/step/reset/free`: the simulated plant, so a
//!   foreign loop closes the loop in simulation first.
//!
//! ## Contract at the boundary
//! Every fallible entry point returns a [`ShearcutStatus`]; on failure the
//! outputs are untouched and `shearcut_last_error()` says why (thread
//! local). No panic crosses the boundary: each entry point runs inside
//! `catch_unwind`, a caught panic returns `SHEARCUT_STATUS_PANIC` and
//! poisons the handle until it is reset. Null pointers are refused with
//! `SHEARCUT_STATUS_NULL_ARGUMENT`, unknown status codes in a reading with
//! `SHEARCUT_STATUS_INVALID_ARGUMENT`.
//!
//! ## Same numbers as the Rust loop
//! [`CutSetup`] builds the controller and the plant exactly as `shearcut
//! run --transport inproc` does, and the `#[repr(C)]` mirrors copy every
//! number bit for bit. A foreign loop that follows the same lockstep
//! (first command: the arm at rest; then reading → tick → command → step)
//! reproduces the Rust run's work and forces bit for bit
//! (`ffi/tests/cpp_loops.rs`).
//!
//! This is the one crate of the workspace that allows `unsafe`: the entry
//! points dereference the caller's pointers. The safe core
//! ([`CutSetup`], [`SimulatedPlant`]) serves the Python package too.

mod arm_mirror;
mod boundary;
mod controller_api;
mod cut_setup;
mod last_error;
mod plant_api;
mod setup_api;
mod simulated_plant;
mod status;
mod task_mirror;
mod telemetry_mirror;
mod truth_mirror;

use std::ffi::c_char;

pub use arm_mirror::{
    SHEARCUT_ARM_ACCELERATION_LIMIT, SHEARCUT_ARM_JERK_LIMIT, SHEARCUT_ARM_MOVING,
    SHEARCUT_ARM_NOT_FINITE, SHEARCUT_ARM_VELOCITY_LIMIT, ShearcutCommand, ShearcutReading,
};
pub use controller_api::{
    ShearcutController, shearcut_controller_free, shearcut_controller_name,
    shearcut_controller_new, shearcut_controller_reset, shearcut_controller_telemetry,
    shearcut_controller_tick,
};
pub use cut_setup::{CutSetup, EmbedError};
pub use last_error::shearcut_last_error;
pub use plant_api::{
    ShearcutPlant, shearcut_plant_free, shearcut_plant_new, shearcut_plant_reset,
    shearcut_plant_step,
};
pub use setup_api::{ShearcutSetup, shearcut_setup_free, shearcut_setup_new, shearcut_setup_task};
pub use simulated_plant::SimulatedPlant;
pub use status::ShearcutStatus;
pub use task_mirror::ShearcutTask;
pub use telemetry_mirror::{SHEARCUT_PHASE_CUTTING, SHEARCUT_PHASE_DONE, ShearcutTelemetry};
pub use truth_mirror::ShearcutTruth;

/// The library's version, `"MAJOR.MINOR.PATCH"` (static, never freed).
#[unsafe(no_mangle)]
pub extern "C" fn shearcut_version() -> *const c_char {
    concat!(env!("CARGO_PKG_VERSION"), "\0").as_ptr().cast()
}
