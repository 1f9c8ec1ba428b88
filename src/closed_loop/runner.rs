//! The lockstep loop: measurement → controller tick → command → plant.

use nalgebra::Vector3;
use serde::Serialize;
use shearcut_controllers::controller::Controller;
use shearcut_controllers::controller::CutPhase;
use shearcut_sim::arm::{ArmStatus, KnifeCommand};

use super::control_record::{ControlSample, TickTimes};
use super::cut_story::CutStory;
use super::plant_link::{LinkError, PlantLink};
use super::series_stream::{LoopRecorder, NoRecorder};
use crate::cut_record::CutSample;
use crate::error::RunError;
use crate::transport::StopSignal;
use shearcut_sim::resource_budget::SERIES_ROWS_BUDGET;

/// Speed below which the knife is at rest, m/s: a nanometre per second, far
/// below any arm's resolution, far above the residue a jerk-limited stop
/// leaves in floating point (1e-20 m/s seen).
const AT_REST: f64 = 1e-9;

/// Why a loop stopped.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum LoopEnd {
    /// The crack reached the target depth (the simulated plant's truth).
    Completed,
    /// The controller declared the cut done and brought the knife to rest
    /// before the plant's crack reached the target depth (or, facing a real
    /// arm, with no truth to compare).
    ControllerDone,
    /// The simulated time ran out first.
    TimedOut,
    /// The plant link failed (the message says why).
    Failed(String),
    /// A signal asked the run to stop (SIGINT or SIGTERM).
    Stopped(StopSignal),
}

impl LoopEnd {
    /// The end of a loop whose link failed with `e`: stopped by the signal
    /// it reports, or failed.
    fn after(e: LinkError) -> Self {
        match e {
            LinkError::Stopped(signal) => LoopEnd::Stopped(signal),
            e => LoopEnd::Failed(e.to_string()),
        }
    }

    /// The end as one word, or a word and the reason: `completed`,
    /// `controller_done`, `timed_out`, `failed: <why>`, `stopped: sigint`
    /// (what `tune`'s tables and the Python summary carry).
    pub fn label(&self) -> String {
        match self {
            LoopEnd::Completed => "completed".to_string(),
            LoopEnd::ControllerDone => "controller_done".to_string(),
            LoopEnd::TimedOut => "timed_out".to_string(),
            LoopEnd::Failed(why) => format!("failed: {why}"),
            LoopEnd::Stopped(StopSignal::Sigint) => "stopped: sigint".to_string(),
            LoopEnd::Stopped(StopSignal::Sigterm) => "stopped: sigterm".to_string(),
        }
    }

    /// What a command that wrote the loop's results into `dir` exits with:
    /// the signal's stop ([`RunError::Stopped`], exit 128 + the signal's
    /// number) for a stopped loop, a failure naming the partial results for
    /// a failed one (exit 1), success for any other end (an algorithmic
    /// outcome, written in the results).
    pub fn exit(&self, dir: &std::path::Path) -> Result<(), RunError> {
        match self {
            LoopEnd::Stopped(signal) => Err(RunError::Stopped {
                signal: *signal,
                dir: dir.display().to_string(),
            }),
            LoopEnd::Failed(why) => Err(RunError::Loop(format!(
                "the loop failed: {why} (partial results in {}/)",
                dir.display()
            ))),
            LoopEnd::Completed | LoopEnd::ControllerDone | LoopEnd::TimedOut => Ok(()),
        }
    }
}

/// What a loop produced.
#[derive(Debug, Clone)]
pub struct LoopOutput {
    /// One sample per tick from the edge's first contact on.
    pub samples: Vec<CutSample>,
    /// One record per controller tick.
    pub control: Vec<ControlSample>,
    /// Why it stopped.
    pub end: LoopEnd,
    /// Commands the arm refused for breaking a limit.
    pub limit_faults: usize,
    /// Controller ticks run.
    pub ticks: usize,
    /// Wall-clock duration of the controller's ticks.
    pub tick_times: TickTimes,
    /// Wall-clock duration of the ticks that planned (MPC solves).
    pub plan_times: TickTimes,
    /// Wall-clock duration of the plans themselves, on the planner thread
    /// ([`Controller::solve_times_us`]; zeros without a planner thread).
    pub solve_times: TickTimes,
    /// Plans that fell back to the previous plan.
    pub fallbacks: u64,
    /// Wall-clock time of the loop, s: from the first command to the last
    /// answer (the plant's and controller's construction before it not
    /// included).
    pub wall_s: f64,
    /// The plant's time at the last answer, s (in lockstep one period per
    /// command; a realtime plant also steps through missed commands).
    pub simulated_s: f64,
}

impl LoopOutput {
    /// Simulated over wall-clock time ([`simulated_s`](Self::simulated_s)
    /// over [`wall_s`](Self::wall_s)): at least 1 when the loop keeps up
    /// with real time.
    pub fn real_time_factor(&self) -> f64 {
        self.simulated_s / self.wall_s
    }
}

/// The cut a loop makes and how its samples are labelled.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LoopCut {
    /// Slice-push ratio written in the samples' `xi` column (the
    /// controller's nominal one).
    pub xi_label: f64,
    /// Heel-to-object distance along the edge, m.
    pub z0: f64,
    /// Knife position before the cut, m.
    pub start: Vector3<f64>,
    /// Normal distance from the edge to the object's top at the start, m.
    pub gap: f64,
    /// Crack depth that completes the cut, m.
    pub target_depth: f64,
    /// Longest simulated time, s.
    pub max_duration: f64,
}

/// Runs `controller` against `link` in lockstep until the cut completes,
/// the time runs out or the link fails. The first command is the arm at
/// rest (its state before the controller has seen a measurement).
pub fn run_loop(
    link: &mut dyn PlantLink,
    controller: &mut dyn Controller,
    cut: &LoopCut,
) -> LoopOutput {
    run_loop_recorded(link, controller, cut, &mut NoRecorder)
}

/// [`run_loop`], handing each sample and control record to `recorder` as
/// the loop goes (between the controller's tick and the next exchange,
/// outside the tick's timing): a [`SeriesStream`](super::SeriesStream)
/// streams them to disk.
#[allow(clippy::disallowed_methods)] // Tick durations are statistics, not model inputs.
pub fn run_loop_recorded(
    link: &mut dyn PlantLink,
    controller: &mut dyn Controller,
    cut: &LoopCut,
    recorder: &mut dyn LoopRecorder,
) -> LoopOutput {
    let max_ticks = (cut.max_duration / link.period()).ceil() as usize;
    // Every per-tick record is preallocated: the loop thread never
    // allocates while it runs (within the series budget).
    let capacity = record_capacity(max_ticks);
    let mut samples = Vec::with_capacity(capacity);
    let mut control = Vec::with_capacity(capacity);
    let mut durations = Vec::with_capacity(capacity);
    let mut plan_durations = Vec::with_capacity(capacity);
    let mut limit_faults = 0;
    let mut end = LoopEnd::TimedOut;
    let loop_started = std::time::Instant::now();
    let mut answer = match link.exchange(&KnifeCommand::default()) {
        Ok(m) => m,
        Err(e) => return failed(e, loop_started.elapsed().as_secs_f64()),
    };
    let mut story = CutStory::new();
    story.observe(&answer);
    let mut ticks = 0;
    while ticks < max_ticks {
        let started = std::time::Instant::now();
        let command = controller.tick(&answer.reading);
        let us = started.elapsed().as_secs_f64() * 1e6;
        durations.push(us);
        ticks += 1;
        let telemetry = controller.telemetry();
        if telemetry.planned {
            plan_durations.push(us);
        }
        let record = ControlSample::new(answer.reading.time, &telemetry, &command);
        recorder.control(&record);
        control.push(record);
        answer = match link.exchange(&command) {
            Ok(m) => m,
            Err(e) => {
                end = LoopEnd::after(e);
                break;
            }
        };
        story.observe(&answer);
        let reading = &answer.reading;
        recorder.tick_done(reading.time);
        if let Some(signal) = recorder.stop_requested() {
            end = LoopEnd::Stopped(signal);
            break;
        }
        if matches!(reading.status, ArmStatus::LimitViolation(_)) {
            limit_faults += 1;
        }
        if let Some(truth) = &answer.truth {
            if let Some(s) =
                CutSample::from_plant(reading, truth, cut.xi_label, cut.z0, &cut.start, cut.gap)
            {
                recorder.sample(&s);
                samples.push(s);
            }
            if truth.crack_depth >= cut.target_depth {
                end = LoopEnd::Completed;
                break;
            }
        }
        if telemetry.phase == CutPhase::Done && reading.velocity.norm() < AT_REST {
            end = LoopEnd::ControllerDone;
            break;
        }
    }
    story.end(&end, ticks, answer.reading.time, &answer, link.rechoices());
    LoopOutput {
        samples,
        control,
        end,
        limit_faults,
        ticks,
        tick_times: TickTimes::from_durations(&mut durations),
        plan_times: TickTimes::from_durations(&mut plan_durations),
        solve_times: TickTimes::from_durations(&mut controller.solve_times_us()),
        fallbacks: controller.telemetry().fallbacks,
        wall_s: loop_started.elapsed().as_secs_f64(),
        simulated_s: answer.reading.time,
    }
}

/// Ticks of records [`run_loop_recorded`] preallocates for a loop of at
/// most `max_ticks` ticks: at most [`SERIES_ROWS_BUDGET`], the rows a
/// scenario's `controller.max_duration × loop.rate_hz` may ask for
/// (`sim/src/resource_budget.rs`; a scenario above it is refused on load).
/// A tick holds [`LOOP_RECORD_BYTES`], so the preallocation is at most
/// [`SERIES_ROWS_BUDGET`] × [`LOOP_RECORD_BYTES`] (address space; pages
/// become resident as the ticks fill them). A loop built outside a scenario
/// that runs longer grows its records past the capacity.
pub fn record_capacity(max_ticks: usize) -> usize {
    max_ticks.min(SERIES_ROWS_BUDGET as usize)
}

/// Bytes [`run_loop_recorded`] holds per tick: a cut sample, a control
/// record and two tick durations.
pub const LOOP_RECORD_BYTES: usize = std::mem::size_of::<CutSample>()
    + std::mem::size_of::<ControlSample>()
    + 2 * std::mem::size_of::<f64>();

fn failed(e: LinkError, wall_s: f64) -> LoopOutput {
    LoopOutput {
        samples: Vec::new(),
        control: Vec::new(),
        end: LoopEnd::after(e),
        limit_faults: 0,
        ticks: 0,
        tick_times: TickTimes::from_durations(&mut []),
        plan_times: TickTimes::from_durations(&mut []),
        solve_times: TickTimes::from_durations(&mut []),
        fallbacks: 0,
        wall_s,
        simulated_s: 0.0,
    }
}

#[cfg(test)]
mod tests {
    use shearcut_controllers::controller::ControllerTelemetry;
    use shearcut_sim::arm::ArmReading;

    use super::*;
    use crate::closed_loop::LinkAnswer;

    /// An arm with no simulated truth (as a real arm's bridge): it executes
    /// each command exactly.
    struct EchoArm {
        reading: ArmReading,
    }

    impl PlantLink for EchoArm {
        fn period(&self) -> f64 {
            1e-3
        }

        fn exchange(&mut self, command: &KnifeCommand) -> Result<LinkAnswer, LinkError> {
            self.reading.time += 1e-3;
            self.reading.velocity = command.velocity;
            self.reading.position += command.velocity * 1e-3;
            Ok(LinkAnswer {
                reading: self.reading,
                truth: None,
            })
        }
    }

    /// A controller that has ended its cut and whose stop left the
    /// floating-point residue of a jerk-limited trajectory.
    struct StoppedWithResidue;

    impl Controller for StoppedWithResidue {
        fn name(&self) -> &str {
            "stopped"
        }

        fn tick(&mut self, _: &ArmReading) -> KnifeCommand {
            KnifeCommand {
                velocity: Vector3::new(0.0, 0.0, -1.567e-20),
            }
        }

        fn telemetry(&self) -> ControllerTelemetry {
            ControllerTelemetry::moving(0.0, 0.0, 0.0, true)
        }
    }

    /// A controller done with the knife at rest (to within floating-point
    /// residue) ends the loop at once rather than idling until the time runs
    /// out.
    #[test]
    fn the_preallocation_is_bounded_by_the_series_budget() {
        // An hour at 20 kHz would be 72 million ticks: the budget caps it.
        assert_eq!(record_capacity(72_000_000), SERIES_ROWS_BUDGET as usize);
        assert_eq!(record_capacity(548), 548);
    }

    #[test]
    fn a_done_controller_at_rest_ends_the_loop() {
        let mut arm = EchoArm {
            reading: ArmReading::at_rest(0.0, Vector3::new(0.0, 0.05, 0.0)),
        };
        let cut = LoopCut {
            xi_label: 0.0,
            z0: 0.02,
            start: Vector3::new(0.0, 0.05, 0.0),
            gap: 1e-3,
            target_depth: 0.01,
            max_duration: 1.0,
        };
        let out = run_loop(&mut arm, &mut StoppedWithResidue, &cut);
        assert_eq!(out.end, LoopEnd::ControllerDone);
        assert_eq!(out.control.len(), 1);
    }
}
