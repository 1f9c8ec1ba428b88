//! Proves that the tick side of a planner — `poll` and `submit`, the
//! lockstep wait included — allocates nothing after construction, with a
//! counting global allocator (its own test binary). Only the tick thread
//! counts: the planner thread's job may allocate (this one does not).

#[path = "support/counting_allocator.rs"]
mod counting_allocator;
#[path = "support/stage_plan_job.rs"]
mod stage_plan_job;

use std::sync::atomic::Ordering;

use counting_allocator::{ALLOCATIONS, Counting, TRACK};
use shearcut_controllers::planner::{LatencyPolicy, Planner, SubmitStatus};
use stage_plan_job::{CutRequest, StageJob, StagePlan};

#[global_allocator]
static GLOBAL: Counting = Counting;

#[test]
fn planner_tick_side_allocates_nothing() {
    // Sanity: the counter works on this thread.
    TRACK.with(|t| t.set(true));
    let probe = ALLOCATIONS.load(Ordering::SeqCst);
    drop(std::hint::black_box(vec![1u8; 16]));
    TRACK.with(|t| t.set(false));
    assert!(ALLOCATIONS.load(Ordering::SeqCst) > probe);

    for policy in [
        LatencyPolicy::Lockstep { ticks: 1 },
        LatencyPolicy::Lockstep { ticks: 3 },
        LatencyPolicy::Realtime,
        LatencyPolicy::Inline,
    ] {
        let mut planner = Planner::new(StageJob::default(), StagePlan::default(), policy).unwrap();
        let (mut accepted, mut fresh) = (0, 0);
        ALLOCATIONS.store(0, Ordering::SeqCst);
        TRACK.with(|t| t.set(true));
        // Realtime: as many ticks as it takes for 1 000 plans to arrive
        // (yielding so that the planner thread runs on a busy machine).
        let realtime = policy == LatencyPolicy::Realtime;
        let mut tick = 0u64;
        while tick < 5_000 || (realtime && fresh < 1_000) {
            tick += 1;
            if realtime {
                std::thread::yield_now();
            }
            let p = planner.poll();
            let request = CutRequest {
                depth: tick as f64 * 1e-5,
                speed: 0.02 + 1e-3 * p.plan.xi[0],
            };
            if planner.submit(&request) == SubmitStatus::Accepted {
                accepted += 1;
            }
            // Fresh after the submit: inline plans arrive in it.
            fresh += u64::from(planner.plan().fresh);
        }
        TRACK.with(|t| t.set(false));
        assert_eq!(ALLOCATIONS.load(Ordering::SeqCst), 0, "{policy:?}");
        // The loop did exchange plans (so the count covers real handovers).
        assert!(
            accepted >= 1_000 && fresh >= 1_000,
            "{policy:?}: {accepted}, {fresh}"
        );
    }
}
