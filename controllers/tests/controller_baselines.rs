//! The baselines in closed loop with a synthetic arm: they hold their
//! ratio and speed, keep the blade budget, stop at the target depth, hold a
//! force setpoint, and never send a command the arm refuses.

mod synthetic_arm;

use shearcut_controllers::controller::{
    ConstantSlice, Controller, CutPhase, ForceFeedback, ForceFeedbackGains,
};
use shearcut_sim::arm::ArmStatus;
use synthetic_arm::{SyntheticArm, task};

/// Runs `c` for `ticks` or until it is done and the knife is at rest;
/// returns the arm.
fn run(c: &mut dyn Controller, arm: &mut SyntheticArm, ticks: usize) {
    let mut m = arm.measure(ArmStatus::Moving);
    for _ in 0..ticks {
        let command = c.tick(&m);
        m = arm.step(&command);
        if c.telemetry().phase == CutPhase::Done && arm.velocity.norm() < 1e-12 {
            break;
        }
    }
}

#[test]
fn constant_slice_moves_at_its_ratio_and_speed_within_the_arm_limits() {
    let (xi, speed) = (0.75, 0.02);
    let mut c = ConstantSlice::new(&task(1.0, 1.0), xi, speed).unwrap();
    let mut arm = SyntheticArm::new(0.0);
    run(&mut c, &mut arm, 500);
    assert_eq!(arm.refused, 0);
    let v = arm.velocity;
    // The shaper reaches the planned velocity exactly (velocity interface).
    assert!((v.z / -v.y - xi).abs() < 1e-12, "ratio {}", v.z / -v.y);
    assert!(
        (v.norm() - speed).abs() < 1e-12 * speed,
        "speed {}",
        v.norm()
    );
    assert_eq!(c.name(), "slice:0.75");
    let t = c.telemetry();
    assert!((t.slice_push_ratio - xi).abs() < 1e-12);
}

#[test]
fn pressing_has_no_tangential_motion() {
    let mut c = ConstantSlice::press(&task(1.0, 1.0), 0.02).unwrap();
    let mut arm = SyntheticArm::new(0.0);
    run(&mut c, &mut arm, 300);
    assert_eq!(arm.refused, 0);
    assert_eq!(arm.position.z, 0.0);
    assert!((arm.velocity.y + 0.02).abs() < 1e-12);
}

#[test]
fn the_blade_budget_is_never_exceeded_and_the_cut_finishes_by_pressing() {
    // ξ = 1 at 0.05 m/s would use 30 mm of blade for 30 mm depth; only 5 mm is left.
    let budget = 0.005;
    let mut c = ConstantSlice::new(&task(0.03, budget), 1.0, 0.05).unwrap();
    let mut arm = SyntheticArm::new(0.0);
    let mut max_z: f64 = 0.0;
    let mut m = arm.measure(ArmStatus::Moving);
    for _ in 0..5000 {
        let command = c.tick(&m);
        m = arm.step(&command);
        max_z = max_z.max(arm.position.z);
    }
    assert_eq!(arm.refused, 0);
    assert!(max_z <= budget, "travel {max_z} > budget {budget}");
    // Most of the budget is used (stopping takes a few µm at these limits).
    assert!(max_z > 0.95 * budget, "travel {max_z}");
    assert!(arm.depth() >= 0.03, "depth {}", arm.depth());
}

#[test]
fn controllers_stop_at_the_target_depth() {
    let target = 0.01;
    let mut c = ConstantSlice::new(&task(target, 1.0), 0.5, 0.02).unwrap();
    let mut arm = SyntheticArm::new(0.0);
    run(&mut c, &mut arm, 5000);
    assert_eq!(c.telemetry().phase, CutPhase::Done);
    assert!(
        arm.velocity.norm() < 1e-12,
        "velocity {}",
        arm.velocity.norm()
    );
    assert_eq!(arm.refused, 0);
    let depth = -arm.position.y;
    // Stopping from 0.02 m/s under the shaper's limits takes well under 0.1 mm.
    assert!(depth >= target && depth < target + 1e-4, "depth {depth}");
}

#[test]
fn force_feedback_holds_the_setpoint_on_a_spring() {
    // F = k·depth: the loop settles where the spring force is the setpoint.
    let (k, setpoint) = (2000.0, 20.0);
    let gains = ForceFeedbackGains::for_setpoint(setpoint, 0.02);
    let mut c = ForceFeedback::new(&task(1.0, 1.0), setpoint, gains, 0.0, 0.02).unwrap();
    let mut arm = SyntheticArm::new(k);
    let mut m = arm.measure(ArmStatus::Moving);
    let mut peak: f64 = 0.0;
    for _ in 0..6000 {
        let command = c.tick(&m);
        m = arm.step(&command);
        peak = peak.max(m.wrench[1]);
    }
    assert_eq!(arm.refused, 0);
    // k·k_p = 2 /s, k·k_i = 1 /s²: a double pole at −1 /s; the small
    // overshoot (the PI's zero) has decayed below 0.5 % after 6 s.
    assert!(
        (m.wrench[1] - setpoint).abs() < 5e-3 * setpoint,
        "force {}",
        m.wrench[1]
    );
    // The approach is P-dominated (integral separation): overshoot < 5 %.
    assert!(peak < 1.05 * setpoint, "peak {peak}");
    assert_eq!(c.name(), "force:20");
}

#[test]
fn bad_settings_are_refused_naming_the_key() {
    let t = task(0.01, 0.0);
    assert_eq!(
        ConstantSlice::new(&t, -1.0, 0.02).unwrap_err().key,
        "slice_push_ratio"
    );
    assert_eq!(ConstantSlice::new(&t, 0.5, 0.0).unwrap_err().key, "speed");
    let g = ForceFeedbackGains::for_setpoint(10.0, 0.02);
    assert_eq!(
        ForceFeedback::new(&t, f64::NAN, g, 0.0, 0.02)
            .unwrap_err()
            .key,
        "force_setpoint"
    );
    let mut bad = t;
    bad.target_depth = 0.0;
    assert_eq!(
        ConstantSlice::new(&bad, 0.5, 0.02).unwrap_err().key,
        "target_depth"
    );
}
