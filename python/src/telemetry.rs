//! `shearcut.Telemetry`: what the controller's last tick planned.

use pyo3::prelude::*;
use shearcut_ffi::{SHEARCUT_PHASE_DONE, ShearcutTelemetry};

/// What the controller's last tick planned, for logs and plots.
#[pyclass(module = "shearcut._shearcut", frozen)]
#[derive(Clone, Copy)]
pub(crate) struct Telemetry {
    pub(crate) inner: ShearcutTelemetry,
}

#[pymethods]
impl Telemetry {
    /// Planned slice-push ratio ξ = v_t / v_n.
    #[getter]
    fn slice_push_ratio(&self) -> f64 {
        self.inner.slice_push_ratio
    }

    /// Planned normal speed (down into the object), m/s.
    #[getter]
    fn normal_speed(&self) -> f64 {
        self.inner.normal_speed
    }

    /// Planned tangential speed (towards the tip), m/s.
    #[getter]
    fn tangential_speed(&self) -> f64 {
        self.inner.tangential_speed
    }

    /// Tangential blade travel used so far, m.
    #[getter]
    fn blade_travel(&self) -> f64 {
        self.inner.blade_travel
    }

    /// ``"cutting"``, or ``"done"`` once the target depth is reached.
    #[getter]
    fn phase(&self) -> &'static str {
        if self.inner.phase == SHEARCUT_PHASE_DONE {
            "done"
        } else {
            "cutting"
        }
    }

    /// Whether this tick took up a new plan.
    #[getter]
    fn planned(&self) -> bool {
        self.inner.planned
    }

    /// Plans so far that fell back to the previous plan.
    #[getter]
    fn fallbacks(&self) -> u64 {
        self.inner.fallbacks
    }

    /// Material scale factors believed (toughness, stiffness, friction).
    #[getter]
    fn scale(&self) -> (f64, f64, f64) {
        let s = self.inner.scale;
        (s[0], s[1], s[2])
    }

    fn __repr__(&self) -> String {
        format!(
            "Telemetry(slice_push_ratio={:?}, normal_speed={:?}, phase={:?})",
            self.inner.slice_push_ratio,
            self.inner.normal_speed,
            self.phase()
        )
    }
}
