//! The bodies of the fuzz targets, shared with the stable regression test
//! `tests/reliability_fuzz_regressions.rs` (both include this file with
//! `#[path]`), so every crash the fuzzer keeps runs again in CI.
//!
//! Each body feeds bytes to one reader of the input surface and asserts
//! what the reader promises: a value that passed validation is usable
//! (finite, buildable), a refusal is one line.

#![allow(dead_code)]

use shearcut::scenario::Scenario;
use shearcut::trajectory_cases::{CASES_SAMPLES_BUDGET, case_line};
use shearcut_sim::geometry::{MeshFormat, SectionPlane, parse_mesh};
use shearcut_sim::surrogate::Surrogate;

fn one_line(message: &str) {
    assert!(!message.contains('\n'), "an error is one line: {message}");
}

/// Scenario TOML: parsed, resolved and validated, or one line. A valid
/// scenario's object builds as a closed mesh, and what `check` builds of it
/// for `simulate` and `run` (`command_checks`) builds or is one line.
pub fn scenario_toml(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    match Scenario::parse(text, "fuzz", "fuzz") {
        Ok(s) => {
            let mesh = s
                .object
                .mesh()
                .expect("a validated object builds as a closed mesh");
            let (lo, hi) = mesh.bounds();
            assert!((hi - lo).iter().all(|d| d.is_finite() && *d > 0.0));
            // What `check` builds of it for `simulate` and `run`: their
            // geometry, plant and controller, or one line each.
            let (simulate, run) = shearcut::commands::check::command_checks(&s);
            for outcome in [simulate, run] {
                if let Err(e) = outcome {
                    one_line(&e.to_string());
                }
            }
        }
        Err(e) => one_line(&e.to_string()),
    }
}

/// An OBJ (first byte even) or STL (odd) file: read as a closed mesh and
/// cut through its middle, or one line.
pub fn mesh_file(data: &[u8]) {
    let Some((&selector, bytes)) = data.split_first() else {
        return;
    };
    let format = if selector % 2 == 0 {
        MeshFormat::Obj
    } else {
        MeshFormat::Stl
    };
    match parse_mesh(bytes, format, "fuzz") {
        Ok(mesh) => {
            let (lo, hi) = mesh.bounds();
            assert!(lo.iter().chain(hi.iter()).all(|v| v.is_finite()));
            let mid = 0.5 * (lo + hi);
            let plane = SectionPlane::normal_to_segment(mid, nalgebra::Vector3::y());
            let _ = plane.loops(&mesh);
        }
        Err(e) => one_line(&e.to_string()),
    }
}

/// A surrogate file: read and validated, or one line.
pub fn surrogate_file(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    if let Err(e) = Surrogate::from_toml_str(text) {
        one_line(&e.to_string());
    }
}

/// A JSONL file of trajectory cases: every line runs or gets an error
/// line; a result's duration is a finite number.
pub fn trajectory_cases(data: &[u8]) {
    let mut samples_left = CASES_SAMPLES_BUDGET;
    for (k, line) in data.split(|&b| b == b'\n').enumerate() {
        match case_line(line, k + 1, &mut samples_left) {
            None => {}
            Some(Ok(v)) => {
                let t = v["duration"]
                    .as_f64()
                    .expect("a result has a numeric duration");
                assert!(t.is_finite() && t >= 0.0, "duration {t}");
                one_line(&v.to_string());
            }
            Some(Err(v)) => one_line(&v.to_string()),
        }
    }
}

/// Little-endian `f64` number `i` of `bytes` (zero past the end).
fn f64_at(bytes: &[u8], i: usize) -> f64 {
    let mut b = [0u8; 8];
    if let Some(chunk) = bytes.get(8 * i..8 * i + 8) {
        b.copy_from_slice(chunk);
    }
    f64::from_le_bytes(b)
}

/// The wire messages from a hostile bridge: the bytes as a measurement
/// (time, position, velocity, wrench, fault value, then status and fault
/// codes) and as a command's velocity. A measurement the controller
/// accepts is finite and within `WireMeasurement::BOUNDS`; a command the
/// plant's arm accepts is finite and within its speed limit.
pub fn wire_messages(data: &[u8]) {
    use shearcut::transport::wire::{WireCommand, WireMeasurement};
    use shearcut_sim::arm::{ArmLimitMonitor, ArmLimits};

    let f = |i| f64_at(data, i);
    let code = |i: usize| data.get(i).copied().map_or(0, |c| u32::from(c % 8));
    let mut m = WireMeasurement::empty();
    m.sequence = 0;
    m.time = f(0);
    m.position = [f(1), f(2), f(3)];
    m.velocity = [f(4), f(5), f(6)];
    m.wrench = [f(7), f(8), f(9), f(10), f(11), f(12)];
    m.fault_value = f(13);
    m.status = code(112);
    m.fault = code(113);
    if let Ok(r) = m.reading() {
        let bounds = WireMeasurement::BOUNDS.map(|(_, b)| b);
        assert!(r.time.is_finite() && r.time.abs() <= bounds[0]);
        assert!(
            r.position
                .iter()
                .all(|v| v.is_finite() && v.abs() <= bounds[1])
        );
        assert!(
            r.velocity
                .iter()
                .all(|v| v.is_finite() && v.abs() <= bounds[2])
        );
        assert!(r.wrench.iter().all(|v| v.is_finite()));
    }
    let command = WireCommand {
        sequence: 0,
        time: f(14),
        velocity: [f(0), f(1), f(2)],
        flags: code(114),
        reserved: 0,
    };
    let limits = ArmLimits::default();
    let mut arm = ArmLimitMonitor::new(limits);
    let v = command.knife_command().velocity;
    if arm.check(v, 1e-3).is_ok() {
        assert!(v.iter().all(|x| x.is_finite()));
        assert!(v.norm() <= limits.velocity * (1.0 + 1e-9));
    }
}
