//! Proves that `update()` and `calculate()` (and the on-demand
//! `Trajectory::independent_min_durations`) allocate nothing after construction, with a counting
//! global allocator (this file is its own test binary, so the allocator sees only this test).

use std::sync::atomic::Ordering;

use shearcut_controllers::trajectory::{
    ControlInterface, Synchronization, Trajectory, TrajectoryGenerator, TrajectoryInput,
    TrajectoryOutput, TrajectorySettings, TrajectoryStatus,
};

#[path = "support/counting_allocator.rs"]
mod counting_allocator;

use counting_allocator::{ALLOCATIONS, Counting, TRACK};

#[global_allocator]
static GLOBAL: Counting = Counting;

/// The count is global: the tests measure one at a time.
static SERIAL: std::sync::Mutex<()> = std::sync::Mutex::new(());

fn input(k: usize) -> TrajectoryInput<6> {
    let mut inp = TrajectoryInput::<6>::default();
    for i in 0..6 {
        let x = (k * 7 + i * 3) as f64;
        inp.current_position[i] = (x * 0.37).sin() * 3.0;
        inp.current_velocity[i] = (x * 0.11).cos() * 0.4;
        inp.current_acceleration[i] = (x * 0.23).sin() * 0.3;
        inp.target_position[i] = (x * 0.53).cos() * 4.0;
        inp.target_velocity[i] = (x * 0.71).sin() * 0.2;
        inp.max_velocity[i] = 1.0 + i as f64 * 0.5;
        inp.max_acceleration[i] = 2.0 + (x * 0.3).sin();
        inp.max_jerk[i] = 5.0 + i as f64;
    }
    inp.synchronization = [
        Synchronization::Time,
        Synchronization::Phase,
        Synchronization::None,
    ][k % 3];
    if k % 4 == 3 {
        inp.interface = ControlInterface::Velocity;
    }
    inp
}

#[test]
fn update_and_calculate_do_not_allocate() {
    let _serial = SERIAL.lock().unwrap_or_else(|e| e.into_inner());
    let mut otg = TrajectoryGenerator::<6>::new(TrajectorySettings::default()).unwrap();
    let mut out = TrajectoryOutput::default();
    let mut traj = Trajectory::default();
    let inputs: Vec<TrajectoryInput<6>> = (0..40)
        .collect::<Vec<_>>()
        .iter()
        .map(|&k| input(k))
        .collect();

    // Sanity check that the counter works on this thread.
    TRACK.with(|t| t.set(true));
    let probe = ALLOCATIONS.load(Ordering::SeqCst);
    drop(std::hint::black_box(vec![1u8; 16]));
    assert!(
        ALLOCATIONS.load(Ordering::SeqCst) > probe,
        "counting allocator inactive"
    );

    let before = ALLOCATIONS.load(Ordering::SeqCst);
    let mut finished = 0;
    for inp0 in &inputs {
        otg.calculate(inp0, &mut traj).unwrap();
        std::hint::black_box(traj.independent_min_durations());
        let mut inp = *inp0;
        for _ in 0..2000 {
            if otg.update(&inp, &mut out).unwrap() == TrajectoryStatus::Finished {
                finished += 1;
                break;
            }
            out.pass_to_input(&mut inp);
        }
    }
    let after = ALLOCATIONS.load(Ordering::SeqCst);
    TRACK.with(|t| t.set(false));
    assert_eq!(
        after - before,
        0,
        "update()/calculate()/independent_min_durations() allocated {} times",
        after - before
    );
    assert!(finished > 0);
}

/// One DoF (the lean shortest-only path) and starts outside the limits (braking, with the
/// braking variants' pruning), for 1 and 3 DoFs: no allocation either.
#[test]
fn one_dof_and_braking_starts_do_not_allocate() {
    let _serial = SERIAL.lock().unwrap_or_else(|e| e.into_inner());
    fn case<const N: usize>(k: usize) -> TrajectoryInput<N> {
        let mut inp = TrajectoryInput::<N>::default();
        for i in 0..N {
            let x = (k * 5 + i * 11) as f64;
            inp.current_position[i] = (x * 0.41).sin() * 2.0;
            inp.target_position[i] = (x * 0.29).cos() * 3.0;
            inp.max_velocity[i] = 1.0;
            inp.max_acceleration[i] = 2.0;
            inp.max_jerk[i] = 4.0;
            if k % 2 == 1 {
                // Above the velocity limit, accelerating: braking comes first.
                inp.current_velocity[i] = 1.5 + 0.1 * (x * 0.7).sin();
                inp.current_acceleration[i] = 1.0;
            } else {
                inp.current_velocity[i] = 0.5 * (x * 0.13).cos();
                inp.current_acceleration[i] = 0.5 * (x * 0.17).sin();
            }
        }
        inp
    }
    fn run<const N: usize>(inputs: &[TrajectoryInput<N>]) -> (usize, usize) {
        let otg = TrajectoryGenerator::<N>::new(TrajectorySettings::default()).unwrap();
        let mut traj = Trajectory::default();
        let mut braking = 0;
        TRACK.with(|t| t.set(true));
        let before = ALLOCATIONS.load(Ordering::SeqCst);
        for inp in inputs {
            if otg.calculate(inp, &mut traj) == Ok(TrajectoryStatus::BrakingThenTarget) {
                braking += 1;
            }
            std::hint::black_box(traj.independent_min_durations());
        }
        let after = ALLOCATIONS.load(Ordering::SeqCst);
        TRACK.with(|t| t.set(false));
        (after - before, braking)
    }
    let one: Vec<TrajectoryInput<1>> = (0..40).map(case::<1>).collect();
    let three: Vec<TrajectoryInput<3>> = (0..40).map(case::<3>).collect();
    let (allocated, braking) = run(&one);
    assert_eq!(allocated, 0, "1 DoF: {allocated} allocations");
    assert!(braking > 0);
    let (allocated, braking) = run(&three);
    assert_eq!(allocated, 0, "3 DoFs: {allocated} allocations");
    assert!(braking > 0);
}
