//! `shearcut run`: the closed loop — a controller driving the plant tick by
//! tick, in lockstep, through a plant link ([`crate::closed_loop`] builds
//! and runs it; this writes its results and prints its summary).

use std::path::Path;

use serde::Serialize;
use shearcut_sim::InvalidSetting;

use crate::closed_loop::{
    DroppedRows, LoopEnd, RunOutput, SeriesStream, TickTimes, run_closed_loop_recorded,
};
use crate::cut_record::{CutSample, CutSummary};
use crate::error::{ConfigError, RunError};
use crate::plot::control_trace::draw_control_trace;
use crate::plot::cut_curves::draw_cut_curves;
use crate::render_plot;
use crate::result_file::write_json;
use crate::run_dir::{self, Destination};
use crate::run_replica::RunReplica;
use crate::scenario::Scenario;
use crate::transport::TerminationWatch;

/// How controller and plant talk.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Transport {
    /// Plant and controller in one process, stepped in lockstep.
    Inproc,
    /// Plant and controller in two processes (`shearcut plant`, `shearcut
    /// controller`) over iceoryx2 shared memory.
    Iceoryx2,
}

/// The summary file's content.
#[derive(Debug, Serialize)]
struct SummaryFile<'a> {
    scenario: &'a str,
    controller: &'a str,
    transport: Transport,
    /// The run's replica: the knife started this many steps of 5 µm
    /// higher than `[plant] start_gap` (0: the scenario as given).
    replica: u32,
    /// How much higher that is, m.
    replica_start_offset_m: f64,
    end: &'a LoopEnd,
    target_depth_m: f64,
    cut: &'a CutSummary,
    ticks: usize,
    limit_faults: usize,
    controller_tick: TickTimes,
    plan_tick: TickTimes,
    /// The plans themselves on the planner thread (zeros without one).
    plan_solve: TickTimes,
    plan_fallbacks: u64,
    /// Wall-clock time of the loop (first command to last answer), s.
    wall_s: f64,
    /// The plant's time at the last answer, s.
    simulated_s: f64,
    /// Simulated over wall-clock time: at least 1 when the loop keeps up
    /// with real time.
    real_time_factor: f64,
    /// Rows missing from the streamed series because the writer fell
    /// behind (0 and 0 when the files hold every tick).
    dropped_rows: DroppedRows,
}

/// Runs the subcommand: load, run, write the results and print a summary.
pub fn run(
    scenario: &str,
    controller: Option<&str>,
    transport: Transport,
    replica: RunReplica,
    out: &Destination,
) -> Result<(), RunError> {
    if transport == Transport::Iceoryx2 {
        if replica != RunReplica::NOMINAL {
            return Err(RunError::Config(ConfigError::Argument(
                InvalidSetting::new(
                    "--replica",
                    replica.index,
                    "0 with --transport iceoryx2 (replicas run in process)",
                ),
            )));
        }
        // Bad input is refused here, on one line, before any process starts.
        let s = Scenario::load(scenario)?;
        crate::commands::controller::controller_choice(&s, controller)?;
        return crate::transport::run_supervisor::run_both(scenario, controller, out);
    }
    let s = Scenario::load(scenario)?;
    let choice = crate::commands::controller::controller_choice(&s, controller)?;
    let dir = run_dir::claim(&s.name, out, &crate::commands::check::resolved_toml(&s))?;
    let mut stream = SeriesStream::create_watching(&dir, TerminationWatch::new())?;
    let run = run_closed_loop_recorded(&s, choice, replica, &mut stream)
        .inspect_err(|_| run_dir::abandon(&dir))?;
    let dropped = stream.finish()?;
    write_results(&s, &run, transport, dropped, &dir)?;
    tracing::info!("results written to {}/", dir.display());
    print_summary(&s, &run)?;
    crate::outln!(
        "results: {}/ (timeseries.csv, controller.csv, summary.json, scenario.toml, forces_work.svg/.png, controller.svg/.png)",
        dir.display()
    )?;
    run.output.end.exit(&dir)
}

/// Writes a run's results into `dir` after its loop: the summary and the
/// plots (the time series were streamed there as the loop ran,
/// [`SeriesStream`], which dropped `dropped` rows).
pub(crate) fn write_results(
    s: &Scenario,
    run: &RunOutput,
    transport: Transport,
    dropped: DroppedRows,
    dir: &Path,
) -> Result<(), RunError> {
    let o = &run.output;
    write_json(
        &dir.join("summary.json"),
        &SummaryFile {
            scenario: &s.name,
            controller: &run.controller,
            transport,
            replica: run.replica.index,
            replica_start_offset_m: run.replica.start_offset(),
            end: &o.end,
            target_depth_m: run.target_depth_m,
            cut: &run.summary,
            ticks: o.ticks,
            limit_faults: o.limit_faults,
            controller_tick: o.tick_times,
            plan_tick: o.plan_times,
            plan_solve: o.solve_times,
            plan_fallbacks: o.fallbacks,
            wall_s: o.wall_s,
            simulated_s: o.simulated_s,
            real_time_factor: o.real_time_factor(),
            dropped_rows: dropped,
        },
    )?;
    let cuts: [&[CutSample]; 1] = [&o.samples];
    let title = format!(
        "{} under {}: force and work on the knife",
        s.name, run.controller
    );
    for name in ["forces_work.svg", "forces_work.png"] {
        render_plot!(&dir.join(name), (1500, 500), |root| draw_cut_curves(
            root, &title, &cuts, false
        ))?;
    }
    let title = format!(
        "{} under {}: what the controller commanded",
        s.name, run.controller
    );
    for name in ["controller.svg", "controller.png"] {
        render_plot!(&dir.join(name), (1200, 500), |root| draw_control_trace(
            root, &title, &o.control
        ))?;
    }
    Ok(())
}

pub(crate) fn print_summary(s: &Scenario, run: &RunOutput) -> Result<(), RunError> {
    let c = &run.summary;
    let o = &run.output;
    crate::outln!(
        "{}: {} [closed loop, {}]",
        s.name,
        s.description,
        run.controller
    )?;
    crate::outln!(
        "end: {:?} after {} ticks ({:.3} s simulated in {:.2} s of wall clock: real-time factor {:.2}); limit faults: {}",
        o.end,
        o.ticks,
        o.simulated_s,
        o.wall_s,
        o.real_time_factor(),
        o.limit_faults
    )?;
    crate::outln!(
        "work {:.4} J, peak Fv {:.3} N, peak Fh {:.3} N, max deformation {:.3} mm, depth {:.2} mm of {:.2} mm, blade used {:.1} mm (path {:.1} mm, {} reversals)",
        c.work_j,
        c.peak_force_vertical_n,
        c.peak_force_horizontal_n,
        c.max_deformation_m * 1e3,
        c.cut_depth_m * 1e3,
        run.target_depth_m * 1e3,
        c.blade_travel_m * 1e3,
        c.blade_path_m * 1e3,
        c.reversals
    )?;
    crate::outln!(
        "controller tick: median {:.2} us, p99 {:.2} us, max {:.2} us (wall clock)",
        o.tick_times.median_us,
        o.tick_times.p99_us,
        o.tick_times.max_us
    )?;
    if o.plan_times.max_us > 0.0 {
        crate::outln!(
            "planning ticks: median {:.1} us, p99 {:.1} us, max {:.1} us; fallbacks {}",
            o.plan_times.median_us,
            o.plan_times.p99_us,
            o.plan_times.max_us,
            o.fallbacks
        )?;
    }
    if o.solve_times.max_us > 0.0 {
        crate::outln!(
            "plans on the planner thread: median {:.1} us, p99 {:.1} us, max {:.1} us",
            o.solve_times.median_us,
            o.solve_times.p99_us,
            o.solve_times.max_us
        )?;
    }
    Ok(())
}
