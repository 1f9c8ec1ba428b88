//! One closed-loop run of a scenario in this process, its records in
//! memory (no files written): what `shearcut run`, `compare`, `tune`, the
//! C ABI and the Python package run.

use super::{InProcessPlant, LoopOutput, LoopRecorder, LoopSetup, NoRecorder, run_loop_recorded};
use crate::controller_choice::ControllerChoice;
use crate::cut_record::CutSummary;
use crate::error::RunError;
use crate::run_replica::RunReplica;
use crate::scenario::Scenario;

/// Everything a closed-loop run produced.
#[derive(Debug, Clone)]
pub struct RunOutput {
    /// The controller's name.
    pub controller: String,
    /// The loop's records.
    pub output: LoopOutput,
    /// Summary of the cut.
    pub summary: CutSummary,
    /// Target crack depth, m.
    pub target_depth_m: f64,
    /// The replica of the run (nominal unless `--replica`).
    pub replica: RunReplica,
}

/// Runs the closed loop for a loaded scenario (no files written).
pub fn run_closed_loop(s: &Scenario, choice: ControllerChoice) -> Result<RunOutput, RunError> {
    run_closed_loop_on(s, choice, RunReplica::NOMINAL)
}

/// Runs the closed loop for a loaded scenario as one of its replicas (the
/// knife starting a few µm higher, [`RunReplica`]; no files written).
pub fn run_closed_loop_on(
    s: &Scenario,
    choice: ControllerChoice,
    replica: RunReplica,
) -> Result<RunOutput, RunError> {
    run_closed_loop_recorded(s, choice, replica, &mut NoRecorder)
}

/// [`run_closed_loop_on`], handing the loop's records to `recorder` as it
/// runs ([`SeriesStream`] streams them to a run directory).
pub fn run_closed_loop_recorded(
    s: &Scenario,
    choice: ControllerChoice,
    replica: RunReplica,
    recorder: &mut dyn LoopRecorder,
) -> Result<RunOutput, RunError> {
    let setup = LoopSetup::on_replica(s, choice, replica)?;
    let mut controller = setup.controller(s, choice)?;
    let plant = setup.plant(s)?;
    let cut = setup.cut(s);
    let mut link = InProcessPlant::new(plant, setup.task.period);
    let output = run_loop_recorded(&mut link, controller.as_mut(), &cut, recorder);
    let summary = CutSummary::from_samples(&output.samples, setup.task.target_depth);
    Ok(RunOutput {
        controller: controller.name().to_string(),
        output,
        summary,
        target_depth_m: setup.task.target_depth,
        replica,
    })
}
