//! The example loops in C and C++ (`examples/c/plain_loop.c`,
//! `examples/cpp/plain_loop.cpp`, `examples/cpp/ros2_control_style.cpp`),
//! compiled with gcc/g++ against this crate's shared library and run on the
//! main job's scenario (`loop-potato-whole-realtime`, the MPC), reproduce
//! `shearcut run … --transport inproc` bit for bit: every tick's reading
//! and truth, read back from the programs' CSV (17 significant digits, so
//! every `f64` reads back exactly), rebuilds the Rust run's samples (time,
//! displacement, forces, torques, work, depth, deformation) and summary
//! (work, peak forces) with no difference in any bit.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

use shearcut::closed_loop::{RunOutput, run_closed_loop};
use shearcut::cut_record::{CutSample, CutSummary};
use shearcut::scenario::Scenario;
use shearcut_ffi::{CutSetup, ShearcutReading, ShearcutTruth};
use shearcut_plant::PlantTruth;
use shearcut_sim::arm::ArmReading;

const SCENARIO: &str = "loop-potato-whole-realtime";
const CONTROLLER: &str = "mpc";

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// The Rust in-process run of the scenario, once per test binary.
fn reference() -> &'static RunOutput {
    static RUN: OnceLock<RunOutput> = OnceLock::new();
    RUN.get_or_init(|| {
        let s = Scenario::load(SCENARIO).unwrap();
        run_closed_loop(&s, CONTROLLER.parse().unwrap()).unwrap()
    })
}

/// The directory of the `libshearcut_ffi.so` of the build this test
/// belongs to: cargo builds the library's `cdylib` beside the `rlib` this
/// test links, in `target/<profile>/deps`, before it runs the test.
fn library_dir() -> PathBuf {
    let exe = std::env::current_exe().unwrap();
    let deps = exe.parent().unwrap().to_path_buf();
    assert!(
        deps.join("libshearcut_ffi.so").exists(),
        "cargo built libshearcut_ffi.so in {}",
        deps.display()
    );
    deps
}

/// Compiles `source` (C or C++ by its extension) against the shared
/// library as a user would (`-lshearcut_ffi`, found at run time through
/// the rpath), with warnings as errors.
fn compile(source: &str, output: &str) -> PathBuf {
    let out = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(output);
    let (compiler, standard) = if source.ends_with(".c") {
        ("gcc", "-std=c99")
    } else {
        ("g++", "-std=c++17")
    };
    let lib = library_dir();
    let result = Command::new(compiler)
        .args([standard, "-O2", "-Wall", "-Wextra", "-Werror", "-I"])
        .arg(repo().join("include"))
        .arg(repo().join(source))
        .arg(format!("-L{}", lib.display()))
        .arg("-lshearcut_ffi")
        .arg(format!("-Wl,-rpath,{}", lib.display()))
        .args(["-lm", "-o"])
        .arg(&out)
        .output()
        .unwrap_or_else(|e| panic!("cannot run {compiler}: {e}"));
    assert!(
        result.status.success(),
        "{compiler} failed on {source}:\n{}",
        String::from_utf8_lossy(&result.stderr)
    );
    out
}

/// Runs a compiled loop; returns its stdout and its per-tick rows.
fn run(program: &Path, csv_name: &str) -> (String, Vec<(ArmReading, PlantTruth)>) {
    let csv = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(csv_name);
    let out = Command::new(program)
        .args([SCENARIO, CONTROLLER])
        .arg(&csv)
        .current_dir(repo())
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(
        out.status.success(),
        "{} failed: {stdout}{}",
        program.display(),
        String::from_utf8_lossy(&out.stderr)
    );
    let rows = std::fs::read_to_string(&csv)
        .unwrap()
        .lines()
        .map(parse_row)
        .collect();
    (stdout, rows)
}

/// One CSV row back into the Rust types, through the C mirrors.
fn parse_row(line: &str) -> (ArmReading, PlantTruth) {
    let f: Vec<f64> = line.split(',').map(|x| x.parse().unwrap()).collect();
    assert_eq!(f.len(), 29, "{line}");
    let reading = ShearcutReading {
        time: f[1],
        position: [f[2], f[3], f[4]],
        velocity: [f[5], f[6], f[7]],
        wrench: [f[8], f[9], f[10], f[11], f[12], f[13]],
        status: f[14] as u32,
        violation: f[15],
    };
    let truth = ShearcutTruth {
        force: [f[16], f[17], f[18]],
        torque: [f[19], f[20], f[21]],
        crack_depth: f[22],
        contact_length: f[23],
        fractured_sections: f[24] as u64,
        work: f[25],
        deformation: f[26],
    };
    (reading.to_arm().unwrap(), PlantTruth::from(&truth))
}

/// The foreign loop's ticks give the Rust run's samples and summary, bit
/// for bit (`{:?}` prints every f64 in its shortest exact form, -0 apart
/// from 0).
fn assert_bit_identical(rows: &[(ArmReading, PlantTruth)]) {
    let reference = reference();
    let setup = CutSetup::load(SCENARIO, Some(CONTROLLER)).unwrap();
    let cut = setup.cut();
    let samples: Vec<CutSample> = rows
        .iter()
        .filter_map(|(r, t)| CutSample::from_plant(r, t, cut.xi_label, cut.z0, &cut.start, cut.gap))
        .collect();
    assert_eq!(rows.len(), reference.output.ticks, "ticks");
    assert_eq!(samples.len(), reference.output.samples.len(), "samples");
    for (k, (a, b)) in samples.iter().zip(&reference.output.samples).enumerate() {
        assert_eq!(format!("{a:?}"), format!("{b:?}"), "sample {k}");
    }
    let summary = CutSummary::from_samples(&samples, reference.target_depth_m);
    assert_eq!(format!("{summary:?}"), format!("{:?}", reference.summary));
    assert_eq!(summary.work_j.to_bits(), reference.summary.work_j.to_bits());
    // The run is the main job's cut: the plant's crack reached the target.
    assert!(reference.summary.completed);
    assert!(rows.last().unwrap().1.crack_depth >= reference.target_depth_m);
}

#[test]
fn the_c_plain_loop_reproduces_the_rust_run() {
    let program = compile("examples/c/plain_loop.c", "plain_loop_c");
    let (stdout, rows) = run(&program, "plain_loop_c.csv");
    assert!(stdout.contains("completed"), "{stdout}");
    assert_bit_identical(&rows);
}

#[test]
fn the_cpp_plain_loop_reproduces_the_rust_run() {
    let program = compile("examples/cpp/plain_loop.cpp", "plain_loop_cpp");
    let (stdout, rows) = run(&program, "plain_loop_cpp.csv");
    assert!(stdout.contains("completed"), "{stdout}");
    assert!(
        stdout.contains(&format!("work {:.4} J", reference().summary.work_j)),
        "{stdout}"
    );
    assert_bit_identical(&rows);
}

#[test]
fn the_ros2_control_shaped_controller_reproduces_the_rust_run() {
    let program = compile("examples/cpp/ros2_control_style.cpp", "ros2_control_style");
    let (stdout, rows) = run(&program, "ros2_control_style.csv");
    assert!(stdout.contains("completed"), "{stdout}");
    assert_bit_identical(&rows);
}
