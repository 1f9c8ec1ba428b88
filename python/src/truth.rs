//! `shearcut.Truth`: what only the simulated plant knows.

use pyo3::prelude::*;
use shearcut_ffi::ShearcutTruth;

/// The simulated plant's ground truth after a step: for a simulation's
/// stop condition, scores and plots, never for control.
#[pyclass(module = "shearcut._shearcut", frozen)]
#[derive(Clone, Copy)]
pub(crate) struct Truth {
    pub(crate) inner: ShearcutTruth,
}

#[pymethods]
impl Truth {
    /// Noise-free force (fx, fy, fz) at the sensor, N, world axes, object
    /// on knife (fy > 0 pushes the knife up).
    #[getter]
    fn force(&self) -> (f64, f64, f64) {
        let f = self.inner.force;
        (f[0], f[1], f[2])
    }

    /// Noise-free torque (tx, ty, tz) about the sensor, N·m.
    #[getter]
    fn torque(&self) -> (f64, f64, f64) {
        let t = self.inner.torque;
        (t[0], t[1], t[2])
    }

    /// Depth of the crack front below the object's top, m.
    #[getter]
    fn crack_depth(&self) -> f64 {
        self.inner.crack_depth
    }

    /// Length of edge in contact with material, m.
    #[getter]
    fn contact_length(&self) -> f64 {
        self.inner.contact_length
    }

    /// Number of sections that have fractured.
    #[getter]
    fn fractured_sections(&self) -> u64 {
        self.inner.fractured_sections
    }

    /// Cumulative knife work on the object, J.
    #[getter]
    fn work(&self) -> f64 {
        self.inner.work
    }

    /// Largest surface deformation next to the blade, m.
    #[getter]
    fn deformation(&self) -> f64 {
        self.inner.deformation
    }

    fn __repr__(&self) -> String {
        format!(
            "Truth(crack_depth={:?}, work={:?}, force={:?})",
            self.inner.crack_depth, self.inner.work, self.inner.force
        )
    }
}
