//! A job that panics becomes a status, never a hang; dropping a planner
//! stops and joins its thread and drops the job, in every state.

#[path = "support/stage_plan_job.rs"]
mod stage_plan_job;
#[path = "support/watchdog.rs"]
mod watchdog;

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

use shearcut_controllers::planner::{
    LatencyPolicy, Planner, PlannerError, PlannerSettings, PlannerStatus, SubmitStatus,
};
use stage_plan_job::{CutRequest, DropFlag, StageJob, StagePlan};
use watchdog::within_watchdog;

fn request(tick: u64) -> CutRequest {
    CutRequest {
        depth: tick as f64 * 1e-4,
        speed: 0.02,
    }
}

fn panicking_job(at: u64, dropped: &Arc<AtomicBool>) -> StageJob {
    StageJob {
        panic_at: Some(at),
        dropped: Some(DropFlag(Arc::clone(dropped))),
        ..StageJob::default()
    }
}

/// The third plan panics: lockstep learns it at that plan's due tick, the
/// second plan stays in force and ages, submits are refused, drop returns.
#[test]
fn lockstep_job_panic_is_a_status_at_the_due_tick() {
    within_watchdog(|| {
        let dropped = Arc::new(AtomicBool::new(false));
        let mut planner = Planner::new(
            panicking_job(3, &dropped),
            StagePlan::default(),
            LatencyPolicy::Lockstep { ticks: 2 },
        )
        .unwrap();
        for tick in 0..12u64 {
            let p = planner.poll();
            match tick {
                0..6 => assert_eq!(p.status, PlannerStatus::Running, "tick {tick}"),
                _ => {
                    assert_eq!(p.status, PlannerStatus::JobPanicked { request_tick: 4 });
                    assert_eq!((p.request_tick, p.plan.count), (Some(2), 2));
                    assert_eq!(p.age, tick - 2);
                }
            }
            let expected = if tick < 6 {
                SubmitStatus::Accepted
            } else {
                SubmitStatus::JobPanicked
            };
            if tick % 2 == 0 {
                assert_eq!(planner.submit(&request(tick)), expected, "tick {tick}");
            }
        }
        assert_eq!(planner.stats().delivered, 2);
        drop(planner);
        assert!(dropped.load(Ordering::SeqCst));
    });
}

#[test]
fn realtime_job_panic_is_a_status() {
    within_watchdog(|| {
        let dropped = Arc::new(AtomicBool::new(false));
        let mut planner = Planner::new(
            panicking_job(1, &dropped),
            StagePlan::default(),
            LatencyPolicy::Realtime,
        )
        .unwrap();
        planner.poll();
        assert_eq!(planner.submit(&request(0)), SubmitStatus::Accepted);
        while planner.poll().status == PlannerStatus::Running {
            std::thread::yield_now();
        }
        let p = planner.plan();
        assert_eq!(p.status, PlannerStatus::JobPanicked { request_tick: 0 });
        assert!(p.request_tick.is_none() && *p.plan == StagePlan::default());
        assert_eq!(planner.submit(&request(1)), SubmitStatus::JobPanicked);
        drop(planner);
        assert!(dropped.load(Ordering::SeqCst));
    });
}

#[test]
fn inline_job_panic_is_a_status() {
    let dropped = Arc::new(AtomicBool::new(false));
    let mut planner = Planner::new(
        panicking_job(2, &dropped),
        StagePlan::default(),
        LatencyPolicy::Inline,
    )
    .unwrap();
    planner.poll();
    assert_eq!(planner.submit(&request(0)), SubmitStatus::Accepted);
    planner.poll();
    // The panic happens inside this submit; the plan in force is the
    // first, intact (the job wrote into scratch, not into it).
    assert_eq!(planner.submit(&request(1)), SubmitStatus::Accepted);
    let p = planner.plan();
    assert_eq!(p.status, PlannerStatus::JobPanicked { request_tick: 1 });
    assert_eq!(
        (p.request_tick, p.plan.count, p.plan.origin),
        (Some(0), 1, 0.0)
    );
    assert_eq!(planner.submit(&request(2)), SubmitStatus::JobPanicked);
    drop(planner);
    assert!(dropped.load(Ordering::SeqCst));
}

/// Drop stops and joins the thread (the job is dropped on it before
/// `drop` returns): idle, with a request in flight, with a plan ready but
/// not yet due, and for every policy.
#[test]
fn drop_joins_the_planner_thread_in_every_state() {
    within_watchdog(|| {
        let policies = [
            LatencyPolicy::Lockstep { ticks: 3 },
            LatencyPolicy::Realtime,
            LatencyPolicy::Inline,
        ];
        for policy in policies {
            for submitted in [0u64, 1, 3] {
                let dropped = Arc::new(AtomicBool::new(false));
                let job = StageJob {
                    dropped: Some(DropFlag(Arc::clone(&dropped))),
                    ..StageJob::with_sleeps(submitted, 2_000)
                };
                let mut planner = Planner::new(job, StagePlan::default(), policy).unwrap();
                for tick in 0..submitted {
                    planner.poll();
                    let _ = planner.submit(&request(tick));
                }
                assert!(!dropped.load(Ordering::SeqCst));
                drop(planner);
                assert!(dropped.load(Ordering::SeqCst), "{policy:?}, {submitted}");
            }
        }
    });
}

#[test]
fn lockstep_latency_out_of_range_is_refused_naming_the_key() {
    for ticks in [0, 10_001] {
        let Err(PlannerError::Setting(e)) = Planner::new(
            StageJob::default(),
            StagePlan::default(),
            LatencyPolicy::Lockstep { ticks },
        ) else {
            panic!("lockstep ticks = {ticks} accepted");
        };
        assert_eq!(e.key, "lockstep_ticks");
        assert_eq!(e.value, ticks.to_string());
        assert_eq!(e.allowed, "in 1..=10000");
    }
    let settings: PlannerSettings = toml::from_str("latency = \"realtime\"").unwrap();
    assert_eq!(settings.policy().unwrap(), LatencyPolicy::Realtime);
    let settings: PlannerSettings = toml::from_str("lockstep_ticks = 4").unwrap();
    assert_eq!(
        settings.policy().unwrap(),
        LatencyPolicy::Lockstep { ticks: 4 }
    );
    let e = toml::from_str::<PlannerSettings>("lockstep_tick = 4").unwrap_err();
    assert!(
        e.to_string().contains("unknown field `lockstep_tick`"),
        "{e}"
    );
    let e = toml::from_str::<PlannerSettings>("latency = \"soon\"").unwrap_err();
    assert!(e.to_string().contains("unknown variant `soon`"), "{e}");
    let bad: PlannerSettings = toml::from_str("lockstep_ticks = 0").unwrap();
    assert_eq!(
        bad.policy().unwrap_err().to_string(),
        "`lockstep_ticks` = 0: in 1..=10000"
    );
}
