//! `shearcut simulate` on seed 001's finite-strain wire–slab scenarios.

#[path = "support/binary_run.rs"]
mod binary_run;

use binary_run::{assert_files, assert_success, read_summary, scratch, shearcut};

/// A coarse, two-angle version of the shipped scenario runs to nucleation
/// and writes the series, the profiles, the summary with the seed's numbers
/// and the three plots.
#[test]
fn simulate_writes_the_seed_figures() {
    let dir = scratch("wire-slab");
    let path = dir.join("coarse.toml");
    let text = include_str!("../config/scenarios/seed001-agar-wire.toml")
        .replace("elements_per_radius = 6", "elements_per_radius = 3")
        .replace(
            "angles_deg = [0.0, 15.0, 30.0, 45.0, 60.0, 75.0]",
            "angles_deg = [60.0, 75.0]",
        );
    std::fs::write(&path, text).unwrap();
    let out = dir.join("run");
    let o = shearcut(&[
        "simulate",
        path.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_success(&o);
    assert_files(
        &out,
        &[
            "series.csv",
            "surface.csv",
            "summary.json",
            "scenario.toml",
            "forces_depth.svg",
            "nucleation_angle.png",
            "stress_map.svg",
        ],
    );
    let summary = read_summary(&out);
    let nuc = summary["nucleation"].as_array().unwrap();
    assert_eq!(nuc.len(), 2);
    assert!(nuc.iter().all(|n| n["nucleated"].as_bool() == Some(true)));
    assert!(
        summary["seed_comparison"]["seed_max_tangential_force"]
            .as_f64()
            .unwrap()
            > 0.0
    );
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains("seed 001 side by side"), "{stdout}");
    std::fs::remove_dir_all(dir).ok();
}

/// A bad value in `[slab]` exits 2 with one line naming key, value and range.
#[test]
fn bad_slab_setting_is_refused_in_one_line() {
    let dir = scratch("wire-slab-bad");
    let path = dir.join("bad.toml");
    let text = include_str!("../config/scenarios/seed001-agar-wire.toml")
        .replace("friction_coefficient = 1.0", "friction_coefficient = -1.0");
    std::fs::write(&path, text).unwrap();
    let o = shearcut(&["simulate", path.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.contains("`slab.friction_coefficient` = -1: must be > 0 (inf for no slip)"),
        "{err}"
    );
    let o = shearcut(&["check", "seed001-agar-wire"]);
    assert!(o.status.success());
    std::fs::remove_dir_all(dir).ok();
}
