//! A plan that chooses to saw only after the knife has stopped
//! tangentially at its stroke's end (it pressed on there): the stroke
//! reverses at once, without stopping the normal motion.

mod synthetic_arm;

use shearcut_controllers::controller::{BladeBudget, SawingStroke, StrokePhase, VelocityShaper};
use shearcut_sim::arm::ArmStatus;
use synthetic_arm::{PERIOD, SyntheticArm, task};

#[test]
fn a_late_choice_to_saw_reverses_without_stopping_the_normal_motion() {
    let blade = 0.004;
    let task = task(0.02, blade);
    let mut shaper = VelocityShaper::new(PERIOD, &task.limits).unwrap();
    let mut budget = BladeBudget::new(blade);
    let mut stroke = SawingStroke::new(4);
    let mut arm = SyntheticArm::new(0.0);
    let (v_n, v_t) = (0.03, 0.045);
    let mut m = arm.measure(ArmStatus::Moving);
    // Not sawing: the blade's end ramps the tangential speed to rest while
    // the knife presses on.
    for _ in 0..400 {
        budget.observe(&m);
        let c = stroke.command(&mut shaper, &budget, &task, v_n, v_t, false);
        m = arm.step(&c);
    }
    assert!(
        m.velocity.z.abs() < 1e-9,
        "still sliding at {}",
        m.velocity.z
    );
    assert!(
        (-m.velocity.y - v_n).abs() < 1e-9,
        "pressing at {}",
        m.velocity.y
    );
    // A plan now wants to saw: the stroke reverses this tick, and the
    // knife goes on cutting down at its speed while the tangential axis
    // speeds up backwards (50 ticks: the back stroke's own end is 89 ms
    // away).
    budget.observe(&m);
    let c = stroke.command(&mut shaper, &budget, &task, v_n, v_t, true);
    assert_eq!(stroke.reversals(), 1);
    assert_eq!(stroke.direction(), -1.0);
    assert_eq!(stroke.phase(), StrokePhase::Stroking);
    m = arm.step(&c);
    for _ in 0..50 {
        assert!(
            (-m.velocity.y - v_n).abs() < 1e-9,
            "normal {}",
            m.velocity.y
        );
        budget.observe(&m);
        let c = stroke.command(&mut shaper, &budget, &task, v_n, v_t, true);
        m = arm.step(&c);
    }
    assert!(
        (m.velocity.z + v_t).abs() < 1e-9,
        "tangential {}",
        m.velocity.z
    );
    assert!(
        (-m.velocity.y - v_n).abs() < 1e-9,
        "normal {}",
        m.velocity.y
    );
    assert_eq!(arm.refused, 0);
}
