//! The order in which the executor's threads take a batch's jobs when
//! there are several: the longest expected first (Graham's LPT rule), so
//! that the last job to finish is a short one and the other threads idle
//! for less time at the end of the batch. The order of taking changes no result: runs share
//! nothing, and results are kept and written in job order.
//!
//! The expectation is known before running and depends on the job alone
//! ([`expected_ticks`]), so the order is deterministic.

use crate::controller_choice::ControllerChoice;
use crate::tune::job_list::Job;

/// The loop ticks a job is expected to run: its cut's depth at the
/// controller's nominal normal speed, at the loop's rate, at most
/// `max_duration × rate_hz`.
///
/// The nominal normal speed is `speed` for pressing and the force loop,
/// `speed · cos α` with tan α = ξ for slicing at ξ (the baselines move at
/// `speed` along their velocity), and `max_normal_speed` for the MPC (its
/// plan's top descent). A scenario without a set depth (its default is a
/// fraction of the object's height, known only once the object is built)
/// is expected to run its `max_duration`. The run's cost per tick (the
/// MPC's plans, the plant's segments) is not counted: the rule only ranks
/// jobs, and within one scenario and controller it is the ticks that
/// differ.
pub fn expected_ticks(job: &Job) -> f64 {
    let s = &job.scenario;
    let c = &s.controller;
    let normal_speed = match job.choice {
        ControllerChoice::Press | ControllerChoice::Force(_) => c.speed,
        ControllerChoice::Slice(xi) => c.speed * xi.atan().cos(),
        ControllerChoice::Mpc => c.max_normal_speed,
    };
    let duration = s
        .motion
        .depth
        .map_or(c.max_duration, |d| (d / normal_speed).min(c.max_duration));
    duration * s.control_loop.rate_hz
}

/// The indices of `expected` (one value per job, in job order) from the
/// largest value to the smallest; equal values keep job order.
pub fn longest_first(expected: &[f64]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..expected.len()).collect();
    order.sort_by(|&a, &b| expected[b].total_cmp(&expected[a]));
    order
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tune::job_list::list_of;

    #[test]
    fn slower_descents_are_expected_to_run_longer() {
        // The cuboid: 20 mm deep at 1 kHz. Pressing at 20 mm/s: 1 s, 1000
        // ticks; at 30 mm/s two thirds of that; slicing at ξ = 0.75
        // descends at 0.8 of its speed.
        let list = list_of(
            r#"
            scenarios = ["loop-potato-cuboid"]
            [[controllers]]
            kind = ["press", "slice:0.75"]
            grid = { speed = [0.02, 0.03] }
            "#,
        );
        let ticks: Vec<f64> = list.jobs.iter().map(expected_ticks).collect();
        let want = [1000.0, 2000.0 / 3.0, 1250.0, 2500.0 / 3.0];
        for (got, want) in ticks.iter().zip(want) {
            assert!((got - want).abs() < 1e-9 * want, "{ticks:?}");
        }
        assert_eq!(longest_first(&ticks), vec![2, 0, 3, 1]);
    }

    #[test]
    fn longest_expected_first_and_ties_in_job_order() {
        assert_eq!(
            longest_first(&[1.0, 3.0, 2.0, 3.0, 1.0]),
            vec![1, 3, 2, 0, 4]
        );
        assert!(longest_first(&[]).is_empty());
    }
}
