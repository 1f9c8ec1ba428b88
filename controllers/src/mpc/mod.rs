//! Model-predictive control of the slice on Clarabel (DESIGN §4).
//!
//! - [`SliceModel`]: what the MPC needs of the cutting model per stage
//!   (work per unit depth with its ξ-derivatives, force, deflection);
//! - [`DepthProfile`]: edge in contact and section size along the cut;
//! - [`DepthQp`]: the convex subproblem over depth stages, persistent;
//! - [`ScaleEstimator`]: online R_c, E, μ scale factors from the forces,
//!   with [`IndentationStiffness`] for E before the first fracture;
//! - [`SurrogateModel`]: the fitted surrogate as a [`SliceModel`];
//! - [`MpcPlanJob`]: the planning half, run off the servo tick by a
//!   [`Planner`](crate::planner::Planner);
//! - [`Mpc`]: the controller.

mod controller;
mod depth_profile;
mod depth_qp;
mod indentation_stiffness;
mod plan_job;
mod scale_estimator;
mod settings;
mod slice_model;
mod surrogate_model;

pub use controller::{Mpc, MpcStats};
pub use depth_profile::DepthProfile;
pub use depth_qp::{DepthQp, EnteringEdge, QpLimits, QpStatus, StageData};
pub use indentation_stiffness::IndentationStiffness;
pub use plan_job::{MpcPlan, MpcPlanJob, PlanRequest};
pub use scale_estimator::ScaleEstimator;
pub use settings::MpcSettings;
pub use slice_model::{ForceModel, SliceModel, StageCost, StageState};
pub use surrogate_model::SurrogateModel;
