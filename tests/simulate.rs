//! `shearcut simulate` end to end: files, columns, summary, physics trends.

#[path = "support/binary_run.rs"]
mod binary_run;

use binary_run::{assert_files, assert_success, read_summary, scratch, shearcut};

#[test]
fn fig7_potato_writes_results_with_the_seed_trends() {
    let dir = scratch("sim");
    let o = shearcut(&["simulate", "fig7-potato", "--out", dir.to_str().unwrap()]);
    assert_success(&o);
    assert_files(
        &dir,
        &[
            "timeseries.csv",
            "summary.json",
            "scenario.toml",
            "forces_work.svg",
            "forces_work.png",
        ],
    );
    let summary = read_summary(&dir);
    let cuts = summary["cuts"].as_array().unwrap();
    assert_eq!(cuts.len(), 4);
    let work: Vec<f64> = cuts.iter().map(|c| c["work_j"].as_f64().unwrap()).collect();
    for c in cuts {
        for key in [
            "work_j",
            "peak_force_vertical_n",
            "peak_force_horizontal_n",
            "max_deformation_m",
            "cut_depth_m",
        ] {
            assert!(c[key].as_f64().unwrap().is_finite(), "{key}");
        }
        assert_eq!(c["completed"], true);
        assert!((c["cut_depth_m"].as_f64().unwrap() - 0.02).abs() < 1e-3);
    }
    // Seed 000 §V.A: total work falls from ξ = 0 to 0.33 to 0.75 and rises
    // again at 1.8 (friction over the longer path outgrows the saturating
    // toughness drop).
    assert!(
        work[0] > work[1] && work[1] > work[2] && work[3] > work[2],
        "{work:?}"
    );
    // Pressing makes no horizontal force; slicing does, and more with ξ.
    let fh: Vec<f64> = cuts
        .iter()
        .map(|c| c["peak_force_horizontal_n"].as_f64().unwrap())
        .collect();
    assert!(
        fh[0].abs() < 1e-12 && fh[1] < fh[2] && fh[2] < fh[3],
        "{fh:?}"
    );
    // Slicing fractures earlier: less deformation before the first fracture.
    let first: Vec<f64> = cuts
        .iter()
        .map(|c| c["first_fracture_displacement_m"].as_f64().unwrap())
        .collect();
    assert!(
        first[0] > first[1] && first[1] > first[2] && first[2] > first[3],
        "{first:?}"
    );
    // The time series has a header of 21 columns (see cut_record::CutSample).
    let csv = std::fs::read_to_string(dir.join("timeseries.csv")).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(header.len(), 21);
    assert_eq!(header[0], "xi");
    assert!(lines.count() > 1000);
    std::fs::remove_dir_all(dir).ok();
}

#[test]
fn curved_knife_runs_the_plant_and_reports_torques() {
    let dir = scratch("sim-chef");
    let path = dir.join("chef.toml");
    // Fig. 8 shortened: two pieces, 4 mm deep, a coarser section mesh.
    let text = include_str!("../config/scenarios/fig8-potato.toml")
        .replace("z0 = [0.02, 0.0765, 0.1135, 0.14]", "z0 = [0.02, 0.14]")
        .replace("depth = 0.02", "depth = 0.004")
        .replace(
            "segments = 10",
            "segments = 5\n\n[section]\nrow_spacing = 0.0005",
        );
    std::fs::write(&path, text).unwrap();
    let out = dir.join("out");
    let o = shearcut(&[
        "simulate",
        path.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_success(&o);
    let summary = read_summary(&out);
    assert_eq!(summary["model"], "multi-section plant");
    let cuts = summary["cuts"].as_array().unwrap();
    assert_eq!(cuts.len(), 2);
    for c in cuts {
        assert_eq!(c["completed"], true);
        // The sensor sits behind the heel: the cutting force has a lever arm.
        assert!(c["peak_torque_nm"].as_f64().unwrap() > 0.0);
    }
    // On the curved part of the edge (z0 = 0.14) the pressing knife is also
    // pushed towards the heel; on the flat part (z0 = 0.02) it is not.
    let fh = |i: usize| cuts[i]["peak_force_horizontal_n"].as_f64().unwrap();
    assert!(fh(0) < 1e-9 && fh(1) > 0.1, "{} {}", fh(0), fh(1));
    std::fs::remove_dir_all(dir).ok();
}

#[test]
fn blade_too_short_for_the_travel_is_refused() {
    let dir = scratch("sim-short");
    let path = dir.join("short.toml");
    let text = include_str!("../config/scenarios/fig7-potato.toml").replace(
        "slice_push_ratios = [0.0, 0.33, 0.75, 1.8]",
        "slice_push_ratios = [0.0, 9.0]",
    );
    std::fs::write(&path, text).unwrap();
    let o = shearcut(&["simulate", path.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("motion.slice_push_ratios[1]") && err.contains("exceeds the edge"),
        "{err}"
    );
    std::fs::remove_dir_all(dir).ok();
}

#[test]
fn mesh_object_is_read_relative_to_the_scenario_and_bad_meshes_exit_2() {
    let dir = std::env::temp_dir().join(format!("shearcut-sim-mesh-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    // An open mesh (a tetrahedron missing a face) next to the scenario.
    std::fs::write(
        dir.join("open.obj"),
        "v 0 0 0\nv 0.03 0 0\nv 0 0.03 0\nv 0 0 0.03\nf 1 3 2\nf 1 2 4\nf 2 3 4\n",
    )
    .unwrap();
    let text = include_str!("../config/scenarios/fig8-potato.toml").replace(
        "kind = \"cuboid\"\nwidth = 0.03\nheight = 0.025\nlength = 0.03",
        "kind = \"mesh\"\npath = \"open.obj\"",
    );
    assert!(text.contains("open.obj"));
    let path = dir.join("mesh.toml");
    std::fs::write(&path, text).unwrap();
    let o = shearcut(&["simulate", path.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("not closed") && err.lines().count() == 1,
        "{err}"
    );
    std::fs::remove_dir_all(dir).ok();
}
