//! Lockstep planning: plans become visible exactly `ticks` ticks after
//! their request, runs are bit-identical whatever the planner thread's
//! timing, and equal to planning inline delayed by `ticks`.

#[path = "support/stage_plan_job.rs"]
mod stage_plan_job;
#[path = "support/watchdog.rs"]
mod watchdog;

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use shearcut_controllers::planner::{LatencyPolicy, Planner, SubmitStatus};
use stage_plan_job::{CutRequest, StageJob, StagePlan};
use watchdog::within_watchdog;

fn submit_code(s: SubmitStatus) -> u64 {
    match s {
        SubmitStatus::Accepted => 0,
        SubmitStatus::InFlight => 1,
        SubmitStatus::JobPanicked => 2,
    }
}

/// A closed loop of `ticks` ticks: the knife advances by the plan in
/// force, and every tick asks for a plan from the state reached (refused
/// while one is in flight). Returns per tick: the plan's bits, its age,
/// request tick, freshness and the submit's outcome.
fn closed_loop(job: StageJob, policy: LatencyPolicy, ticks: u64) -> Vec<Vec<u64>> {
    let mut planner = Planner::new(job, StagePlan::default(), policy).unwrap();
    let mut depth = 0.0;
    let mut trace = Vec::new();
    for _ in 0..ticks {
        let in_force = planner.poll();
        let mut row = in_force.plan.bits();
        row.extend([
            in_force.age,
            in_force.request_tick.unwrap_or(u64::MAX),
            u64::from(in_force.fresh),
        ]);
        let (xi, tau) = (in_force.plan.xi[0], in_force.plan.tau[0]);
        depth += 1e-3 / tau * (1.0 + 0.1 * xi);
        let request = CutRequest {
            depth,
            speed: 0.02 + 0.01 * (xi * 3.0).sin(),
        };
        row.push(submit_code(planner.submit(&request)));
        trace.push(row);
    }
    trace
}

#[test]
fn lockstep_is_bit_identical_across_runs_with_random_planner_delays() {
    within_watchdog(|| {
        for ticks in [1, 2, 5] {
            let policy = LatencyPolicy::Lockstep { ticks };
            let reference = closed_loop(StageJob::default(), policy, 300);
            // The loop must actually replan: one plan per `ticks` ticks.
            let fresh = reference.iter().filter(|r| r[r.len() - 2] == 1).count();
            assert_eq!(fresh, (300 - 1) / ticks as usize, "k = {ticks}");
            for run in 0..12 {
                // Sleeps of 0–300 µs before each plan: longer than a tick
                // of the loop, so the tick side waits at some due ticks
                // and finds plans ready early at others.
                let job = StageJob::with_sleeps(run, 300);
                let trace = closed_loop(job, policy, 300);
                assert!(trace == reference, "k = {ticks}, run {run} differs");
            }
        }
    });
}

#[test]
fn lockstep_equals_inline_delayed_by_its_latency() {
    within_watchdog(|| {
        for ticks in [1u32, 2, 5] {
            let k = u64::from(ticks);
            // Requests at random gaps of k..=3k ticks (never refused), with
            // contents that do not depend on the plans.
            let mut rng = ChaCha8Rng::seed_from_u64(22);
            let mut schedule = Vec::new();
            let mut t = 0;
            while t < 400 {
                schedule.push(t);
                t += rng.random_range(k..=3 * k);
            }
            let run = |policy: LatencyPolicy, job: StageJob| {
                let mut planner = Planner::new(job, StagePlan::default(), policy).unwrap();
                let mut trace = Vec::new();
                for tick in 0..420u64 {
                    planner.poll();
                    if schedule.contains(&tick) {
                        let request = CutRequest {
                            depth: tick as f64 * 1e-4,
                            speed: 0.02 + 1e-3 * (tick % 5) as f64,
                        };
                        assert_eq!(planner.submit(&request), SubmitStatus::Accepted);
                    }
                    let p = planner.plan();
                    trace.push((p.plan.bits(), p.request_tick, p.age, p.fresh));
                }
                trace
            };
            let inline = run(LatencyPolicy::Inline, StageJob::default());
            let lockstep = run(
                LatencyPolicy::Lockstep { ticks },
                StageJob::with_sleeps(u64::from(ticks), 200),
            );
            for t in 0..inline.len() - k as usize {
                let (bits, request_tick, age, fresh) = &inline[t];
                let later = &lockstep[t + k as usize];
                assert!(
                    later.0 == *bits,
                    "k = {k}: plan at tick {} differs",
                    t + k as usize
                );
                assert_eq!(later.1, *request_tick);
                assert_eq!(later.2, age + k);
                assert_eq!(later.3, *fresh);
            }
            // Before the first plan is due, the initial plan is in force.
            for row in &lockstep[..k as usize] {
                assert!(row.0 == StagePlan::default().bits() && row.1.is_none());
            }
        }
    });
}

#[test]
fn lockstep_holds_one_request_in_flight_and_delivers_it_on_time() {
    within_watchdog(|| {
        let mut planner = Planner::new(
            StageJob::default(),
            StagePlan::default(),
            LatencyPolicy::Lockstep { ticks: 4 },
        )
        .unwrap();
        let request = CutRequest {
            depth: 1e-3,
            speed: 0.02,
        };
        planner.poll();
        assert_eq!(planner.submit(&request), SubmitStatus::Accepted);
        for tick in 1..4 {
            let p = planner.poll();
            assert!(!p.fresh && p.request_tick.is_none(), "tick {tick}");
            assert_eq!(p.age, tick);
            assert_eq!(planner.submit(&request), SubmitStatus::InFlight);
        }
        let p = planner.poll();
        assert!(p.fresh);
        assert_eq!((p.request_tick, p.age, p.plan.count), (Some(0), 4, 1));
        assert_eq!(p.plan.origin, 1e-3);
        assert_eq!(planner.submit(&request), SubmitStatus::Accepted);
        let p = planner.poll();
        assert!(!p.fresh);
        assert_eq!((p.request_tick, p.age), (Some(0), 5));
        let stats = planner.stats();
        assert_eq!((stats.submitted, stats.refused, stats.delivered), (2, 3, 1));
    });
}

#[test]
fn each_plan_s_time_on_the_planner_thread_is_recorded_in_order() {
    // The job sleeps a seeded 0..=2000 µs before each plan: each recorded
    // time is at least that plan's sleep (a sleep never returns early),
    // one per plan delivered, in the order made. Inline plans on the tick
    // and records none.
    within_watchdog(|| {
        let (seed, max_us) = (11, 2000);
        let mut planner = Planner::new(
            StageJob::with_sleeps(seed, max_us),
            StagePlan::default(),
            LatencyPolicy::Lockstep { ticks: 1 },
        )
        .unwrap();
        let request = CutRequest {
            depth: 1e-3,
            speed: 0.02,
        };
        for _ in 0..20 {
            planner.poll();
            assert_eq!(planner.submit(&request), SubmitStatus::Accepted);
        }
        planner.poll();
        let times = planner.solve_times_us();
        assert_eq!(times.len() as u64, planner.stats().delivered);
        assert_eq!(times.len(), 20);
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        for (k, t) in times.iter().enumerate() {
            let slept = rng.random_range(0..=max_us) as f64;
            assert!(*t >= slept, "plan {k}: {t} us recorded, {slept} us slept");
        }
        let mut inline = Planner::new(
            StageJob::default(),
            StagePlan::default(),
            LatencyPolicy::Inline,
        )
        .unwrap();
        inline.poll();
        assert_eq!(inline.submit(&request), SubmitStatus::Accepted);
        assert!(inline.solve_times_us().is_empty());
    });
}
