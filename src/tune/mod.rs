//! Controller tuning at scale (`shearcut tune`): sweeps of controller
//! settings over scenarios and perturbed variants of them, run locally in
//! parallel and resumably, or sharded over a scheduler's job array and
//! merged; one row per run, Pareto fronts, robust statistics, plots and a
//! recommended settings block. See docs/tuning.md.

pub mod analysis;
pub mod best_constant_pairing;
pub mod constant_grid;
pub mod controller_setting;
pub mod dispatch_order;
pub mod effect_plot;
pub mod executor;
#[cfg(test)]
pub(crate) mod finished_sweep_fixture;
pub mod front_plot;
pub mod job_list;
pub mod job_outcome;
pub mod merge;
pub mod objective;
pub mod pareto_front;
pub mod perturbation;
pub mod recommendation;
pub mod result_dir;
pub mod result_table;
pub mod robust_stats;
pub mod run_log;
pub mod setting_effect;
pub mod shard;
pub mod specimen_spread;
pub mod staged_runs;
pub mod stop_request;
pub mod sweep_file;
pub mod uniform_constant;
pub mod weighting;
