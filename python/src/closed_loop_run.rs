//! `shearcut.run`: the Rust closed loop (`shearcut run … --transport
//! inproc`), its time series as NumPy arrays and its summary as a dict.

use numpy::IntoPyArray;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use shearcut::closed_loop::ControlSample;
use shearcut::closed_loop::run_closed_loop;
use shearcut::controller_choice::ControllerChoice;
use shearcut::cut_record::CutSample;
use shearcut::scenario::{Scenario as ScenarioFile, check_controller_kind};
use shearcut_ffi::CutSetup;

use crate::errors::to_py;
use crate::scenario::Scenario;

/// A column of the series: its name and how a sample gives it.
type SampleColumn = (&'static str, fn(&CutSample) -> f64);

/// A column of the plan series: its name and how a controller tick gives it.
type PlanColumn = (&'static str, fn(&ControlSample) -> f64);

/// Runs the closed loop in Rust, exactly as ``shearcut run SCENARIO
/// --controller CONTROLLER --transport inproc``, and returns
/// ``(series, summary)``.
///
/// ``scenario``: a ``Scenario`` (its controller is used unless
/// ``controller`` is given) or a TOML path or built-in name.
///
/// ``series`` maps column names to NumPy arrays, one entry per tick from
/// the edge's first contact (``time_s``, ``displacement_m``,
/// ``tangential_displacement_m``, ``force_vertical_n``,
/// ``force_horizontal_n``, ``torque_x_nm``, ``torque_y_nm``,
/// ``torque_z_nm``, ``contact_length_m``, ``work_j``, ``crack_depth_m``,
/// ``deformation_m``; forces are the noise-free truth, resistance
/// positive), and ``plan_*`` arrays, one entry per controller tick
/// (``plan_time_s``, ``plan_xi``, ``plan_normal_speed_m_s``,
/// ``plan_tangential_speed_m_s``, ``plan_command_vy_m_s``,
/// ``plan_command_vz_m_s``).
///
/// ``summary`` holds ``end`` (``"completed"``, ``"controller_done"``,
/// ``"timed_out"`` or ``"failed: …"``), ``ticks``, ``limit_faults``,
/// ``controller``, ``target_depth_m``, ``wall_s`` (the loop's wall-clock
/// time, s), ``simulated_s`` and the cut's ``work_j``,
/// ``peak_force_vertical_n``, ``peak_force_horizontal_n``,
/// ``peak_torque_nm``, ``max_deformation_m``, ``cut_depth_m``,
/// ``blade_travel_m``, ``blade_path_m``, ``reversals``, ``duration_s``,
/// ``completed``.
#[pyfunction]
#[pyo3(signature = (scenario, controller=None))]
pub(crate) fn run<'py>(
    py: Python<'py>,
    scenario: &Bound<'py, PyAny>,
    controller: Option<&str>,
) -> PyResult<(Bound<'py, PyDict>, Bound<'py, PyDict>)> {
    let (file, choice): (ScenarioFile, _) = if let Ok(s) = scenario.cast::<Scenario>() {
        let s = s.get();
        match controller {
            Some(c) => (
                s.setup.scenario().clone(),
                c.parse::<ControllerChoice>()
                    .and_then(|c| check_controller_kind("controller", c).map(|()| c))
                    .map_err(|e| PyValueError::new_err(e.to_string()))?,
            ),
            None => (s.setup.scenario().clone(), s.setup.choice()),
        }
    } else if let Ok(name) = scenario.extract::<String>() {
        let setup = CutSetup::load(&name, controller).map_err(to_py)?;
        (setup.scenario().clone(), setup.choice())
    } else {
        return Err(PyValueError::new_err(
            "scenario: a shearcut.Scenario, a TOML path or a built-in scenario name",
        ));
    };
    let out = run_closed_loop(&file, choice).map_err(|e| to_py(e.into()))?;
    let o = &out.output;
    let series = PyDict::new(py);
    let column = |f: fn(&CutSample) -> f64| o.samples.iter().map(f).collect::<Vec<f64>>();
    let columns: [SampleColumn; 12] = [
        ("time_s", |s| s.time_s),
        ("displacement_m", |s| s.displacement_m),
        ("tangential_displacement_m", |s| s.tangential_displacement_m),
        ("force_vertical_n", |s| s.force_vertical_n),
        ("force_horizontal_n", |s| s.force_horizontal_n),
        ("torque_x_nm", |s| s.torque_x_nm),
        ("torque_y_nm", |s| s.torque_y_nm),
        ("torque_z_nm", |s| s.torque_z_nm),
        ("contact_length_m", |s| s.contact_length_m),
        ("work_j", |s| s.work_j),
        ("crack_depth_m", |s| s.crack_depth_m),
        ("deformation_m", |s| s.deformation_m),
    ];
    for (name, f) in columns {
        series.set_item(name, column(f).into_pyarray(py))?;
    }
    let plans: [PlanColumn; 6] = [
        ("plan_time_s", |c| c.time_s),
        ("plan_xi", |c| c.xi_plan),
        ("plan_normal_speed_m_s", |c| c.normal_speed_plan_m_s),
        ("plan_tangential_speed_m_s", |c| c.tangential_speed_plan_m_s),
        ("plan_command_vy_m_s", |c| c.command_vy_m_s),
        ("plan_command_vz_m_s", |c| c.command_vz_m_s),
    ];
    for (name, f) in plans {
        let values: Vec<f64> = o.control.iter().map(f).collect();
        series.set_item(name, values.into_pyarray(py))?;
    }

    let c = &out.summary;
    let summary = PyDict::new(py);
    summary.set_item("end", o.end.label())?;
    summary.set_item("ticks", o.ticks)?;
    summary.set_item("limit_faults", o.limit_faults)?;
    summary.set_item("controller", &out.controller)?;
    summary.set_item("target_depth_m", out.target_depth_m)?;
    summary.set_item("wall_s", o.wall_s)?;
    summary.set_item("simulated_s", o.simulated_s)?;
    summary.set_item("work_j", c.work_j)?;
    summary.set_item("peak_force_vertical_n", c.peak_force_vertical_n)?;
    summary.set_item("peak_force_horizontal_n", c.peak_force_horizontal_n)?;
    summary.set_item("peak_torque_nm", c.peak_torque_nm)?;
    summary.set_item("max_deformation_m", c.max_deformation_m)?;
    summary.set_item("cut_depth_m", c.cut_depth_m)?;
    summary.set_item("blade_travel_m", c.blade_travel_m)?;
    summary.set_item("blade_path_m", c.blade_path_m)?;
    summary.set_item("reversals", c.reversals)?;
    summary.set_item("duration_s", c.duration_s)?;
    summary.set_item("completed", c.completed)?;
    Ok((series, summary))
}
