//! The planning work that runs off the servo tick.

/// One step of planning: turn the latest request into a plan.
///
/// A [`super::Planner`] runs the job on its own thread (or inside the tick
/// under [`super::LatencyPolicy::Inline`]). Requests are small `Copy` values
/// the tick side builds each planning period (the state the plan starts
/// from); plans are fixed-size and preallocated (the MPC's: at most 64
/// stages of (ξ, τ) plus a status, origin, step and counters), so handing
/// them over allocates nothing.
///
/// ## Contract
/// - `plan` overwrites `out` with the whole plan: `out` holds an earlier
///   plan of this job on entry (not necessarily the last one), usable as
///   scratch but never as the previous plan. A job that warm-starts from
///   its previous plan keeps a copy of it in `self`.
/// - `plan` is deterministic in `self` and `request`: under
///   [`super::LatencyPolicy::Lockstep`] the job sees every accepted request
///   in order, so equal request sequences give bit-identical plans.
/// - `plan` returns: dropping or shutting down a [`super::Planner`] waits
///   for the plan under way. A job that cannot solve reports that in its
///   plan (a status inside the plan), it does not panic; a panic is caught
///   and stops the planner ([`super::PlannerStatus::JobPanicked`]).
/// - `plan` may allocate on the planner thread (the tick side does not
///   care); under `Inline` it runs on the tick and should not.
pub trait PlanJob {
    /// What the tick side asks for: the state a plan starts from.
    type Request: Copy + Send + 'static;
    /// A plan: fixed-size, preallocated, cloned once per buffer at start-up.
    type Plan: Clone + Send + 'static;

    /// Writes the plan for `request` into `out`.
    fn plan(&mut self, request: &Self::Request, out: &mut Self::Plan);
}
