//! `shearcut.Reading` and `shearcut.Command`: the arm's side of the servo
//! loop, every number carried bit for bit.

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use shearcut_ffi::{
    SHEARCUT_ARM_ACCELERATION_LIMIT, SHEARCUT_ARM_JERK_LIMIT, SHEARCUT_ARM_MOVING,
    SHEARCUT_ARM_NOT_FINITE, SHEARCUT_ARM_VELOCITY_LIMIT, ShearcutCommand, ShearcutReading,
};
use shearcut_sim::arm::ArmReading;

/// The arm's status by name, and its code in the C ABI.
const STATUSES: [(&str, u32); 5] = [
    ("moving", SHEARCUT_ARM_MOVING),
    ("velocity_limit", SHEARCUT_ARM_VELOCITY_LIMIT),
    ("acceleration_limit", SHEARCUT_ARM_ACCELERATION_LIMIT),
    ("jerk_limit", SHEARCUT_ARM_JERK_LIMIT),
    ("not_finite", SHEARCUT_ARM_NOT_FINITE),
];

/// One servo tick's reading: what an arm with a wrist F/T sensor reports.
/// World frame: origin on the board, y up; the knife moves in its plane
/// (y, z), +z along the edge towards the tip.
///
/// ``time`` (s), ``position`` of the knife frame's origin (the edge's
/// heel) (m), ``velocity`` executed over the last tick (m/s), ``wrench``
/// (fx, fy, fz, tx, ty, tz) of the F/T sensor, object on knife, noise and
/// bias included (N, N·m), ``status`` (``"moving"`` or the limit that
/// refused the last command: ``"velocity_limit"``,
/// ``"acceleration_limit"``, ``"jerk_limit"``, ``"not_finite"``) and
/// ``violation``, the refused command's value of that limit (m/s, m/s²,
/// m/s³; 0 while moving).
#[pyclass(module = "shearcut._shearcut", frozen)]
#[derive(Clone, Copy)]
pub(crate) struct Reading {
    pub(crate) inner: ShearcutReading,
}

#[pymethods]
impl Reading {
    #[new]
    #[pyo3(signature = (time, position, velocity, wrench, status="moving", violation=0.0))]
    fn new(
        time: f64,
        position: [f64; 3],
        velocity: [f64; 3],
        wrench: [f64; 6],
        status: &str,
        violation: f64,
    ) -> PyResult<Self> {
        let code = STATUSES
            .iter()
            .find(|(name, _)| *name == status)
            .map(|(_, code)| *code)
            .ok_or_else(|| {
                PyValueError::new_err(format!(
                    "status = {status:?}: one of moving, velocity_limit, acceleration_limit, jerk_limit, not_finite"
                ))
            })?;
        Ok(Self {
            inner: ShearcutReading {
                time,
                position,
                velocity,
                wrench,
                status: code,
                violation,
            },
        })
    }

    /// Time of the reading, s.
    #[getter]
    fn time(&self) -> f64 {
        self.inner.time
    }

    /// Knife frame origin (x, y, z), m.
    #[getter]
    fn position(&self) -> (f64, f64, f64) {
        let p = self.inner.position;
        (p[0], p[1], p[2])
    }

    /// Executed knife velocity (vx, vy, vz), m/s.
    #[getter]
    fn velocity(&self) -> (f64, f64, f64) {
        let v = self.inner.velocity;
        (v[0], v[1], v[2])
    }

    /// F/T wrench (fx, fy, fz, tx, ty, tz), N and N·m, sensor frame.
    #[getter]
    fn wrench(&self) -> (f64, f64, f64, f64, f64, f64) {
        let w = self.inner.wrench;
        (w[0], w[1], w[2], w[3], w[4], w[5])
    }

    /// ``"moving"`` or the limit that refused the last command.
    #[getter]
    fn status(&self) -> &'static str {
        STATUSES
            .iter()
            .find(|(_, code)| *code == self.inner.status)
            .map_or("moving", |(name, _)| name)
    }

    /// The refused command's value of the broken limit (m/s, m/s², m/s³).
    #[getter]
    fn violation(&self) -> f64 {
        self.inner.violation
    }

    fn __repr__(&self) -> String {
        format!(
            "Reading(time={:?}, position={:?}, velocity={:?}, wrench={:?}, status={:?})",
            self.inner.time,
            self.inner.position,
            self.inner.velocity,
            self.inner.wrench,
            self.status()
        )
    }
}

impl Reading {
    /// The reading as the controllers take it.
    pub(crate) fn to_arm(self) -> ArmReading {
        // Only `new` and the plant make readings, both with known codes.
        self.inner.to_arm().unwrap_or(ArmReading {
            status: shearcut_sim::arm::ArmStatus::Moving,
            ..ArmReading::at_rest(self.inner.time, self.inner.position.into())
        })
    }
}

/// A knife motion command: the twist (vx, vy, vz) of the knife frame in
/// the world frame, m/s (vx = 0: the knife moves in its plane).
/// ``Command()`` is the arm at rest, the first command of a loop.
#[pyclass(module = "shearcut._shearcut", frozen)]
#[derive(Clone, Copy)]
pub(crate) struct Command {
    pub(crate) inner: ShearcutCommand,
}

#[pymethods]
impl Command {
    #[new]
    #[pyo3(signature = (velocity=(0.0, 0.0, 0.0)))]
    fn new(velocity: (f64, f64, f64)) -> Self {
        Self {
            inner: ShearcutCommand {
                velocity: [velocity.0, velocity.1, velocity.2],
            },
        }
    }

    /// Knife velocity (vx, vy, vz), m/s.
    #[getter]
    fn velocity(&self) -> (f64, f64, f64) {
        let v = self.inner.velocity;
        (v[0], v[1], v[2])
    }

    fn __repr__(&self) -> String {
        format!("Command(velocity={:?})", self.inner.velocity)
    }
}
