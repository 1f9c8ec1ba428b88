//! Random trajectory cases drawn from ruckig's test distributions, shared by
//! the stress and property tests and the benchmark: positions N(0, 4),
//! velocities and accelerations N(0, 0.8) (zero with some probability),
//! limits U(0.1, 12) plus the target value's magnitude.

use rand::Rng;
use shearcut_controllers::trajectory::TrajectoryInput;

/// A normal sample by Box–Muller.
pub fn normal<R: Rng>(rng: &mut R, sd: f64) -> f64 {
    let u1: f64 = rng.random_range(f64::EPSILON..1.0);
    let u2: f64 = rng.random();
    sd * (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
}

/// One random case with `N` DoFs.
pub fn random_input<const N: usize, R: Rng>(rng: &mut R) -> TrajectoryInput<N> {
    let mut inp = TrajectoryInput::<N>::default();
    for i in 0..N {
        let mut maybe = |p: f64, sd: f64| {
            if rng.random::<f64>() < p {
                normal(rng, sd)
            } else {
                0.0
            }
        };
        inp.current_position[i] = maybe(1.0, 4.0);
        inp.current_velocity[i] = maybe(0.9, 0.8);
        inp.current_acceleration[i] = maybe(0.8, 0.8);
        inp.target_position[i] = maybe(1.0, 4.0);
        inp.target_velocity[i] = maybe(0.7, 0.8);
        inp.target_acceleration[i] = maybe(0.6, 0.8);
        inp.max_velocity[i] = rng.random_range(0.1..12.0) + inp.target_velocity[i].abs();
        inp.max_acceleration[i] = rng.random_range(0.1..12.0) + inp.target_acceleration[i].abs();
        inp.max_jerk[i] = rng.random_range(0.1..12.0);
    }
    inp
}

/// Start states from which no limit violation is unavoidable.
pub fn start_is_safe<const N: usize>(inp: &TrajectoryInput<N>) -> bool {
    (0..N).all(|i| {
        let (v, a) = (inp.current_velocity[i], inp.current_acceleration[i]);
        let (vm, am, j) = (
            inp.max_velocity[i],
            inp.max_acceleration[i],
            inp.max_jerk[i],
        );
        a.abs() <= am && v.abs() <= vm && v.abs() + a * a / (2.0 * j) <= vm
    })
}
