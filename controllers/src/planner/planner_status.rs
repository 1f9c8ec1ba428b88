//! What the tick side learns of the planner each tick.

/// The planner's health.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PlannerStatus {
    /// The job plans every request handed to it.
    Running,
    /// The job panicked planning the request submitted at `request_tick`;
    /// the planner takes no more requests and the last plan stays in force.
    JobPanicked {
        /// Tick of the request whose plan panicked.
        request_tick: u64,
    },
}

/// Outcome of [`super::Planner::submit`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[must_use]
pub enum SubmitStatus {
    /// Handed to the planner (or planned, under `Inline`).
    Accepted,
    /// Refused under `Lockstep`: the previous request's plan is not due
    /// yet. Nothing was sent.
    InFlight,
    /// Refused: the job has panicked; nothing will be planned.
    JobPanicked,
}

/// The plan in force at the current tick and how old it is.
#[derive(Debug, Clone, Copy)]
pub struct PlanInForce<'a, P> {
    /// The newest plan visible to the tick side (the initial plan until
    /// the first one arrives).
    pub plan: &'a P,
    /// Tick of the request it answers; `None` for the initial plan.
    pub request_tick: Option<u64>,
    /// Ticks since that request was submitted (since tick 0 for the
    /// initial plan): `ticks` on arrival under `Lockstep`, growing by one
    /// per tick until the next plan.
    pub age: u64,
    /// Whether it became visible in the current tick.
    pub fresh: bool,
    /// The planner's health.
    pub status: PlannerStatus,
}

/// Counters of a [`super::Planner`], tick side.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct PlannerStats {
    /// Requests accepted.
    pub submitted: u64,
    /// Requests refused (in flight under `Lockstep`, or after a panic).
    pub refused: u64,
    /// Plans that became visible.
    pub delivered: u64,
    /// Accepted requests whose plan never became visible (`Realtime`
    /// only): replaced by a newer request before the planner took them up,
    /// or their plan replaced by a newer plan before a poll took it.
    /// Counted when a later plan arrives.
    pub superseded: u64,
}
