//! The application's errors and their exit codes.
//!
//! | code | meaning |
//! |---|---|
//! | 0 | success |
//! | 1 | a run that failed after it started (peer lost, solver failure, a result that cannot be written) |
//! | 2 | bad input: config, file, argument, or a model that cannot run with the given settings |
//! | 130, 143 | stopped by SIGINT, SIGTERM after a clean stop |
//! | 141 | stdout closed by its reader (`| head -1`): ends quietly, as a Unix tool killed by SIGPIPE |

use std::path::PathBuf;

use shearcut_sim::InvalidSetting;
use shearcut_sim::capped_read::CappedReadError;

/// Anything the user gave that cannot be used: a config, a file, an argument.
/// Exit code 2, one line, no backtrace.
#[derive(Debug, thiserror::Error)]
pub enum ConfigError {
    /// A file could not be read (missing, too large, not text).
    #[error("cannot read `{path}`: {source}")]
    Read {
        /// The file.
        path: PathBuf,
        /// Why.
        source: CappedReadError,
    },
    /// A TOML file does not parse or has an unknown or missing key.
    #[error("{path}:{line}:{column}: {message}")]
    Parse {
        /// The file (or a built-in name).
        path: String,
        /// 1-based line of the problem.
        line: usize,
        /// 1-based column of the problem.
        column: usize,
        /// What is wrong, on one line.
        message: String,
    },
    /// A value is out of its allowed range.
    #[error("{path}: {setting}")]
    Invalid {
        /// The file (or a built-in name).
        path: String,
        /// The key, value and allowed range.
        setting: InvalidSetting,
    },
    /// A scenario that loads but that neither `simulate` nor `run` can
    /// use (`shearcut check`).
    #[error("{path}: neither simulate nor run can use it: simulate: {simulate}; run: {run}")]
    Unusable {
        /// The file (or a built-in name).
        path: String,
        /// Why `simulate` refuses it.
        simulate: String,
        /// Why `run` refuses it.
        run: String,
    },
    /// A command-line argument is out of its allowed range.
    #[error("{0}")]
    Argument(InvalidSetting),
    /// `--run-id` names a run that a live process of the same role already
    /// serves.
    #[error(
        "run id `{run_id}` is in use: a {role} of it is running (iceoryx2 node {role}/{run_id}); choose another --run-id"
    )]
    RunIdInUse {
        /// The run id.
        run_id: String,
        /// `plant` or `controller`.
        role: &'static str,
    },
}

/// Failures while doing the work (writing results, drawing plots).
#[derive(Debug, thiserror::Error)]
pub enum RunError {
    /// Bad input: exit code 2.
    #[error(transparent)]
    Config(#[from] ConfigError),
    /// Writing an output failed.
    #[error("cannot write `{path}`: {message}")]
    Write {
        /// The output file or directory.
        path: PathBuf,
        /// Why.
        message: String,
    },
    /// The control loop between processes failed (a side lost, braked or
    /// stopped): exit code 1.
    #[error("{0}")]
    Loop(String),
    /// Printing to stdout failed: a closed pipe (exit 141, nothing printed)
    /// or a full or failing device (exit 1).
    #[error("cannot write to stdout: {0}")]
    Stdout(std::io::Error),
    /// A signal stopped a process that had no results to write (a plant, or
    /// a controller before its loop): exit code 130 (SIGINT) or 143
    /// (SIGTERM); the message says what was stopped.
    #[error("{message}")]
    Signalled {
        /// The signal.
        signal: crate::transport::StopSignal,
        /// What was stopped, on one line.
        message: String,
    },
    /// A child process of `run --transport iceoryx2` failed: the supervisor
    /// exits with `code` (2 when a child refused its input, 130/143 when a
    /// child was stopped by a signal the supervisor did not send, else 1).
    #[error("{message}")]
    Supervised {
        /// The exit code.
        code: u8,
        /// How each failed child ended, with its error line, on one line.
        message: String,
    },
    /// A signal stopped the run after its results were written: exit code
    /// 130 (SIGINT) or 143 (SIGTERM).
    #[error("stopped by {signal}: partial results in {dir}/")]
    Stopped {
        /// The signal.
        signal: crate::transport::StopSignal,
        /// Where the partial results are.
        dir: String,
    },
}

/// Exit code of a process whose stdout reader went away (128 + SIGPIPE).
pub const EXIT_CLOSED_PIPE: u8 = 141;

impl RunError {
    /// The process exit code for this error: 2 for bad input,
    /// [`EXIT_CLOSED_PIPE`] for a closed stdout, 1 otherwise.
    pub fn exit_code(&self) -> u8 {
        match self {
            RunError::Config(_) => 2,
            RunError::Stdout(e) if e.kind() == std::io::ErrorKind::BrokenPipe => EXIT_CLOSED_PIPE,
            RunError::Stopped { signal, .. } | RunError::Signalled { signal, .. } => {
                signal.exit_code()
            }
            RunError::Supervised { code, .. } => *code,
            RunError::Write { .. } | RunError::Loop(_) | RunError::Stdout(_) => 1,
        }
    }

    /// Whether the error is reported by its exit code alone (a closed
    /// stdout: its reader wants no more, on either stream).
    pub fn is_quiet(&self) -> bool {
        self.exit_code() == EXIT_CLOSED_PIPE
    }

    /// The error of a process named `name` (`plant/<run-id>`) whose
    /// iceoryx2 services failed: a run id that is not allowed or in use, or
    /// a prefix that is not allowed, is bad input (exit 2), a signal during
    /// the set-up a stop (130/143), anything else a failed run (exit 1).
    pub fn service(name: &str, e: crate::transport::ServiceError) -> Self {
        use crate::transport::loop_services::PREFIX_ENV;
        let names = "characters among letters, digits, '-', '_' and '.'";
        match e {
            crate::transport::ServiceError::RunId(id) => RunError::Config(ConfigError::Argument(
                InvalidSetting::new("--run-id", id, format!("must be 1 to 64 {names}")),
            )),
            crate::transport::ServiceError::Prefix(prefix) => {
                RunError::Config(ConfigError::Argument(InvalidSetting::new(
                    PREFIX_ENV,
                    prefix,
                    format!("must be 1 to 32 {names} (the iceoryx2 prefix)"),
                )))
            }
            crate::transport::ServiceError::RunIdInUse { run_id, role } => {
                RunError::Config(ConfigError::RunIdInUse {
                    run_id,
                    role: role.as_str(),
                })
            }
            crate::transport::ServiceError::Stopped(signal) => RunError::Signalled {
                signal,
                message: format!("{name}: {e}"),
            },
            e => RunError::Loop(format!("{name}: {e}")),
        }
    }

    /// A write error for `path`.
    pub fn write(path: impl Into<PathBuf>, err: impl std::fmt::Display) -> Self {
        RunError::Write {
            path: path.into(),
            message: err.to_string(),
        }
    }
}
