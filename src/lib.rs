//! shearcut application.

pub mod trajectory_cases;
