//! One module per `shearcut` subcommand.

pub mod check;
pub mod compare;
pub mod controller;
pub mod default_job;
pub mod fit;
pub mod plant;
pub mod run;
pub mod scenarios;
pub mod simulate;
pub mod toughness;
pub mod trajectory;
pub mod tune;
