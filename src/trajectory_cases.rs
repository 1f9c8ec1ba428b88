//! JSONL case runner for the trajectory generator (`shearcut trajectory --cases FILE.jsonl`).
//!
//! Each input line is one case in ruckig's field names (`current_position`, `current_velocity`,
//! `current_acceleration`, `target_position`, `target_velocity`, `target_acceleration`,
//! `max_velocity`, `max_acceleration`, `max_jerk`, optional `min_velocity`, `min_acceleration`,
//! `synchronization` = "time" | "phase" | "none", `control_interface` = "position" | "velocity",
//! `duration_discretization` = "continuous" | "discrete", `cycle_time` in s, `sample_count` k to
//! add k + 1 uniformly spaced samples of the trajectory, and an `id` copied to the output). Each output line carries `line`, `id`, and either `error` or `status`,
//! `duration`, `final_position/velocity/acceleration`, `position_extrema`, `velocity_extrema`,
//! `acceleration_extrema` (per DoF `[min, max]`) and `independent_min_durations`. Malformed lines
//! get an error line; the other lines still run. Blank lines and lines starting with `#` are
//! skipped.
//!
//! Limits (docs/reliability.md): the file is read with a cap of [`CASES_FILE_BYTES`]; a line
//! that is not UTF-8 gets an error line; `cycle_time` must be in [1e-5, 1] s; `sample_count` is
//! at most [`MAX_CASE_SAMPLES`] and all cases of a file together at most
//! [`CASES_SAMPLES_BUDGET`] samples, so that a short line cannot ask for gigabytes of output; a
//! result that is not finite is an error line, never `null`.

use std::io::Write;
use std::path::Path;

use serde::Deserialize;
use serde_json::{Value, json};
use shearcut_controllers::trajectory::{
    ControlInterface, DurationDiscretization, Synchronization, Trajectory, TrajectoryGenerator,
    TrajectoryInput, TrajectorySettings, TrajectoryStatus,
};
use shearcut_sim::capped_read::{CappedReadError, read_capped};
use shearcut_sim::physical_range::{CYCLE_TIME, number_text};

/// Largest DoF count the runner accepts.
pub const MAX_CASE_DOFS: usize = 8;

/// Largest cases file read, bytes.
pub const CASES_FILE_BYTES: u64 = 64 << 20;

/// Most samples one case may ask for (`sample_count`): with 8 DoF about 5 MB of output.
pub const MAX_CASE_SAMPLES: usize = 100_000;

/// Most samples all cases of a file may ask for together: with 8 DoF about 100 MB of output.
pub const CASES_SAMPLES_BUDGET: usize = 200_000;

/// Why a case file could not be run.
#[derive(Debug, thiserror::Error)]
pub enum CasesError {
    /// The input could not be read (missing, too large): bad input.
    #[error("{0}")]
    Read(#[from] CappedReadError),
    /// The output could not be written.
    #[error("{0}")]
    Write(#[from] std::io::Error),
}

/// Counts of a case run.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct CasesReport {
    /// Lines that held a case (blank and comment lines excluded).
    pub cases: usize,
    /// Cases that produced a trajectory.
    pub ok: usize,
    /// Cases that produced an error line (malformed input or generator error).
    pub errors: usize,
}

/// One case as read from JSON.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct Case {
    #[serde(default)]
    id: Option<Value>,
    current_position: Vec<f64>,
    #[serde(default)]
    current_velocity: Option<Vec<f64>>,
    #[serde(default)]
    current_acceleration: Option<Vec<f64>>,
    target_position: Vec<f64>,
    #[serde(default)]
    target_velocity: Option<Vec<f64>>,
    #[serde(default)]
    target_acceleration: Option<Vec<f64>>,
    max_velocity: Vec<f64>,
    max_acceleration: Vec<f64>,
    max_jerk: Vec<f64>,
    #[serde(default)]
    min_velocity: Option<Vec<f64>>,
    #[serde(default)]
    min_acceleration: Option<Vec<f64>>,
    #[serde(default)]
    synchronization: Synchronization,
    #[serde(default, alias = "interface")]
    control_interface: ControlInterface,
    #[serde(default)]
    duration_discretization: DurationDiscretization,
    #[serde(default)]
    cycle_time: Option<f64>,
    #[serde(default)]
    sample_count: Option<usize>,
}

fn array<const N: usize>(name: &str, v: Option<&Vec<f64>>) -> Result<[f64; N], String> {
    match v {
        None => Ok([0.0; N]),
        Some(v) => <[f64; N]>::try_from(v.as_slice())
            .map_err(|_| format!("{name} has {} entries, expected {N}", v.len())),
    }
}

fn run_n<const N: usize>(c: &Case) -> Result<Value, String> {
    let mut input = TrajectoryInput::<N> {
        interface: c.control_interface,
        synchronization: c.synchronization,
        duration_discretization: c.duration_discretization,
        current_position: array("current_position", Some(&c.current_position))?,
        current_velocity: array("current_velocity", c.current_velocity.as_ref())?,
        current_acceleration: array("current_acceleration", c.current_acceleration.as_ref())?,
        target_position: array("target_position", Some(&c.target_position))?,
        target_velocity: array("target_velocity", c.target_velocity.as_ref())?,
        target_acceleration: array("target_acceleration", c.target_acceleration.as_ref())?,
        max_velocity: array("max_velocity", Some(&c.max_velocity))?,
        max_acceleration: array("max_acceleration", Some(&c.max_acceleration))?,
        max_jerk: array("max_jerk", Some(&c.max_jerk))?,
        ..TrajectoryInput::default()
    };
    if let Some(m) = &c.min_velocity {
        input.min_velocity = Some(array("min_velocity", Some(m))?);
    }
    if let Some(m) = &c.min_acceleration {
        input.min_acceleration = Some(array("min_acceleration", Some(m))?);
    }
    let mut settings = TrajectorySettings::default();
    if let Some(dt) = c.cycle_time {
        CYCLE_TIME
            .check("cycle_time", dt)
            .map_err(|e| e.to_string())?;
        settings.cycle_time = dt;
    }
    let otg = TrajectoryGenerator::<N>::new(settings).map_err(|e| e.to_string())?;
    let mut traj = Trajectory::<N>::default();
    let status = otg
        .calculate(&input, &mut traj)
        .map_err(|e| e.to_string())?;
    let t = traj.duration();
    let (mut p, mut v, mut a) = ([0.0; N], [0.0; N], [0.0; N]);
    traj.at_time(t, &mut p, &mut v, &mut a);
    if !(t.is_finite() && p.iter().chain(&v).chain(&a).all(|x| x.is_finite())) {
        return Err(format!(
            "the generator returned a non-finite result (duration {} s): the limits or states are out of its numeric range",
            number_text(t)
        ));
    }
    let ext = traj.extrema();
    let status = match status {
        TrajectoryStatus::Working => "working",
        TrajectoryStatus::BrakingThenTarget => "braking_then_target",
        TrajectoryStatus::Finished => "finished",
    };
    let mut samples = Value::Null;
    if let Some(k) = c.sample_count.filter(|&k| k > 0) {
        let (mut ts, mut ps, mut vs, mut as_) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
        for i in 0..=k {
            let ti = t * i as f64 / k as f64;
            traj.at_time(ti, &mut p, &mut v, &mut a);
            ts.push(ti);
            ps.push(p.to_vec());
            vs.push(v.to_vec());
            as_.push(a.to_vec());
        }
        samples = json!({"t": ts, "p": ps, "v": vs, "a": as_});
        traj.at_time(t, &mut p, &mut v, &mut a);
    }
    Ok(json!({
        "samples": samples,
        "brake_duration": traj.brake_duration(),
        "status": status,
        "duration": t,
        "final_position": p.to_vec(),
        "final_velocity": v.to_vec(),
        "final_acceleration": a.to_vec(),
        "position_extrema": ext.iter().map(|e| [e.position.min, e.position.max]).collect::<Vec<_>>(),
        "velocity_extrema": ext.iter().map(|e| [e.velocity.min, e.velocity.max]).collect::<Vec<_>>(),
        "acceleration_extrema": ext.iter().map(|e| [e.acceleration.min, e.acceleration.max]).collect::<Vec<_>>(),
        "independent_min_durations": traj.independent_min_durations().to_vec(),
        "braking": traj.is_braking(),
    }))
}

fn run_case(
    line: &str,
    samples_left: &mut usize,
) -> Result<(Option<Value>, Value), (Option<Value>, String)> {
    let c: Case = serde_json::from_str(line).map_err(|e| (None, format!("malformed case: {e}")))?;
    let id = c.id.clone();
    let samples = c.sample_count.unwrap_or(0);
    if samples > MAX_CASE_SAMPLES {
        return Err((
            id,
            format!("`sample_count` = {samples}: must be at most {MAX_CASE_SAMPLES}"),
        ));
    }
    if samples > *samples_left {
        return Err((
            id,
            format!(
                "`sample_count` = {samples}: the file's cases may ask for {CASES_SAMPLES_BUDGET} samples in all, {} are left",
                *samples_left
            ),
        ));
    }
    *samples_left -= samples;
    let n = c.current_position.len();
    let r = match n {
        1 => run_n::<1>(&c),
        2 => run_n::<2>(&c),
        3 => run_n::<3>(&c),
        4 => run_n::<4>(&c),
        5 => run_n::<5>(&c),
        6 => run_n::<6>(&c),
        7 => run_n::<7>(&c),
        8 => run_n::<8>(&c),
        _ => Err(format!(
            "current_position has {n} entries, expected 1 to {MAX_CASE_DOFS}"
        )),
    };
    match r {
        Ok(v) => Ok((id, v)),
        Err(e) => Err((id, e)),
    }
}

/// The output line of one input line (1-based `line_number`), or `None`
/// for a blank or comment line. `samples_left` is the file's remaining
/// sample budget; a case's samples are taken from it.
pub fn case_line(
    line: &[u8],
    line_number: usize,
    samples_left: &mut usize,
) -> Option<Result<Value, Value>> {
    let Ok(text) = std::str::from_utf8(line) else {
        return Some(Err(
            json!({"line": line_number, "id": Value::Null, "error": "the line is not UTF-8 text"}),
        ));
    };
    let trimmed = text.trim();
    if trimmed.is_empty() || trimmed.starts_with('#') {
        return None;
    }
    Some(match run_case(trimmed, samples_left) {
        Ok((id, mut v)) => {
            v["line"] = json!(line_number);
            v["id"] = id.unwrap_or(Value::Null);
            Ok(v)
        }
        Err((id, e)) => {
            Err(json!({"line": line_number, "id": id.unwrap_or(Value::Null), "error": e}))
        }
    })
}

/// Runs every case of the JSONL file `input` (read with a cap of
/// [`CASES_FILE_BYTES`]), writing one JSON line per case to `output`.
/// Read and write errors abort; a bad case only produces an error line.
pub fn run_cases(input: &Path, output: &mut dyn Write) -> Result<CasesReport, CasesError> {
    let bytes = read_capped(input, CASES_FILE_BYTES)?;
    let mut report = CasesReport::default();
    let mut samples_left = CASES_SAMPLES_BUDGET;
    for (k, line) in bytes.split(|&b| b == b'\n').enumerate() {
        let Some(result) = case_line(line, k + 1, &mut samples_left) else {
            continue;
        };
        report.cases += 1;
        let out = match result {
            Ok(v) => {
                report.ok += 1;
                v
            }
            Err(v) => {
                report.errors += 1;
                v
            }
        };
        writeln!(output, "{out}")?;
    }
    Ok(report)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Runs the cases of `text` from a file in a directory named by
    /// `test`; the report and the result lines.
    fn run_text(test: &str, text: &str) -> (CasesReport, Vec<Value>) {
        let dir =
            std::env::temp_dir().join(format!("shearcut-cases-{test}-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("cases.jsonl");
        std::fs::write(&path, text).unwrap();
        let mut out = Vec::new();
        let r = run_cases(&path, &mut out).unwrap();
        std::fs::remove_dir_all(&dir).unwrap();
        let lines = String::from_utf8(out)
            .unwrap()
            .lines()
            .map(|l| serde_json::from_str(l).unwrap())
            .collect();
        (r, lines)
    }

    #[test]
    fn bad_lines_get_errors_and_the_rest_runs() {
        let (r, lines) = run_text(
            "bad-lines",
            "{\"current_position\":[0],\"target_position\":[1],\"max_velocity\":[1],\"max_acceleration\":[1],\"max_jerk\":[1],\"id\":7}\n\
             not json\n\
             \n\
             {\"current_position\":[0,0],\"target_position\":[1],\"max_velocity\":[1],\"max_acceleration\":[1],\"max_jerk\":[1]}\n\
             {\"current_position\":[0],\"target_position\":[1],\"max_velocity\":[-1],\"max_acceleration\":[1],\"max_jerk\":[1]}\n\
             {\"current_position\":[0,0],\"target_position\":[1,2],\"max_velocity\":[1,1],\"max_acceleration\":[1,1],\"max_jerk\":[1,1],\"synchronization\":\"phase\"}\n",
        );
        assert_eq!(
            r,
            CasesReport {
                cases: 5,
                ok: 2,
                errors: 3
            }
        );
        assert_eq!(lines[0]["id"], json!(7));
        assert!((lines[0]["duration"].as_f64().unwrap() - 3.174_802_103_9).abs() < 1e-9);
        assert!(lines[1]["error"].as_str().unwrap().starts_with("malformed"));
        assert!(
            lines[2]["error"]
                .as_str()
                .unwrap()
                .contains("target_position")
        );
        assert!(lines[3]["error"].as_str().unwrap().contains("max_velocity"));
        assert_eq!(lines[4]["status"], json!("working"));
    }

    #[test]
    fn a_result_out_of_the_numeric_range_is_an_error_line_with_its_duration_short() {
        // Reaching 1e300 m/s at 1 m/s² takes 1e300 s, over which the
        // position overflows.
        let (r, lines) = run_text(
            "numeric-range",
            "{\"current_position\":[0],\"target_position\":[1],\"target_velocity\":[1e300],\"max_velocity\":[1e300],\"max_acceleration\":[1],\"max_jerk\":[1],\"control_interface\":\"velocity\"}\n",
        );
        assert_eq!(r.errors, 1);
        assert_eq!(
            lines[0]["error"],
            json!(
                "the generator returned a non-finite result (duration 1e300 s): \
                 the limits or states are out of its numeric range"
            )
        );
    }
}
