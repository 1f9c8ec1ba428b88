//! The in-process closed loop: determinism, limits, the seed's trend, and
//! agreement with the open-loop model; `shearcut run` end to end.

#[path = "support/binary_run.rs"]
mod binary_run;

use binary_run::{assert_files, assert_success, read_summary, scratch, shearcut};
use nalgebra::Vector3;
use shearcut::closed_loop::{LoopSetup, run_closed_loop, run_closed_loop_on};
use shearcut::commands::simulate::simulate;
use shearcut::controller_choice::ControllerChoice;
use shearcut::cut_record::CutSample;
use shearcut::run_replica::{RunReplica, START_STEP};
use shearcut::scenario::Scenario;

/// Fig. 7's potato cuboid, 6 mm deep, at one ξ, with a coarse section.
fn small_potato(xi: f64) -> Scenario {
    let text = include_str!("../config/scenarios/fig7-potato.toml").to_string()
        + "\n[plant]\nsegments = 2\n\n[section]\nrow_spacing = 0.0005\n";
    let text = text
        .replace(
            "slice_push_ratios = [0.0, 0.33, 0.75, 1.8]",
            &format!("slice_push_ratios = [{xi}]"),
        )
        .replace("depth = 0.02", "depth = 0.006");
    Scenario::parse(&text, "small-potato", "small-potato").unwrap()
}

#[test]
fn lockstep_runs_are_bit_identical_and_respect_the_arm() {
    let s = small_potato(0.75);
    let a = run_closed_loop(&s, ControllerChoice::Slice(0.75)).unwrap();
    let b = run_closed_loop(&s, ControllerChoice::Slice(0.75)).unwrap();
    assert_eq!(a.output.end, shearcut::closed_loop::LoopEnd::Completed);
    assert_eq!(a.output.limit_faults, 0);
    assert!(a.summary.completed);
    assert_eq!(a.output.samples.len(), b.output.samples.len());
    // Debug prints every f64 in its shortest round-trip form: equal text is
    // equal bits.
    assert_eq!(
        format!("{:?}", a.output.samples),
        format!("{:?}", b.output.samples)
    );
    assert_eq!(
        format!("{:?}", a.output.control),
        format!("{:?}", b.output.control)
    );
}

#[test]
fn a_replica_is_the_same_cut_begun_higher() {
    let s = small_potato(0.75);
    let choice = ControllerChoice::Slice(0.75);
    let replica = RunReplica { index: 20 };
    let nominal = LoopSetup::new(&s, choice).unwrap();
    let raised = LoopSetup::on_replica(&s, choice, replica).unwrap();
    // The knife starts straight above where it did, 20 steps (100 µm)
    // higher; the plant puts it where the loop's labels say.
    let (a, b) = (nominal.cut(&s), raised.cut(&s));
    let up = b.start - a.start;
    assert!(
        (up - Vector3::new(0.0, 20.0 * START_STEP, 0.0)).norm() < 1e-15,
        "{up}"
    );
    assert_eq!(raised.plant(&s).unwrap().position(), b.start);
    assert_eq!(b.gap, s.plant.start_gap + 20.0 * START_STEP);
    // So the edge touches 100 µm of normal travel later: at the speed along
    // the velocity s, v_n = s/√(1+ξ²), within a tick either way.
    let r0 = run_closed_loop_on(&s, choice, RunReplica::NOMINAL).unwrap();
    let r1 = run_closed_loop_on(&s, choice, replica).unwrap();
    assert!(r0.summary.completed && r1.summary.completed);
    assert_eq!(r1.replica, replica);
    let v_n = s.controller.speed / (1.0_f64 + 0.75 * 0.75).sqrt();
    let later = r1.output.samples[0].time_s - r0.output.samples[0].time_s;
    let expected = 20.0 * START_STEP / v_n;
    let tick = 1.0 / s.control_loop.rate_hz;
    assert!(
        (later - expected).abs() <= tick + 1e-12,
        "{later} s against {expected} s"
    );
}

#[test]
fn closed_loop_slicing_agrees_with_the_open_loop_model_and_beats_pressing() {
    // The open loop's speed, so that the plant's 1 ms ticks move the knife
    // about as far as the open loop's model steps (the crack advances in
    // row-sized jumps whose timing depends on the step).
    let mut s = small_potato(0.75);
    s.controller.speed = s.motion.speed;
    let open = simulate(&s).unwrap();
    let slice = run_closed_loop(&s, ControllerChoice::Slice(0.75)).unwrap();
    // Work per unit length of edge in contact when the crack first reaches
    // 5 mm: the same cross-section physics whichever loop drives it.
    let at = |v: &[CutSample]| {
        *v.iter()
            .find(|x| x.crack_depth_m >= 0.005)
            .expect("the cut reaches 5 mm")
    };
    let (o, c) = (at(&open.samples), at(&slice.output.samples));
    assert!(
        (c.crack_depth_m - o.crack_depth_m).abs() < 1e-5,
        "{} {}",
        c.crack_depth_m,
        o.crack_depth_m
    );
    assert!(
        (c.work_j_per_m - o.work_j_per_m).abs() < 5e-3 * o.work_j_per_m,
        "closed loop {} J/m vs open loop {} J/m",
        c.work_j_per_m,
        o.work_j_per_m
    );
    // Seed 000 §V.A: slicing at ξ = 0.75 takes less work per unit length
    // than pressing.
    let press = run_closed_loop(&s, ControllerChoice::Press).unwrap();
    let p = at(&press.output.samples);
    assert!(
        p.work_j_per_m > c.work_j_per_m,
        "press {} slice {}",
        p.work_j_per_m,
        c.work_j_per_m
    );
    assert_eq!(press.summary.peak_force_horizontal_n, 0.0);
}

#[test]
fn run_writes_the_results_and_bad_controllers_exit_2() {
    let dir = scratch("run");
    let path = dir.join("small.toml");
    let text = include_str!("../config/scenarios/fig7-potato.toml").to_string()
        + "\n[plant]\nsegments = 2\n\n[section]\nrow_spacing = 0.0005\n\n[controller]\nkind = \"force:5\"\n";
    std::fs::write(&path, text.replace("depth = 0.02", "depth = 0.003")).unwrap();
    let out = dir.join("out");
    let p = path.to_str().unwrap();
    let o = shearcut(&["run", p, "--out", out.to_str().unwrap()]);
    assert_success(&o);
    assert_files(
        &out,
        &[
            "timeseries.csv",
            "controller.csv",
            "summary.json",
            "scenario.toml",
            "forces_work.svg",
            "forces_work.png",
            "controller.svg",
            "controller.png",
        ],
    );
    let summary = read_summary(&out);
    assert_eq!(summary["controller"], "force:5");
    assert_eq!(summary["end"], "completed");
    assert_eq!(summary["limit_faults"], 0);
    for bad in ["pid", "slice:-1", "force:0"] {
        let o = shearcut(&["run", p, "--controller", bad]);
        assert_eq!(o.status.code(), Some(2), "{bad}");
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(err.contains(bad), "{err}");
    }
    std::fs::remove_dir_all(dir).ok();
}

#[test]
fn the_depth_profile_follows_the_objects_silhouette() {
    use shearcut::object_profile::depth_profile;
    // A cuboid: the whole length at every depth.
    let s = small_potato(0.0);
    let p = depth_profile(&s.object.mesh().unwrap()).unwrap();
    for d in [0.001, 0.01, 0.02] {
        assert!(
            (p.contact_length(d) - 0.03).abs() < 1e-9,
            "{}",
            p.contact_length(d)
        );
    }
    assert!((p.height() - 0.025).abs() < 1e-12 && (p.half_width() - 0.015).abs() < 1e-12);
    // A half ellipsoid (length 90 mm, height 35 mm, flat base): the chord at
    // depth d is 90·√(1 − (1 − d/35)²) mm (within the mesh's facets).
    let s = Scenario::load("config/scenarios/fig10-potato-whole.toml").unwrap();
    let p = depth_profile(&s.object.mesh().unwrap()).unwrap();
    for d in [0.002, 0.01, 0.02, 0.03] {
        let z: f64 = 1.0 - d / 0.035;
        let exact = 0.09 * (1.0 - z * z).sqrt();
        assert!(
            (p.contact_length(d) - exact).abs() < 0.03 * exact,
            "d = {d}: {} vs {exact}",
            p.contact_length(d)
        );
    }
}

#[test]
fn the_mpc_sees_a_dome_section_as_its_equivalent_rectangle() {
    use shearcut::object_profile::{depth_profile, surrogate_profile};
    use shearcut::surrogates::surrogate_for;
    // The half potato's crest section, a half ellipse, maps to about 0.9
    // of its width (27.0 of 30 mm measured); a cuboid's is itself.
    for (name, low, high) in [
        ("loop-potato-whole-realtime", 0.88, 0.92),
        ("loop-potato-cuboid", 1.0, 1.0),
    ] {
        let s = Scenario::load(name).unwrap();
        let mesh = s.object.mesh().unwrap();
        let boxed = depth_profile(&mesh).unwrap();
        let surrogate = surrogate_for(&s).unwrap();
        let seen = surrogate_profile(&s, &surrogate, &mesh, 0.025).unwrap();
        let ratio = seen.half_width() / boxed.half_width();
        assert!((low..=high).contains(&ratio), "{name}: {ratio}");
        assert_eq!(seen.height(), boxed.height(), "{name}");
        assert_eq!(
            seen.contact_length(0.01),
            boxed.contact_length(0.01),
            "{name}"
        );
    }
}

#[test]
fn the_mpc_completes_within_its_constraints_on_the_full_plant() {
    // The small potato cuboid, 10 segments, a short blade stroke.
    let text = include_str!("../config/scenarios/fig7-potato.toml").to_string()
        + "\n[plant]\nsegments = 10\n\n[section]\nrow_spacing = 0.0005\n\n[controller]\nblade_budget = 0.004\n";
    let text = text.replace("depth = 0.02", "depth = 0.006");
    let s = Scenario::parse(&text, "mpc-potato", "mpc-potato").unwrap();
    let a = run_closed_loop(&s, ControllerChoice::Mpc).unwrap();
    assert_eq!(a.controller, "mpc");
    assert_eq!(a.output.end, shearcut::closed_loop::LoopEnd::Completed);
    assert_eq!(a.output.limit_faults, 0);
    assert_eq!(a.output.fallbacks, 0);
    assert!(a.summary.completed);
    // The blade budget holds (net travel towards the tip).
    let travel = a
        .output
        .samples
        .iter()
        .map(|x| x.tangential_displacement_m)
        .fold(0.0, f64::max);
    assert!(travel <= 0.004, "travel {travel}");
    // It planned every 10 ticks (100 Hz) and sliced (|ξ| > 0; negative on
    // a sawing back stroke) for most of the cut.
    let plans = a
        .output
        .control
        .iter()
        .filter(|c| c.xi_plan.abs() > 0.0)
        .count();
    assert!(plans > a.output.control.len() / 2, "{plans}");
    // Lockstep: bit-identical on a rerun.
    let b = run_closed_loop(&s, ControllerChoice::Mpc).unwrap();
    assert_eq!(
        format!("{:?}", a.output.samples),
        format!("{:?}", b.output.samples)
    );
    assert_eq!(
        format!("{:?}", a.output.control),
        format!("{:?}", b.output.control)
    );
}
