//! The controller process's servo thread at real-time priority.
//!
//! A real arm's servo loop runs under `SCHED_FIFO` (libfranka's
//! `RealtimeConfig::kEnforce`, ros2_control's `lock_memory`/`thread_priority`),
//! so that no ordinary thread on the machine can delay a tick. The planner
//! thread must stay at normal priority: it is started before the servo thread
//! is raised, and a thread inherits its creator's policy only at creation.

use thread_priority::{
    RealtimeThreadSchedulePolicy, ThreadPriority, ThreadPriorityValue, ThreadSchedulePolicy,
    set_thread_priority_and_policy, thread_native_id,
};

/// Runs the calling thread under `SCHED_FIFO` at `priority` (1–99); 0 leaves
/// it as it is.
///
/// # Errors
/// The priority cannot be set (no `CAP_SYS_NICE`, or a kernel that refuses
/// it): the message says which and how to proceed.
pub fn raise_servo_thread(priority: u8) -> Result<(), String> {
    if priority == 0 {
        return Ok(());
    }
    let value = ThreadPriorityValue::try_from(priority)
        .map_err(|e| format!("loop.servo_priority = {priority}: {e}"))?;
    set_thread_priority_and_policy(
        thread_native_id(),
        ThreadPriority::Crossplatform(value),
        ThreadSchedulePolicy::Realtime(RealtimeThreadSchedulePolicy::Fifo),
    )
    .map_err(|e| {
        format!(
            "loop.servo_priority = {priority}: cannot run the servo thread under SCHED_FIFO ({e:?}); \
             grant CAP_SYS_NICE (or run as root), or set servo_priority = 0"
        )
    })
}
