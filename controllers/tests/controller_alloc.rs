//! Proves that the baselines' `tick()` allocates nothing after construction,
//! with a counting global allocator (its own test binary).

mod synthetic_arm;

use std::sync::atomic::Ordering;

use shearcut_controllers::controller::{
    ConstantSlice, Controller, ForceFeedback, ForceFeedbackGains,
};
use shearcut_sim::arm::ArmStatus;
use synthetic_arm::{SyntheticArm, task};

#[path = "support/counting_allocator.rs"]
mod counting_allocator;

use counting_allocator::{ALLOCATIONS, Counting, TRACK};

#[global_allocator]
static GLOBAL: Counting = Counting;

/// Allocations made by `ticks` ticks of `c` against a spring arm, through
/// approach, contact, the blade budget running out and the target depth.
fn allocations(c: &mut dyn Controller, ticks: usize) -> usize {
    let mut arm = SyntheticArm::new(2000.0);
    let mut m = arm.measure(ArmStatus::Moving);
    ALLOCATIONS.store(0, Ordering::SeqCst);
    TRACK.with(|t| t.set(true));
    for _ in 0..ticks {
        let command = c.tick(&m);
        m = arm.step(&command);
    }
    TRACK.with(|t| t.set(false));
    ALLOCATIONS.load(Ordering::SeqCst)
}

#[test]
fn controller_ticks_allocate_nothing() {
    let t = task(0.01, 0.002);
    let mut slice = ConstantSlice::new(&t, 1.0, 0.02).unwrap();
    assert_eq!(allocations(&mut slice, 2000), 0);
    let mut press = ConstantSlice::press(&t, 0.02).unwrap();
    assert_eq!(allocations(&mut press, 2000), 0);
    let g = ForceFeedbackGains::for_setpoint(10.0, 0.02);
    let mut force = ForceFeedback::new(&t, 10.0, g, 0.5, 0.02).unwrap();
    assert_eq!(allocations(&mut force, 2000), 0);
    // In the same test: the counter is global, tests run in parallel.
    //
    // The MPC: ticks between plans allocate nothing; each solve of a plan
    // (two while sawing is considered) allocates one block inside clarabel
    // 0.11.1 itself (`Timers::reset` clears the solve timer's nested maps,
    // and the next `timeit!` re-creates one), nothing in our code. Counted
    // exactly so that any new allocation shows. 4 mm of blade for 40 mm of
    // depth: the plans consider sawing and the knife reverses.
    use shearcut_controllers::mpc::{DepthProfile, Mpc, MpcSettings};
    // The MPC on a widening object, against a spring arm, after its first
    // plan (which sets up clarabel's timer maps).
    let started = |settings: &MpcSettings| {
        let profile = DepthProfile::new(vec![0.0, 0.02], vec![0.01, 0.05], 0.03, 0.015).unwrap();
        let q = synthetic_arm::QuadraticModel;
        let mut mpc = Mpc::new(&task(0.04, 0.004), settings, q, profile, 0.5).unwrap();
        let mut arm = SyntheticArm::new(2000.0);
        let m = arm.measure(ArmStatus::Moving);
        let command = mpc.tick(&m);
        let m = arm.step(&command);
        (mpc, arm, m)
    };
    let (mut mpc, mut arm, mut m) = started(&MpcSettings::default());
    let (mut plans, mut in_plans, mut between) = (0, 0, 0);
    let solves_before = mpc.stats().solves;
    for _ in 0..2000 {
        ALLOCATIONS.store(0, Ordering::SeqCst);
        TRACK.with(|t| t.set(true));
        let command = mpc.tick(&m);
        TRACK.with(|t| t.set(false));
        m = arm.step(&command);
        let n = ALLOCATIONS.load(Ordering::SeqCst);
        if mpc.replanned() {
            plans += 1;
            in_plans += n;
        } else {
            between += n;
        }
    }
    let solves = mpc.stats().solves - solves_before;
    assert!(plans > 50, "{plans} plans");
    assert!(
        solves > plans,
        "{solves} solves in {plans} plans: sawing never considered"
    );
    assert!(mpc.stroke().reversals() > 0, "no reversal");
    // The tick allocates nothing, planning ticks included: the solves (and
    // clarabel's one allocation per solve) run on the planner thread.
    assert_eq!(between, 0);
    assert_eq!(in_plans, 0, "{solves} solves off the tick");

    // The plan itself, made on the tick (inline) with every check a plan
    // makes (sawing, holding the ratio, `min_saving`, and the finish's price,
    // `finish_gap`), and copied into
    // the planner's slot (`MpcPlan::clone_from` reuses its buffers):
    // nothing in our code, one block per solve inside clarabel.
    use shearcut_controllers::planner::{LatencyMode, PlannerSettings};
    let settings = MpcSettings {
        min_saving: 0.005,
        finish_gap: true,
        planner: PlannerSettings {
            latency: LatencyMode::Inline,
            ..PlannerSettings::default()
        },
        ..MpcSettings::default()
    };
    let (mut mpc, mut arm, mut m) = started(&settings);
    let solves_before = mpc.stats().solves;
    ALLOCATIONS.store(0, Ordering::SeqCst);
    TRACK.with(|t| t.set(true));
    for _ in 0..2000 {
        let command = mpc.tick(&m);
        m = arm.step(&command);
    }
    TRACK.with(|t| t.set(false));
    let solves = mpc.stats().solves - solves_before;
    assert!(solves > 50, "{solves} solves");
    assert_eq!(ALLOCATIONS.load(Ordering::SeqCst) as u64, solves);
}
