//! The application's errors and their exit codes.

use std::path::PathBuf;

use shearcut_sim::InvalidSetting;

/// Anything the user gave that cannot be used: a config, a file, an argument.
/// Exit code 2, one line, no backtrace.
#[derive(Debug, thiserror::Error)]
pub enum ConfigError {
    /// A file could not be read.
    #[error("cannot read `{path}`: {source}")]
    Read {
        /// The file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
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
    /// A command-line argument is out of its allowed range.
    #[error("{0}")]
    Argument(InvalidSetting),
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
}

impl RunError {
    /// The process exit code for this error: 2 for bad input, 1 otherwise.
    pub fn exit_code(&self) -> u8 {
        match self {
            RunError::Config(_) => 2,
            RunError::Write { .. } | RunError::Loop(_) => 1,
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
