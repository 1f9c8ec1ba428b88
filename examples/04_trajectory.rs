//! # 04: the jerk-limited trajectory generator
//!
//! Shows our time-optimal, jerk-limited online trajectory generator
//! (`shearcut_controllers::trajectory`, docs/trajectory.md): a knife moved
//! on three axes from rest to a target with the Franka FR3's Cartesian
//! limits (3 m/s, 9 m/s², 4500 m/s³), the three axes synchronised so they
//! arrive together.
//!
//! 1. Offline: `calculate` gives the whole trajectory; the example prints
//!    its duration and each axis's analytic velocity and acceleration
//!    extrema, all within the limits.
//! 2. Online: `update` once per 1 ms control cycle, the output fed back as
//!    the next input (an arm that follows its commands exactly); the example
//!    prints the commanded state every 50 cycles until the target is
//!    reached, which takes the same number of cycles as the duration.
//!
//! ```sh
//! cargo run --release --example 04_trajectory
//! ```

use shearcut_controllers::trajectory::{
    Trajectory, TrajectoryError, TrajectoryGenerator, TrajectoryInput, TrajectoryOutput,
    TrajectorySettings, TrajectoryStatus,
};

/// The move: from rest at the start to rest at the target, m.
fn input() -> TrajectoryInput<3> {
    TrajectoryInput::<3> {
        current_position: [0.0, 0.10, -0.20],
        target_position: [0.0, -0.02, 0.10],
        max_velocity: [3.0; 3],     // m/s
        max_acceleration: [9.0; 3], // m/s²
        max_jerk: [4500.0; 3],      // m/s³
        ..Default::default()
    }
}

fn main() -> Result<(), TrajectoryError> {
    // The generator's control cycle is 1 ms by default.
    let mut otg = TrajectoryGenerator::<3>::new(TrajectorySettings::default())?;
    let mut input = input();

    let mut trajectory = Trajectory::<3>::default();
    otg.calculate(&input, &mut trajectory)?;
    println!("duration {:.6} s", trajectory.duration());
    for (axis, e) in ["x", "y", "z"].iter().zip(trajectory.extrema()) {
        println!(
            "  {axis}: velocity in [{:+.4}, {:+.4}] m/s, acceleration in [{:+.3}, {:+.3}] m/s²",
            e.velocity.min, e.velocity.max, e.acceleration.min, e.acceleration.max
        );
    }

    println!("cycle   y (m)     z (m)     vy (m/s)  vz (m/s)");
    let mut output = TrajectoryOutput::<3>::default();
    let mut cycles = 0u32;
    loop {
        let status = otg.update(&input, &mut output)?;
        cycles += 1;
        if cycles.is_multiple_of(50) || status == TrajectoryStatus::Finished {
            println!(
                "{cycles:5} {:+.5} {:+.5} {:+.5} {:+.5}",
                output.new_position[1],
                output.new_position[2],
                output.new_velocity[1],
                output.new_velocity[2]
            );
        }
        if status == TrajectoryStatus::Finished {
            break;
        }
        output.pass_to_input(&mut input);
    }
    println!("target reached after {cycles} cycles of 1 ms");
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The offline trajectory respects every limit (analytic extrema,
    /// within 1e-12 relative: the generator's own guarantee) and ends at the
    /// target; the axes are synchronised, so each ends at the same duration.
    #[test]
    fn the_move_is_within_the_limits_and_reaches_the_target() {
        let otg = TrajectoryGenerator::<3>::new(TrajectorySettings::default()).unwrap();
        let input = input();
        let mut trajectory = Trajectory::<3>::default();
        otg.calculate(&input, &mut trajectory).unwrap();
        for e in trajectory.extrema() {
            assert!(e.velocity.max.abs().max(e.velocity.min.abs()) <= 3.0 * (1.0 + 1e-12));
            assert!(e.acceleration.max.abs().max(e.acceleration.min.abs()) <= 9.0 * (1.0 + 1e-12));
        }
        let (mut p, mut v, mut a) = ([0.0; 3], [0.0; 3], [0.0; 3]);
        trajectory.at_time(trajectory.duration(), &mut p, &mut v, &mut a);
        for i in 0..3 {
            assert!((p[i] - input.target_position[i]).abs() < 1e-8, "{p:?}");
            assert!(v[i].abs() < 1e-8, "{v:?}");
        }
    }

    /// The example runs as a user runs it (`cargo run --example`): `main`
    /// prints its output and succeeds.
    #[test]
    fn the_example_runs() {
        main().unwrap();
    }
}
