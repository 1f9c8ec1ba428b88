//! How the successor workers' threads are scheduled by the operating system.
//!
//! A plant whose tick never waits for a build
//! ([`SuccessorPolicy::KeepCurrent`](crate::SuccessorPolicy::KeepCurrent))
//! needs its builds to yield to every thread that must keep the servo
//! period: its own tick and the controller's. In the background a worker
//! runs under Linux's `SCHED_IDLE`, which the kernel schedules only on a CPU
//! that has no other runnable thread; a build that does not get one is
//! deferred, never the tick. A process may always lower its own threads, so
//! this needs no privilege.

use thread_priority::{
    NormalThreadSchedulePolicy, ThreadPriority, ThreadSchedulePolicy,
    set_thread_priority_and_policy, thread_native_id,
};

/// Runs the calling thread in the background (`SCHED_IDLE`). A refusal by
/// the operating system (one without `SCHED_IDLE`) leaves the thread as it
/// was: the scheduling changes how soon a successor is built, never what is
/// built.
pub(crate) fn run_this_thread_in_background() {
    let outcome = set_thread_priority_and_policy(
        thread_native_id(),
        ThreadPriority::Min,
        ThreadSchedulePolicy::Normal(NormalThreadSchedulePolicy::Idle),
    );
    if let Err(e) = outcome {
        tracing::debug!("successor worker: SCHED_IDLE refused: {e:?}");
    }
}
