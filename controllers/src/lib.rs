//! shearcut-controllers: the [`controller::Controller`] trait and its
//! controllers (baselines, MPC), and our jerk-limited trajectory generator.

pub mod controller;
pub mod mpc;
pub mod observer;
pub mod trajectory;
