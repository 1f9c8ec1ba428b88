//! The `shearcut` command line.

use std::io::Write;
use std::path::PathBuf;

use clap::{Parser, Subcommand};

use crate::error::RunError;

/// Prints `text` to stdout and flushes it. A failed write is an error, not
/// a panic: a closed pipe ends the command quietly (exit 141), a full
/// device with one line (exit 1).
pub fn print(text: &str) -> Result<(), RunError> {
    let mut out = std::io::stdout().lock();
    out.write_all(text.as_bytes())
        .and_then(|()| out.flush())
        .map_err(RunError::Stdout)
}

/// `println!` through [`print`]: evaluates to `Result<(), RunError>`, so a
/// closed or full stdout is an error to return, not a panic.
#[macro_export]
macro_rules! outln {
    ($($arg:tt)*) => {
        $crate::cli::print(&format!("{}\n", format_args!($($arg)*)))
    };
}

/// shearcut: robotic slicing of fruits and vegetables — a fracture-mechanics
/// cutting model (seed 000), its surrogates, an MPC and an arm-style loop.
///
/// With no subcommand, runs the main job on the built-in default scenario.
#[derive(Debug, Parser)]
#[command(name = "shearcut", version, about, long_about)]
pub struct Cli {
    /// What to do (default: the main job on the built-in default scenario).
    #[command(subcommand)]
    pub command: Option<Command>,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Print the slice-push toughness law r(ξ,ν) (seed 000 eq. 6) and, with
    /// --plot, draw seed 000 Fig. 3 and write its CSV.
    Toughness {
        /// Poisson's ratio ν, in (0, 0.5): the law is finite on the open
        /// interval and falls to 0 for ξ > 0 as ν → 0.5 (Fig. 3's right edge).
        /// A scenario's `poisson_ratio` stops at 0.49, where its plane-strain
        /// elements lock.
        #[arg(long, allow_negative_numbers = true)]
        nu: f64,
        /// Slice-push ratio ξ = tan α, in [0, 20].
        #[arg(long, allow_negative_numbers = true)]
        xi: f64,
        /// Draw Fig. 3 (r against ν for several ξ) to this .svg or .png file;
        /// the table goes to the same name with extension .csv.
        #[arg(long, value_name = "FILE")]
        plot: Option<PathBuf>,
    },
    /// Cut the scenario's object open-loop with its prescribed motion, one cut
    /// per slice-push ratio, and write time series, summary and plots.
    Simulate {
        /// Scenario TOML file, or the name of a built-in scenario.
        scenario: String,
        /// Where the results go.
        #[command(flatten)]
        out: crate::run_dir::Destination,
    },
    /// Close the loop: a controller drives the plant tick by tick (lockstep)
    /// until the target depth, and the run's time series, controller trace,
    /// summary and plots are written.
    Run {
        /// Scenario TOML file, or the name of a built-in scenario.
        scenario: String,
        /// The controller: mpc, press, slice:XI or force:N (default: the
        /// scenario's `[controller] kind`).
        #[arg(long, value_name = "NAME")]
        controller: Option<String>,
        /// How controller and plant talk.
        #[arg(long, value_enum, default_value = "inproc")]
        transport: crate::commands::run::Transport,
        /// Run replica K of the scenario: the knife starts K·5 µm higher
        /// above the object (as `compare --replicas` does; in-process only).
        #[arg(long, value_name = "K", default_value_t = 0, allow_negative_numbers = true,
              value_parser = clap::value_parser!(u32).range(0..=crate::commands::compare::MAX_REPLICAS as i64 - 1))]
        replica: u32,
        /// Where the results go.
        #[command(flatten)]
        out: crate::run_dir::Destination,
    },
    /// Compare the MPC with the baselines in closed loop on one scenario:
    /// pressing, the best constant slice-push ratio under the same blade
    /// budget (searched), and the force loop; write a table and a bar plot.
    Compare {
        /// Scenario TOML file, or the name of a built-in scenario.
        scenario: String,
        /// Replicas of the run (replica k starts the knife k·5 µm higher)
        /// the MPC and the best constant ratio's candidates run on: their
        /// rows are the means, with the work's range; 1 runs the scenario
        /// as given only.
        #[arg(long, default_value_t = crate::commands::compare::DEFAULT_REPLICAS, allow_negative_numbers = true,
              value_parser = clap::value_parser!(u64).range(1..=crate::commands::compare::MAX_REPLICAS))]
        replicas: u64,
        /// Runs at a time (default: the machine's cores); the results do
        /// not depend on it.
        #[arg(long, value_name = "N", allow_negative_numbers = true,
              value_parser = clap::value_parser!(u32).range(1..=1024))]
        jobs: Option<u32>,
        /// Where the results go.
        #[command(flatten)]
        out: crate::run_dir::Destination,
    },
    /// Tune controllers: run a sweep of controller settings over scenarios
    /// and perturbed variants (in parallel, resumably, or one shard of it),
    /// and write one row per run; `tune merge DIR…` combines shards.
    Tune(crate::commands::tune::TuneArgs),
    /// Run time-optimal jerk-limited trajectory cases (one JSON object per
    /// line, ruckig's field names) and write one JSON result per line.
    Trajectory {
        /// The cases, JSONL.
        #[arg(long, value_name = "FILE.jsonl")]
        cases: PathBuf,
        /// Where to write the results (default: stdout).
        #[arg(long, value_name = "FILE")]
        out: Option<PathBuf>,
    },
    /// Fit a surrogate of the cross-section model for a material and knife
    /// (full-model sweeps on both cores, least squares, accuracy against
    /// held-out runs, plots); see docs/surrogates.md.
    Fit {
        /// Material preset (potato-cuboid, eggplant-cuboid, potato-whole, eggplant-whole, agar).
        #[arg(long)]
        material: String,
        /// Knife preset with a blade (straight, chef).
        #[arg(long)]
        knife: String,
        /// Surrogate file to write (default: config/surrogates/<material>-<knife>.toml);
        /// the accuracy report and plot go next to it.
        #[arg(long, value_name = "FILE")]
        out: Option<PathBuf>,
        /// Weight (>= 0) of one row per run asking the strain-energy rate's
        /// mean over the run's settled window to match the run's (0: none;
        /// the shipped potato-cuboid files use 10; docs/surrogates.md).
        #[arg(
            long,
            value_name = "W",
            default_value_t = 0.0,
            allow_negative_numbers = true
        )]
        window_weight: f64,
        /// Section sizes added to the fit's sweeps, HEIGHTxHALF_WIDTH in mm,
        /// comma-separated (e.g. 65x95,50x60): for objects whose equivalent
        /// section lies beyond the default 20–45 mm high, 10–30 mm half
        /// width (docs/surrogates.md).
        #[arg(
            long,
            value_name = "HxW",
            value_delimiter = ',',
            allow_hyphen_values = true
        )]
        extra_sizes: Vec<String>,
        /// Section sizes added to the held-out runs of the accuracy report
        /// (as --extra-sizes; none of them a fitted size).
        #[arg(
            long,
            value_name = "HxW",
            value_delimiter = ',',
            allow_hyphen_values = true
        )]
        extra_held_out_sizes: Vec<String>,
    },
    /// The plant process of the arm-style loop: serve the scenario's plant
    /// over iceoryx2 to the controller of run ID (lockstep or realtime per
    /// the scenario's `[loop] clock`), braking after `missed_command_limit`
    /// consecutive missed commands.
    Plant {
        /// Scenario TOML file, or the name of a built-in scenario.
        #[arg(long)]
        scenario: String,
        /// The run's id (service names `shearcut/<ID>/...`): letters, digits, '-', '_', '.'.
        #[arg(long, value_name = "ID")]
        run_id: String,
        /// The controller whose nominal direction the plant's sections are
        /// planned for (default: the scenario's `[controller] kind`).
        #[arg(long, value_name = "NAME")]
        controller: Option<String>,
        /// How to wait for commands.
        #[arg(long, value_enum, default_value = "blocking")]
        wait: crate::transport::WaitMode,
    },
    /// The controller process of the arm-style loop: drive run ID's plant
    /// (`shearcut plant` or an arm bridge) over iceoryx2 and write the results.
    Controller {
        /// Scenario TOML file, or the name of a built-in scenario.
        #[arg(long)]
        scenario: String,
        /// The run's id (service names `shearcut/<ID>/...`): letters, digits, '-', '_', '.'.
        #[arg(long, value_name = "ID")]
        run_id: String,
        /// The controller: mpc, press, slice:XI or force:N (default: the
        /// scenario's `[controller] kind`).
        #[arg(long, value_name = "NAME")]
        controller: Option<String>,
        /// How to wait for measurements.
        #[arg(long, value_enum, default_value = "blocking")]
        wait: crate::transport::WaitMode,
        /// Where the results go.
        #[command(flatten)]
        out: crate::run_dir::Destination,
    },
    /// Validate a scenario, say whether `simulate` and `run` take it, and print its resolved values.
    Check {
        /// Scenario TOML file, or the name of a built-in scenario (`shearcut scenarios`).
        scenario: String,
    },
    /// List the built-in scenarios, one line each: name and description.
    Scenarios,
}

impl Cli {
    /// Parses the process's arguments; `--help` ends with the built-in
    /// scenarios' names. Bad arguments exit 2 with clap's first line
    /// ([`exit_on`]).
    pub fn parse_with_scenarios() -> Self {
        let matches = <Self as clap::CommandFactory>::command()
            .after_help(crate::commands::scenarios::names_help())
            .try_get_matches()
            .unwrap_or_else(|e| exit_on(e));
        <Self as clap::FromArgMatches>::from_arg_matches(&matches).unwrap_or_else(|e| exit_on(e))
    }
}

/// Ends the process for a parse outcome: help and version as clap prints
/// them; bad arguments (exit 2) with the one line that says what is wrong
/// (`error: invalid value '0' for '--jobs <N>': …`), without clap's tips
/// and usage.
fn exit_on(e: clap::Error) -> ! {
    use clap::error::ErrorKind;
    match e.kind() {
        ErrorKind::DisplayHelp
        | ErrorKind::DisplayVersion
        | ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => e.exit(),
        _ => {
            eprintln!("{}", one_line(&e.render().to_string()));
            std::process::exit(2)
        }
    }
}

/// Clap's message on one line: its first paragraph (the error and what it
/// names on the lines below it: the missing arguments, the possible
/// values), without the tips and usage after the first blank line.
fn one_line(text: &str) -> String {
    let line = text
        .lines()
        .take_while(|l| !l.trim().is_empty())
        .map(str::trim)
        .filter(|l| !l.starts_with("tip:"))
        .collect::<Vec<_>>()
        .join(" ");
    if line.is_empty() {
        "error: bad arguments".to_string()
    } else {
        line
    }
}

#[cfg(test)]
mod tests {
    use super::one_line;

    #[test]
    fn clap_errors_keep_what_they_name_on_one_line() {
        let missing = "error: the following required arguments were not provided:\n  \
                       <SCENARIO>\n\nUsage: shearcut run <SCENARIO>\n\nFor more information, try '--help'.\n";
        assert_eq!(
            one_line(missing),
            "error: the following required arguments were not provided: <SCENARIO>"
        );
        let choice = "error: invalid value 'foo' for '--transport <TRANSPORT>'\n  \
                      [possible values: inproc, iceoryx2]\n\nFor more information, try '--help'.\n";
        assert_eq!(
            one_line(choice),
            "error: invalid value 'foo' for '--transport <TRANSPORT>' \
             [possible values: inproc, iceoryx2]"
        );
        let tip = "error: unexpected argument '-1' found\n\n  tip: to pass '-1' as a value, use '-- -1'\n";
        assert_eq!(one_line(tip), "error: unexpected argument '-1' found");
    }
}
