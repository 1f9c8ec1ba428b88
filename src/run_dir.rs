//! Result directories: one new directory per run, never shared by two.
//!
//! A run claims its directory before it starts: `runs/<scenario>-<UTC
//! time>` (with `-N` appended while that name is taken) by default, or the
//! directory `--out` names, which must not exist or be empty unless
//! `--overwrite` is given. The claim is atomic (the directory's creation, or
//! for an existing empty one the creation of its [`CLAIM`] file), so two
//! runs started at once never write into the same directory. Each result
//! file is written under a temporary name and renamed into place
//! ([`publish`](crate::result_file::publish)): a file in a run directory is either complete or absent.

use std::fs::OpenOptions;
use std::io::ErrorKind;
use std::path::{Path, PathBuf};
use std::time::{SystemTime, UNIX_EPOCH};

use shearcut_sim::InvalidSetting;

use crate::error::{ConfigError, RunError};
use crate::result_file::publish;

/// The file that marks a directory as claimed by a run: the resolved
/// scenario the run was started with, written first.
pub const CLAIM: &str = "scenario.toml";

/// Where a command writes its results (`--out`, `--overwrite`).
#[derive(Debug, Clone, Default, PartialEq, Eq, clap::Args)]
pub struct Destination {
    /// Result directory (default: runs/<scenario>-<UTC time>). It must not
    /// exist or be empty, unless --overwrite is given.
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Replace the contents of an existing --out directory.
    #[arg(long, requires = "out")]
    pub overwrite: bool,
}

impl Destination {
    /// Results to `out` (refused if it holds anything).
    pub fn to(out: &Path) -> Self {
        Self {
            out: Some(out.to_path_buf()),
            overwrite: false,
        }
    }
}

/// Claims the result directory for a run of scenario `name` and writes
/// `scenario` (the resolved scenario) into it as [`CLAIM`].
///
/// # Errors
/// `--out` names a directory that holds files and `--overwrite` is not
/// given, or another run claimed it first (exit 2); the directory cannot
/// be created or written (exit 1).
pub fn claim(name: &str, to: &Destination, scenario: &str) -> Result<PathBuf, RunError> {
    let dir = match &to.out {
        Some(dir) => {
            claim_named(dir, to.overwrite)?;
            dir.clone()
        }
        None => claim_default(name)?,
    };
    publish(&dir.join(CLAIM), |path| {
        std::fs::write(path, scenario).map_err(|e| RunError::write(path, e))
    })?;
    Ok(dir)
}

/// Removes a claimed directory that holds nothing but its [`CLAIM`] and
/// empty files (series streams not yet written to): a run refused before
/// it produced anything leaves no directory behind.
pub fn abandon(dir: &Path) {
    let only_claim = std::fs::read_dir(dir).is_ok_and(|entries| {
        entries.filter_map(Result::ok).all(|e| {
            e.file_name() == CLAIM || e.metadata().is_ok_and(|m| m.is_file() && m.len() == 0)
        })
    });
    if only_claim {
        let _ = std::fs::remove_dir_all(dir);
    }
}

/// Checks, without claiming it, that `to` could be claimed: what a
/// supervisor checks before it starts the process that claims it.
///
/// # Errors
/// As [`claim`]'s refusals (exit 2).
pub fn check(to: &Destination) -> Result<(), RunError> {
    let Some(dir) = &to.out else {
        return Ok(());
    };
    if !dir.exists() || to.overwrite {
        return Ok(());
    }
    if holds_files(dir)? {
        Err(refused(dir, HOLDS_FILES))
    } else {
        Ok(())
    }
}

/// Whether the existing `dir` holds any file; refused if it is not a
/// directory.
pub(crate) fn holds_files(dir: &Path) -> Result<bool, RunError> {
    if !dir.is_dir() {
        return Err(refused(dir, "a directory (this is a file)"));
    }
    Ok(std::fs::read_dir(dir)
        .map_err(|e| RunError::write(dir, e))?
        .next()
        .is_some())
}

/// What `--out` allows, when it names a directory that holds files.
const HOLDS_FILES: &str = "a new or empty directory (it holds files; --overwrite replaces them)";

/// A refusal of `--out` = `dir`.
pub(crate) fn refused(dir: &Path, allowed: impl Into<String>) -> RunError {
    RunError::Config(ConfigError::Argument(InvalidSetting::new(
        "--out",
        dir.display(),
        allowed,
    )))
}

/// Claims `dir`: creates it, or takes it if it exists and is empty (or,
/// with `overwrite`, after emptying it).
fn claim_named(dir: &Path, overwrite: bool) -> Result<(), RunError> {
    if let Some(parent) = dir.parent()
        && !parent.as_os_str().is_empty()
    {
        std::fs::create_dir_all(parent).map_err(|e| uncreatable(dir, parent, &e))?;
    }
    match std::fs::create_dir(dir) {
        Ok(()) => return Ok(()),
        Err(e) if e.kind() == ErrorKind::AlreadyExists => {}
        Err(e) => return Err(uncreatable(dir, dir, &e)),
    }
    if holds_files(dir)? {
        if !overwrite {
            return Err(refused(dir, HOLDS_FILES));
        }
        std::fs::remove_dir_all(dir).map_err(|e| RunError::write(dir, e))?;
        std::fs::create_dir(dir).map_err(|e| RunError::write(dir, e))?;
    }
    // The claim: only one run creates the file in an empty directory.
    match OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(dir.join(CLAIM))
    {
        Ok(_) => Ok(()),
        Err(e) if e.kind() == ErrorKind::AlreadyExists => Err(refused(
            dir,
            "a directory no other run is writing to (another run claimed it)",
        )),
        Err(e) => Err(RunError::write(dir, e)),
    }
}

/// A refusal of `--out` = `dir` that cannot be created: `at` (the
/// directory or a parent) failed with `e`. The path is the user's input, so
/// this is bad input (exit 2), not a failed write.
pub fn uncreatable(dir: &Path, at: &Path, e: &std::io::Error) -> RunError {
    unusable_output("--out", dir, at, e, "a directory this process can create")
}

/// A refusal of the output path `path` given as argument `key`, which
/// cannot be created (`what` it must be): `at` (the path or a parent)
/// failed with `e`. Bad input (exit 2): the error names the first
/// component that is a file, else the system's reason.
pub fn unusable_output(
    key: &str,
    path: &Path,
    at: &Path,
    e: &std::io::Error,
    what: &str,
) -> RunError {
    // The component nearest the root that is a file blocks the rest.
    let file = at
        .ancestors()
        .filter(|a| !a.as_os_str().is_empty() && a.exists() && !a.is_dir())
        .last();
    let reason = match file {
        Some(f) => format!("{} is a file", f.display()),
        None => format!("{}: {e}", at.display()),
    };
    RunError::Config(ConfigError::Argument(InvalidSetting::new(
        key,
        path.display(),
        format!("{what} ({reason})"),
    )))
}

/// Checks, before any work, that the output file `path` given as argument
/// `key` can be written: not a directory, its directory exists or is
/// created, and a new file can be made there (tried as `<path>.probe`, then
/// removed: no file is left behind). Bad input (exit 2), naming `key`.
pub fn claim_output_file(key: &str, path: &Path) -> Result<(), RunError> {
    let what = "a file this process can create";
    let refused = |at: &Path, e: std::io::Error| unusable_output(key, path, at, &e, what);
    if path.is_dir() {
        return Err(refused(
            path,
            std::io::Error::new(ErrorKind::IsADirectory, "a directory"),
        ));
    }
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(|e| refused(dir, e))?;
    }
    let mut probe = path.as_os_str().to_owned();
    probe.push(".probe");
    std::fs::File::create(&probe).map_err(|e| refused(path, e))?;
    std::fs::remove_file(&probe).map_err(|e| refused(path, e))
}

/// Creates `runs/<name>-<YYYYmmdd-HHMMSS>` (UTC), or with `-N` appended the
/// first such name not yet taken.
fn claim_default(name: &str) -> Result<PathBuf, RunError> {
    // Naming a result directory is the one use of wall time here.
    #[allow(clippy::disallowed_methods)]
    let secs = SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .map_or(0, |d| d.as_secs());
    let runs = PathBuf::from("runs");
    std::fs::create_dir_all(&runs).map_err(|e| RunError::write(&runs, e))?;
    let base = format!("{name}-{}", utc_stamp(secs));
    for n in 1.. {
        let dir = if n == 1 {
            runs.join(&base)
        } else {
            runs.join(format!("{base}-{n}"))
        };
        match std::fs::create_dir(&dir) {
            Ok(()) => return Ok(dir),
            Err(e) if e.kind() == ErrorKind::AlreadyExists => continue,
            Err(e) => return Err(RunError::write(&dir, e)),
        }
    }
    unreachable!("an unbounded range ends only by returning")
}

/// `YYYYmmdd-HHMMSS` for `secs` since the Unix epoch, UTC (civil-from-days,
/// H. Hinnant's algorithm).
pub fn utc_stamp(secs: u64) -> String {
    let days = (secs / 86_400) as i64;
    let rem = secs % 86_400;
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + i64::from(m <= 2);
    format!(
        "{y:04}{m:02}{d:02}-{:02}{:02}{:02}",
        rem / 3600,
        (rem % 3600) / 60,
        rem % 60
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn known_stamps() {
        assert_eq!(utc_stamp(0), "19700101-000000");
        // 2000-02-29 12:34:56 UTC = 951827696.
        assert_eq!(utc_stamp(951_827_696), "20000229-123456");
        // 2026-11-22 03:24:05 UTC.
        assert_eq!(utc_stamp(1_795_317_845), "20261122-032405");
    }

    fn scratch(name: &str) -> PathBuf {
        let d =
            std::env::temp_dir().join(format!("shearcut-run-dir-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        d
    }

    #[test]
    fn a_new_or_empty_directory_is_claimed_once() {
        let d = scratch("empty");
        std::fs::create_dir_all(&d).unwrap();
        assert_eq!(claim("s", &Destination::to(&d), "a").unwrap(), d);
        assert_eq!(std::fs::read_to_string(d.join(CLAIM)).unwrap(), "a");
        // A second run is refused, with exit code 2, naming --out.
        let e = claim("s", &Destination::to(&d), "b").unwrap_err();
        assert_eq!(e.exit_code(), 2);
        assert!(e.to_string().contains("--out"), "{e}");
        assert_eq!(std::fs::read_to_string(d.join(CLAIM)).unwrap(), "a");
        std::fs::remove_dir_all(&d).unwrap();
        let fresh = d.join("deeper");
        assert!(claim("s", &Destination::to(&fresh), "c").is_ok());
        std::fs::remove_dir_all(&d).unwrap();
    }

    #[test]
    fn overwrite_replaces_what_was_there() {
        let d = scratch("overwrite");
        std::fs::create_dir_all(&d).unwrap();
        std::fs::write(d.join("old.csv"), "x").unwrap();
        let to = Destination {
            out: Some(d.clone()),
            overwrite: true,
        };
        claim("s", &to, "new").unwrap();
        assert!(!d.join("old.csv").exists());
        assert_eq!(std::fs::read_to_string(d.join(CLAIM)).unwrap(), "new");
        std::fs::remove_dir_all(&d).unwrap();
    }
}
