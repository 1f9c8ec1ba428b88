//! Braking from start states outside the limits, against durations recorded from ruckig 0.19.4
//! (`scripts/otg_vs_ruckig.sh 100000 42`, the external oracle): the braking pre-phase must not
//! make the whole trajectory slower than ruckig's, and after it every limit holds.

use shearcut_controllers::trajectory::{
    Trajectory, TrajectoryGenerator, TrajectoryInput, TrajectorySettings, TrajectoryStatus,
};

fn check_after_braking<const N: usize>(inp: &TrajectoryInput<N>, t: &Trajectory<N>) {
    for i in 0..N {
        let p = t.profile(i);
        let e = p.end();
        assert!((e.position - inp.target_position[i]).abs() < 1e-8);
        assert!((e.velocity - inp.target_velocity[i]).abs() < 1e-8);
        assert!((e.acceleration - inp.target_acceleration[i]).abs() < 1e-10);
        let x = p.extrema_from(p.brake_segments());
        let lim = |l: f64| l * (1.0 + 1e-12);
        assert!(x.velocity.max <= lim(inp.max_velocity[i]), "{x:?}");
        assert!(-x.velocity.min <= lim(inp.max_velocity[i]), "{x:?}");
        assert!(x.acceleration.max <= lim(inp.max_acceleration[i]), "{x:?}");
        assert!(-x.acceleration.min <= lim(inp.max_acceleration[i]), "{x:?}");
    }
}

/// v0 + a0²/(2J) = 4.41 ≫ v_max = 0.81: the overshoot is unavoidable. Braking by holding the
/// deepest safe acceleration took 49.83 s in total; the earliest (bang-bang) return into the
/// safe set takes no longer than ruckig's 48.9406 s.
#[test]
fn unavoidable_overshoot_brakes_no_slower_than_ruckig() {
    let inp = TrajectoryInput::<1> {
        current_position: [-5.543822476963744],
        current_velocity: [0.47402610614486723],
        current_acceleration: [1.3291742693353503],
        target_position: [4.093611068103768],
        target_velocity: [-0.19854725579183263],
        max_velocity: [0.8096662710402359],
        max_acceleration: [10.79535781776441],
        max_jerk: [0.22460029340587973],
        ..Default::default()
    };
    let otg = TrajectoryGenerator::<1>::new(TrajectorySettings::default()).unwrap();
    let mut t = Trajectory::default();
    let s = otg.calculate(&inp, &mut t).unwrap();
    assert_eq!(s, TrajectoryStatus::BrakingThenTarget);
    let ruckig = 48.940_638_716_398_92;
    assert!(
        t.duration() <= ruckig + 1e-9 * ruckig,
        "{} > {ruckig}",
        t.duration()
    );
    check_after_braking(&inp, &t);
}

/// Three DoFs; DoF 2 starts below its velocity limit (v0 = −1.634 < −1.474). Its faster
/// braking variant cannot last exactly the common duration (a blocked interval), the other one
/// (braking to rest at the limit velocity) can. Keeping only one variant gave 5.511 s against
/// ruckig's 4.2844 s.
#[test]
fn synchronisation_uses_the_other_braking_variant() {
    let inp = TrajectoryInput::<3> {
        current_position: [8.834198820297932, -0.4075053638637192, 2.6593968322115487],
        current_velocity: [
            -0.9436706159174513,
            -0.3119713527074677,
            -1.6342005297236946,
        ],
        current_acceleration: [
            0.47463758439895715,
            -0.10320228645325541,
            0.01215921010668973,
        ],
        target_position: [0.2325022112403717, -0.6748534985655558, -0.1346669720234973],
        target_velocity: [
            0.15187675460821448,
            -0.14531343950486683,
            -0.9776210260909995,
        ],
        target_acceleration: [1.1729428096311068, 0.0, 0.45533713625511907],
        max_velocity: [4.539153577254801, 6.301894968450758, 1.4737181350672244],
        max_acceleration: [2.8792073763183175, 2.4007534542615665, 11.232484478365793],
        max_jerk: [10.265169744604643, 10.747675131208586, 1.461328879270179],
        ..Default::default()
    };
    let otg = TrajectoryGenerator::<3>::new(TrajectorySettings::default()).unwrap();
    let mut t = Trajectory::default();
    let s = otg.calculate(&inp, &mut t).unwrap();
    assert_eq!(s, TrajectoryStatus::BrakingThenTarget);
    let ruckig = 4.284_395_018_904_4;
    assert!(
        t.duration() <= ruckig + 1e-9 * ruckig,
        "{} > {ruckig}",
        t.duration()
    );
    let longest = t
        .independent_min_durations()
        .into_iter()
        .fold(0.0, f64::max);
    assert!(t.duration() >= longest - 1e-12);
    for i in 0..3 {
        assert!((t.profile(i).duration() - t.duration()).abs() < 1e-12 * (1.0 + t.duration()));
    }
    check_after_braking(&inp, &t);
}
