//! The native module `shearcut._shearcut` of the Python package `shearcut`
//! (python/shearcut, docs/embedding.md): the scenario set up for a
//! controller, the simulated plant, the controller, and `run`, the Rust
//! closed loop with its time series as NumPy arrays.
//!
//! Built by maturin with the `python` feature; without it (the workspace's
//! own `cargo build/test/clippy`) the library is empty and needs no Python.
#![cfg(feature = "python")]

mod arm_types;
mod closed_loop_run;
mod controller;
mod errors;
mod plant;
mod scenario;
mod telemetry;
mod truth;

use pyo3::prelude::*;

/// shearcut's controller and simulated plant (native part).
#[pymodule]
fn _shearcut(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_class::<scenario::Scenario>()?;
    m.add_class::<arm_types::Reading>()?;
    m.add_class::<arm_types::Command>()?;
    m.add_class::<truth::Truth>()?;
    m.add_class::<telemetry::Telemetry>()?;
    m.add_class::<plant::Plant>()?;
    m.add_class::<controller::Controller>()?;
    m.add_function(wrap_pyfunction!(closed_loop_run::run, m)?)?;
    Ok(())
}
