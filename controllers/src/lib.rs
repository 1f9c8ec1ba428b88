//! shearcut-controllers: the [`controller::Controller`] trait and its
//! controllers (baselines, MPC), the observers of what an arm does not
//! measure, planning off the servo tick, and our jerk-limited trajectory
//! generator.
//!
//! A controller sees only what an arm reports (`shearcut_sim::arm`): this
//! crate does not depend on `shearcut-plant`, where the simulated plant's
//! ground truth lives.

pub mod controller;
pub mod mpc;
pub mod observer;
pub mod planner;
pub mod trajectory;
