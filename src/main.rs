//! The `shearcut` binary.

use std::io::Write;
use std::process::ExitCode;

use shearcut::cli::{Cli, Command};
use shearcut::commands;
use shearcut::error::RunError;
use shearcut::run_replica::RunReplica;

fn main() -> ExitCode {
    shearcut::logging::init();
    let cli = Cli::parse_with_scenarios();
    let result: Result<(), RunError> = match cli.command {
        None => commands::default_job::run(),
        Some(Command::Toughness { nu, xi, plot }) => {
            commands::toughness::run(nu, xi, plot.as_deref())
        }
        Some(Command::Simulate { scenario, out }) => commands::simulate::run(&scenario, &out),
        Some(Command::Run {
            scenario,
            controller,
            transport,
            replica,
            out,
        }) => commands::run::run(
            &scenario,
            controller.as_deref(),
            transport,
            RunReplica { index: replica },
            &out,
        ),
        Some(Command::Compare {
            scenario,
            replicas,
            jobs,
            out,
        }) => commands::compare::run(
            &scenario,
            replicas,
            jobs.map_or_else(shearcut::tune::executor::default_threads, |n| n as usize),
            &out,
        ),
        Some(Command::Tune(args)) => commands::tune::run(args),
        Some(Command::Trajectory { cases, out }) => {
            commands::trajectory::run(&cases, out.as_deref())
        }
        Some(Command::Check { scenario }) => commands::check::run(&scenario),
        Some(Command::Scenarios) => commands::scenarios::run(),
        Some(Command::Fit {
            material,
            knife,
            out,
            window_weight,
            extra_sizes,
            extra_held_out_sizes,
        }) => commands::fit::run(&commands::fit::FitRequest {
            material: &material,
            knife: &knife,
            window_weight,
            extra_sizes: &extra_sizes,
            extra_held_out_sizes: &extra_held_out_sizes,
            out: out.as_deref(),
        }),
        Some(Command::Plant {
            scenario,
            run_id,
            controller,
            wait,
        }) => commands::plant::run(&scenario, &run_id, controller.as_deref(), wait),
        Some(Command::Controller {
            scenario,
            run_id,
            controller,
            wait,
            out,
        }) => commands::controller::run(&scenario, &run_id, controller.as_deref(), wait, &out),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            if !e.is_quiet() {
                // A closed stderr leaves the exit code as the only report.
                let _ = writeln!(std::io::stderr(), "error: {e}");
            }
            ExitCode::from(e.exit_code())
        }
    }
}
