//! Planning off the servo tick (DESIGN §4): a planner thread runs the
//! expensive half of a controller (the MPC's solve) and hands plans to the
//! servo tick through a single-slot, allocation-free exchange.
//!
//! - [`PlanJob`]: the planning work, request → fixed-size plan;
//! - [`Planner`]: owns the thread, the exchange and the plan in force;
//! - [`LatencyPolicy`]: `Lockstep { ticks }` (deterministic latency),
//!   `Realtime` (newest plan, never wait), `Inline` (plan on the tick);
//! - [`PlannerSettings`]: the policy as config;
//! - [`PlanInForce`], [`PlannerStatus`], [`SubmitStatus`],
//!   [`PlannerStats`]: what the tick side learns.
//!
//! docs/planner.md gives the timing measured by `benches/planner.rs`.

mod exchange;
mod latency_policy;
mod plan_job;
mod planner_error;
mod planner_settings;
mod planner_status;
mod planner_thread;
mod tick_side;

pub use latency_policy::{LatencyPolicy, MAX_LOCKSTEP_TICKS};
pub use plan_job::PlanJob;
pub use planner_error::PlannerError;
pub use planner_settings::{LatencyMode, PlannerSettings};
pub use planner_status::{PlanInForce, PlannerStats, PlannerStatus, SubmitStatus};
pub use tick_side::Planner;
