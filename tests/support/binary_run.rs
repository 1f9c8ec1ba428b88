//! Runs the `shearcut` binary and reads back what it wrote: the harness of
//! the command-line tests (included with `#[path]`). Logs are filtered to
//! errors (`RUST_LOG=error`), so stderr carries only the binary's own lines.
#![allow(dead_code)] // Each test binary uses the parts it needs.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// Runs `shearcut args…` to completion.
pub fn shearcut(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_shearcut"))
        .args(args)
        .env("RUST_LOG", "error")
        .output()
        .expect("the shearcut binary runs")
}

/// A fresh directory under the system's temporary directory for one test
/// (`shearcut-<name>-<pid>`); the test removes it when done.
pub fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("shearcut-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Asserts that the command succeeded, showing its stderr if not.
pub fn assert_success(o: &Output) {
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

/// Asserts that every one of `files` was written in `dir`.
pub fn assert_files(dir: &Path, files: &[&str]) {
    for f in files {
        assert!(dir.join(f).is_file(), "{f} missing in {}", dir.display());
    }
}

/// The run's `summary.json` in `dir`.
pub fn read_summary(dir: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap()
}

/// What the command printed on stdout.
pub fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// What the command printed on stderr.
pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Sends SIG`signal` (`INT`, `TERM`) to the running `child`, reads the rest
/// of its stdout (`stdout`, taken from it) and waits for it: its output and
/// what it printed after the signal.
pub fn signal_and_wait(
    child: std::process::Child,
    mut stdout: std::io::BufReader<std::process::ChildStdout>,
    signal: &str,
) -> (Output, String) {
    let sent = Command::new("kill")
        .args([&format!("-{signal}"), &child.id().to_string()])
        .status()
        .unwrap();
    assert!(sent.success());
    let mut rest = String::new();
    std::io::Read::read_to_string(&mut stdout, &mut rest).unwrap();
    (child.wait_with_output().unwrap(), rest)
}
