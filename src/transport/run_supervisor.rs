//! `shearcut run --transport iceoryx2`: spawns the plant and controller
//! processes for one run, supervises them and reports how they ended, on
//! one line and with the exit code that names the cause (a child's bad
//! input 2, a child stopped by a signal 130/143, any other failure 1).

use std::io::{BufRead, BufReader, Write};
use std::path::Path;
use std::process::{Child, Command, ExitStatus, Stdio};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use super::termination_watch::{StopSignal, TerminationWatch};
use crate::error::RunError;
use crate::run_dir::Destination;

/// How long the plant may outlive the controller (it brakes after its
/// missed-command limit if the controller died without ending the run).
const PLANT_GRACE: Duration = Duration::from_secs(5);
/// How long the controller may outlive the plant (it detects the loss
/// within its response timeout).
const CONTROLLER_GRACE: Duration = Duration::from_secs(10);
/// How long a child may outlive its peer's failure before the supervisor
/// asks it to stop: a controller that never saw its plant would otherwise
/// wait for its connect timeout, a plant for its missed-command limit.
const PEER_FAILED_PATIENCE: Duration = Duration::from_secs(1);

/// A unique run id: `<scenario>-<pid>-<ns>` (scenario name reduced to the
/// allowed characters and 32 of them).
#[allow(clippy::disallowed_methods)] // A unique name, not model time.
pub fn new_run_id(scenario: &str) -> String {
    let name: String = Path::new(scenario)
        .file_stem()
        .and_then(|s| s.to_str())
        .unwrap_or("run")
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '_'
            }
        })
        .take(32)
        .collect();
    let ns = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.subsec_nanos());
    format!("{name}-{}-{ns}", std::process::id())
}

/// How a child ended, in words: `the plant process (pid N) exited with
/// code C` or `… died by signal S`.
fn describe(role: &str, pid: u32, status: ExitStatus) -> String {
    use std::os::unix::process::ExitStatusExt;
    match (status.code(), status.signal()) {
        (Some(c), _) => format!("the {role} process (pid {pid}) exited with code {c}"),
        (None, Some(s)) => format!("the {role} process (pid {pid}) died by signal {s}"),
        _ => format!("the {role} process (pid {pid}) ended: {status}"),
    }
}

/// Forwards `child`'s stderr to this process's stderr line by line, but for
/// the lines starting `error: ` (a process's one error line, its last):
/// the last of them is returned once the child's stderr closes, for the
/// supervisor's own line. A closed stderr here loses the forwarded lines
/// only.
fn forward_stderr(child: &mut Child) -> JoinHandle<Option<String>> {
    let stderr = child.stderr.take();
    std::thread::spawn(move || {
        let mut error = None;
        let mut reader = BufReader::new(stderr?);
        let mut line = Vec::new();
        loop {
            line.clear();
            match reader.read_until(b'\n', &mut line) {
                Ok(0) | Err(_) => return error,
                Ok(_) => {}
            }
            let text = String::from_utf8_lossy(&line);
            let text = text.trim_end_matches(['\n', '\r']);
            match text.strip_prefix("error: ") {
                Some(e) => error = Some(e.to_string()),
                None => {
                    let _ = writeln!(std::io::stderr(), "{text}");
                }
            }
        }
    })
}

/// One child process: the process, its role and its stderr's forwarder.
struct Supervised {
    role: &'static str,
    child: Child,
    stderr: Option<JoinHandle<Option<String>>>,
}

/// How a supervised child ended.
struct ChildEnd {
    role: &'static str,
    pid: u32,
    /// `None` if it could not be reaped.
    status: Option<ExitStatus>,
    /// Whether the supervisor had asked it to stop (sent it a signal).
    asked: bool,
    /// Its error line (without `error: `), if it printed one.
    error: Option<String>,
}

impl Supervised {
    /// Starts `command` as the `role` process, its stderr forwarded.
    fn spawn(role: &'static str, command: &mut Command) -> Result<Self, RunError> {
        let mut child = command
            .stderr(Stdio::piped())
            .spawn()
            .map_err(|e| RunError::Loop(format!("cannot start the {role} process: {e}")))?;
        let stderr = Some(forward_stderr(&mut child));
        Ok(Self {
            role,
            child,
            stderr,
        })
    }

    /// Its end, once its `status` is known (joins the stderr forwarder).
    fn ended(&mut self, status: Option<ExitStatus>, asked: bool) -> ChildEnd {
        let error = self.stderr.take().and_then(|h| h.join().ok()).flatten();
        ChildEnd {
            role: self.role,
            pid: self.child.id(),
            status,
            asked,
            error,
        }
    }

    /// Its end once its peer ended as `peer`: after a peer that ended well
    /// it has up to `grace` to end by itself (then SIGKILL); after a peer
    /// that failed, [`PEER_FAILED_PATIENCE`], and is then asked to stop with
    /// SIGTERM ([`stop`], up to `grace`).
    fn after_peer(&mut self, peer: &ChildEnd, grace: Duration) -> ChildEnd {
        if peer.is_fine() {
            let s = wait_or_kill(&mut self.child, grace);
            return self.ended(s, false);
        }
        match wait_within(&mut self.child, PEER_FAILED_PATIENCE) {
            Some(s) => self.ended(Some(s), false),
            None => {
                let s = stop(&mut self.child, StopSignal::Sigterm, grace);
                self.ended(s, true)
            }
        }
    }
}

impl ChildEnd {
    /// Whether it ended well: success, or a clean stop on a signal the
    /// supervisor sent.
    fn is_fine(&self) -> bool {
        self.status
            .is_some_and(|s| s.success() || (self.asked && stopped_cleanly(Some(s))))
    }

    /// `the plant process (pid N) exited with code C: <its error line>`.
    fn failure(&self) -> String {
        let how = match self.status {
            Some(s) => describe(self.role, self.pid, s),
            None => format!(
                "the {} process (pid {}) could not be reaped",
                self.role, self.pid
            ),
        };
        match &self.error {
            Some(e) => format!("{how}: {e}"),
            None => how,
        }
    }
}

/// The supervisor's exit code for children that failed: 2 if one refused
/// its input, else 130/143 if one stopped cleanly on a signal the
/// supervisor did not send, else 1.
fn failure_code(failed: &[&ChildEnd]) -> u8 {
    let codes: Vec<i32> = failed.iter().filter_map(|c| c.status?.code()).collect();
    if codes.contains(&2) {
        return 2;
    }
    [StopSignal::Sigint, StopSignal::Sigterm]
        .into_iter()
        .map(StopSignal::exit_code)
        .find(|&c| codes.contains(&i32::from(c)))
        .unwrap_or(1)
}

/// Sends `signal` to `child` (through `kill(1)`: no unsafe code here).
fn signal(child: &Child, signal: StopSignal) {
    let name = match signal {
        StopSignal::Sigint => "-INT",
        StopSignal::Sigterm => "-TERM",
    };
    let _ = Command::new("kill")
        .args([name, &child.id().to_string()])
        .status();
}

/// Sends SIGTERM to `child`.
fn terminate(child: &Child) {
    signal(child, StopSignal::Sigterm);
}

/// How often [`stop`] repeats its signal.
const RESEND: Duration = Duration::from_millis(500);

/// Sends `sent` (the signal the supervisor received) to `child`, repeated
/// every [`RESEND`] until it exits or `grace` has passed (then SIGKILL).
/// iceoryx2 keeps one pending signal in a flag that its own calls can reset
/// (`SignalHandler::call_and_fetch` clears it before a call, and every
/// termination check consumes it), so a single signal can be lost and a
/// child under load run on for the whole grace. A repeated signal gets
/// through.
fn stop(child: &mut Child, sent: StopSignal, grace: Duration) -> Option<ExitStatus> {
    #[allow(clippy::disallowed_methods)] // Supervision deadline.
    let until = Instant::now() + grace;
    loop {
        signal(child, sent);
        #[allow(clippy::disallowed_methods)]
        let left = until.saturating_duration_since(Instant::now());
        if left <= RESEND {
            return wait_or_kill(child, left);
        }
        if let Some(s) = wait_within(child, RESEND) {
            return Some(s);
        }
    }
}

/// Waits for `child` up to `grace`, without killing it: its exit status, or
/// None if it is still running.
fn wait_within(child: &mut Child, grace: Duration) -> Option<ExitStatus> {
    #[allow(clippy::disallowed_methods)] // Supervision deadline.
    let until = Instant::now() + grace;
    loop {
        if let Ok(Some(s)) = child.try_wait() {
            return Some(s);
        }
        #[allow(clippy::disallowed_methods)]
        if Instant::now() > until {
            return None;
        }
        std::thread::sleep(Duration::from_millis(5));
    }
}

/// Waits for `child` up to `grace`; kills it (SIGKILL) after that.
fn wait_or_kill(child: &mut Child, grace: Duration) -> Option<ExitStatus> {
    wait_within(child, grace).or_else(|| {
        let _ = child.kill();
        child.wait().ok()
    })
}

/// Whether a child that ended with `status` stopped cleanly on the
/// supervisor's request: success (it had finished, or the controller's end
/// of the run ended the plant) or the exit code of a clean stop on a signal.
fn stopped_cleanly(status: Option<ExitStatus>) -> bool {
    status.is_some_and(|s| {
        s.success()
            || s.code().is_some_and(|c| {
                [StopSignal::Sigint, StopSignal::Sigterm]
                    .iter()
                    .any(|sig| i32::from(sig.exit_code()) == c)
            })
    })
}

/// Runs `scenario` (loaded and checked by the caller) as two processes
/// (plant and controller) over iceoryx2, supervising both: their stderr is
/// forwarded but for their error lines, which the supervisor's one line
/// quotes. A child that fails is reported with its line, and its peer is
/// asked to stop (SIGTERM) if it has not ended within
/// [`PEER_FAILED_PATIENCE`]; SIGINT/SIGTERM is forwarded to the controller
/// (which writes its partial results) and then to the plant, and the
/// supervisor exits 130/143 once both stopped.
///
/// # Errors
/// A child could not start; either ended with a failure
/// ([`RunError::Supervised`]: exit 2 if a child refused its input, 130/143
/// if one was stopped by a signal from elsewhere, else 1; the controller
/// still wrote its partial results); a signal stopped the run
/// ([`RunError::Signalled`]: exit 130/143).
pub fn run_both(
    scenario: &str,
    controller: Option<&str>,
    out: &Destination,
) -> Result<(), RunError> {
    crate::run_dir::check(out)?;
    let exe = std::env::current_exe()
        .map_err(|e| RunError::Loop(format!("cannot find the shearcut executable: {e}")))?;
    let run_id = new_run_id(scenario);
    let watch = TerminationWatch::new();
    let command = |role: &str| {
        let mut c = Command::new(&exe);
        c.args([role, "--scenario", scenario, "--run-id", &run_id]);
        if let Some(name) = controller {
            c.args(["--controller", name]);
        }
        if role == "controller"
            && let Some(dir) = &out.out
        {
            c.arg("--out").arg(dir);
            if out.overwrite {
                c.arg("--overwrite");
            }
        }
        c
    };
    let mut plant = Supervised::spawn("plant", &mut command("plant"))?;
    let mut ctl = match Supervised::spawn("controller", &mut command("controller")) {
        Ok(c) => c,
        Err(e) => {
            terminate(&plant.child);
            wait_or_kill(&mut plant.child, PLANT_GRACE);
            return Err(e);
        }
    };
    tracing::info!(
        "run {run_id}: plant pid {}, controller pid {}",
        plant.child.id(),
        ctl.child.id()
    );
    let mut stopped_by = None;
    let (plant_end, ctl_end) = loop {
        if let Some(sig) = watch.requested_within(Duration::from_millis(5)) {
            let _ = writeln!(
                std::io::stderr(),
                "run {run_id}: termination requested ({sig}), stopping controller and plant"
            );
            stopped_by = Some(sig);
            // The controller first, and the plant once it has gone: the
            // controller then stops on its own signal (and writes its partial
            // results saying so) instead of finding the plant gone first.
            let c = stop(&mut ctl.child, sig, CONTROLLER_GRACE);
            let c = ctl.ended(c, true);
            let p = stop(&mut plant.child, sig, PLANT_GRACE);
            break (plant.ended(p, true), c);
        }
        // After a successful run the plant has acknowledged its end and
        // leaves by itself; a plant that ended well leaves the controller
        // writing its results.
        if let Ok(Some(c)) = ctl.child.try_wait() {
            let c = ctl.ended(Some(c), false);
            break (plant.after_peer(&c, PLANT_GRACE), c);
        }
        if let Ok(Some(p)) = plant.child.try_wait() {
            let p = plant.ended(Some(p), false);
            let c = ctl.after_peer(&p, CONTROLLER_GRACE);
            break (p, c);
        }
    };
    if let Some(signal) = stopped_by
        && ctl_end.is_fine()
        && plant_end.is_fine()
    {
        let said = ctl_end
            .error
            .as_deref()
            .map_or(String::new(), |e| format!(": the controller said: {e}"));
        return Err(RunError::Signalled {
            signal,
            message: format!(
                "run {run_id}: stopped by {signal}; plant and controller stopped cleanly{said}"
            ),
        });
    }
    let failed: Vec<&ChildEnd> = [&ctl_end, &plant_end]
        .into_iter()
        .filter(|c| !c.is_fine())
        .collect();
    if failed.is_empty() {
        return Ok(());
    }
    Err(RunError::Supervised {
        code: failure_code(&failed),
        message: format!(
            "run {run_id} failed: {}",
            failed
                .iter()
                .map(|c| c.failure())
                .collect::<Vec<_>>()
                .join("; ")
        ),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::os::unix::process::ExitStatusExt;

    fn exited(role: &'static str, code: i32, asked: bool) -> ChildEnd {
        ChildEnd {
            role,
            pid: 1,
            status: Some(ExitStatus::from_raw(code << 8)),
            asked,
            error: Some(format!("{role} said {code}")),
        }
    }

    #[test]
    fn a_childs_bad_input_is_exit_2_and_a_signal_from_elsewhere_its_code() {
        let bad = exited("controller", 2, false);
        let lost = exited("plant", 1, false);
        assert_eq!(failure_code(&[&bad, &lost]), 2);
        assert_eq!(failure_code(&[&lost, &bad]), 2);
        assert_eq!(failure_code(&[&lost]), 1);
        let interrupted = exited("plant", 130, false);
        assert_eq!(failure_code(&[&lost, &interrupted]), 130);
        assert!(!interrupted.is_fine());
        // A clean stop the supervisor asked for is no failure.
        assert!(exited("plant", 143, true).is_fine());
        assert!(!exited("plant", 1, true).is_fine());
        assert_eq!(
            bad.failure(),
            "the controller process (pid 1) exited with code 2: controller said 2"
        );
    }
}
