//! Tick-side cost of planning off the tick, and request → plan round trips,
//! with a job shaped like the MPC's (64 stages of (ξ, τ)) that costs about
//! a microsecond, so the figures are the exchange's, not the job's.
//!
//! `cargo bench -p shearcut-controllers --bench planner` prints median, p99
//! and max of: a `Realtime` tick (poll + submit, a request every tick, the
//! planner always busy); `Lockstep` ticks with no plan due and the polls at
//! which one is due (these wait if it is not ready); and round trips from
//! submit to the plan visible, `Realtime` (the tick side spinning on poll)
//! and `Lockstep { ticks: 1 }` (the tick side blocked in the due poll).
//! docs/planner.md gives figures and how the cores were loaded.
#![allow(clippy::disallowed_methods)] // A benchmark reads the wall clock.

#[path = "../tests/support/stage_plan_job.rs"]
mod stage_plan_job;

use std::time::Instant;

use shearcut_controllers::planner::{LatencyPolicy, Planner, SubmitStatus};
use stage_plan_job::{CutRequest, StageJob, StagePlan};

fn stats(mut v: Vec<f64>) -> (f64, f64, f64) {
    v.sort_by(f64::total_cmp);
    let at = |q: f64| v[((v.len() - 1) as f64 * q).round() as usize];
    (at(0.5), at(0.99), v[v.len() - 1])
}

fn report(what: &str, samples: Vec<f64>) {
    let n = samples.len();
    let (med, p99, max) = stats(samples);
    println!("{what} ({n} samples): median {med:.2} us, p99 {p99:.2} us, max {max:.1} us");
}

fn request(tick: u64) -> CutRequest {
    CutRequest {
        depth: (tick % 10_000) as f64 * 1e-6,
        speed: 0.02,
    }
}

fn planner(policy: LatencyPolicy) -> Planner<StageJob> {
    Planner::new(StageJob::default(), StagePlan::default(), policy).unwrap()
}

fn realtime_ticks(ticks: u64) {
    let mut p = planner(LatencyPolicy::Realtime);
    let mut times = Vec::with_capacity(ticks as usize);
    for tick in 0..ticks {
        let start = Instant::now();
        let fresh = p.poll().fresh;
        let status = p.submit(&request(tick));
        times.push(start.elapsed().as_secs_f64() * 1e6);
        std::hint::black_box(fresh);
        assert_eq!(status, SubmitStatus::Accepted);
    }
    let s = p.stats();
    report(
        &format!(
            "Realtime tick, poll + submit every tick ({} plans arrived)",
            s.delivered
        ),
        times,
    );
}

fn lockstep_ticks(ticks: u64, k: u32) {
    let mut p = planner(LatencyPolicy::Lockstep { ticks: k });
    let (mut other, mut due) = (Vec::new(), Vec::new());
    for tick in 0..ticks {
        let start = Instant::now();
        let fresh = p.poll().fresh;
        let status = p.submit(&request(tick));
        let us = start.elapsed().as_secs_f64() * 1e6;
        assert_eq!(fresh, tick >= u64::from(k) && tick % u64::from(k) == 0);
        assert_eq!(status == SubmitStatus::Accepted, tick % u64::from(k) == 0);
        if fresh { &mut due } else { &mut other }.push(us);
    }
    report(
        &format!("Lockstep {{ ticks: {k} }} tick, no plan due, poll (+ refused submit)"),
        other,
    );
    report(
        &format!("Lockstep {{ ticks: {k} }} tick, plan due: poll (waits if not ready) + submit"),
        due,
    );
}

fn realtime_round_trips(n: u64) {
    let mut p = planner(LatencyPolicy::Realtime);
    let mut times = Vec::with_capacity(n as usize);
    for _ in 0..n {
        p.poll();
        let tick = p.tick();
        let start = Instant::now();
        assert_eq!(p.submit(&request(tick)), SubmitStatus::Accepted);
        while p.poll().request_tick != Some(tick) {
            std::hint::spin_loop();
        }
        times.push(start.elapsed().as_secs_f64() * 1e6);
    }
    report(
        "Realtime round trip, submit -> plan visible (tick side spinning on poll)",
        times,
    );
}

fn lockstep_round_trips(n: u64) {
    let mut p = planner(LatencyPolicy::Lockstep { ticks: 1 });
    let mut times = Vec::with_capacity(n as usize);
    for _ in 0..n {
        p.poll();
        let start = Instant::now();
        assert_eq!(p.submit(&request(p.tick())), SubmitStatus::Accepted);
        assert!(p.poll().fresh);
        times.push(start.elapsed().as_secs_f64() * 1e6);
    }
    report(
        "Lockstep { ticks: 1 } round trip, submit -> due poll returns (blocked in the poll)",
        times,
    );
}

fn main() {
    // Counts sized for a loaded 2-core machine, where each wake-up of the
    // planner thread can take milliseconds.
    realtime_ticks(200_000);
    lockstep_ticks(20_000, 4);
    realtime_round_trips(5_000);
    lockstep_round_trips(5_000);
}
