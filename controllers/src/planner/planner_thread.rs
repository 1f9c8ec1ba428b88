//! The planner thread's loop.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::Arc;
use std::sync::atomic::Ordering;

use triple_buffer::{Input, Output};

use super::PlanJob;
use super::exchange::{Signals, Stamped};

/// Runs `job` on every new request until told to stop or the job panics;
/// parks while there is nothing to do (the tick side unparks it on each
/// submit and on shutdown). `ring`: wake a waiting lockstep tick side after
/// each plan. Returns (dropping the job) on stop or after a panic.
pub(super) fn run<J: PlanJob>(
    mut job: J,
    mut requests: Output<Stamped<Option<J::Request>>>,
    mut plans: Input<Stamped<J::Plan>>,
    signals: Arc<Signals>,
    ring: bool,
) {
    loop {
        if signals.stop.load(Ordering::Acquire) {
            return;
        }
        if !requests.update() {
            std::thread::park();
            continue;
        }
        let Stamped {
            seq,
            tick,
            value: Some(request),
        } = *requests.output_buffer()
        else {
            continue;
        };
        let slot = plans.input_buffer_mut();
        #[allow(clippy::disallowed_methods)] // Planning latency statistics, not model time.
        let started = std::time::Instant::now();
        let planned = catch_unwind(AssertUnwindSafe(|| job.plan(&request, &mut slot.value)));
        let took_us = started.elapsed().as_secs_f64() * 1e6;
        if planned.is_ok() {
            signals
                .solve_times_us
                .lock()
                .unwrap_or_else(std::sync::PoisonError::into_inner)
                .push(took_us);
            slot.seq = seq;
            slot.tick = tick;
            plans.publish();
            signals.published.store(seq, Ordering::Release);
        } else {
            signals.panicked_tick.store(tick, Ordering::Relaxed);
            signals.panicked.store(true, Ordering::Release);
        }
        if ring {
            signals.ring();
        }
        if planned.is_err() {
            return;
        }
    }
}
