//! When a plan becomes visible to the servo tick.

/// Largest lockstep latency, servo ticks: 10 s at 1 kHz. A plan older than
/// that describes a cut that is over.
pub const MAX_LOCKSTEP_TICKS: u32 = 10_000;

/// When the plan for a request becomes visible to the tick side.
///
/// Ticks are the [`super::Planner::poll`] calls; a request submitted at
/// tick t is stamped t.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LatencyPolicy {
    /// The plan for the request submitted at tick t becomes visible at the
    /// poll of tick t + `ticks`, never earlier or later: a plan that is
    /// ready early is held back, and a plan not ready at t + `ticks` is
    /// waited for there. That wait is the tick side's only wait: in
    /// lockstep simulated time does not run on its own, so waiting for the
    /// planner stands for the planner having finished within `ticks`
    /// servo periods. One request is in flight at a time; a submit before
    /// its plan is due is refused ([`super::SubmitStatus::InFlight`]), so
    /// a submit every `ticks` ticks or fewer often is always accepted.
    /// Runs are bit-identical run to run and identical to `Inline`
    /// delayed by `ticks` ticks.
    Lockstep {
        /// Plan latency, servo ticks, in 1..=[`MAX_LOCKSTEP_TICKS`].
        ticks: u32,
    },
    /// The tick side takes the newest plan at each poll and never waits;
    /// a request submitted while the planner is busy replaces any request
    /// not yet taken up. For a real arm's loop: plans arrive when the
    /// planner finishes them, and their age tells how late they are.
    Realtime,
    /// The job runs inside [`super::Planner::submit`], on the tick: the
    /// plan is visible at once (latency 0). For tests and comparisons.
    Inline,
}
