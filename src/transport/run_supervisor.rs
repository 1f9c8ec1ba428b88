//! `shearcut run --transport iceoryx2`: spawns the plant and controller
//! processes for one run, supervises them and reports how they ended.

use std::path::Path;
use std::process::{Child, Command, ExitStatus};
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

fn describe(role: &str, child: &Child, status: ExitStatus) -> String {
    use std::os::unix::process::ExitStatusExt;
    match (status.code(), status.signal()) {
        (Some(c), _) => format!(
            "the {role} process (pid {}) exited with code {c}",
            child.id()
        ),
        (None, Some(s)) => format!("the {role} process (pid {}) died by signal {s}", child.id()),
        _ => format!("the {role} process (pid {}) ended: {status}", child.id()),
    }
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
/// termination check consumes it): a controller under load once ran on for
/// the whole 10 s grace after a single SIGTERM and was killed. A repeated
/// signal gets through.
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

/// Runs `scenario` as two processes (plant and controller) over iceoryx2,
/// supervising both: a child that dies is reported; SIGINT/SIGTERM is
/// forwarded to the controller (which writes its partial results) and then
/// to the plant, and the supervisor exits 130/143 once both stopped.
///
/// # Errors
/// A child could not start, or either ended with a failure (its message is
/// on stderr; the controller still wrote the partial results); a signal
/// stopped the run ([`RunError::Signalled`]: exit 130/143).
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
    let spawn = |role: &str| {
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
        c.spawn()
            .map_err(|e| RunError::Loop(format!("cannot start the {role} process: {e}")))
    };
    let mut plant = spawn("plant")?;
    let mut ctl = match spawn("controller") {
        Ok(c) => c,
        Err(e) => {
            terminate(&plant);
            wait_or_kill(&mut plant, PLANT_GRACE);
            return Err(e);
        }
    };
    eprintln!(
        "run {run_id}: plant pid {}, controller pid {}",
        plant.id(),
        ctl.id()
    );
    let mut stopped_by = None;
    let (plant_status, ctl_status) = loop {
        if let Some(sig) = watch.requested_within(Duration::from_millis(5)) {
            eprintln!(
                "run {run_id}: termination requested ({sig:?}), stopping controller and plant"
            );
            stopped_by = Some(sig);
            // The controller first, and the plant once it has gone: the
            // controller then stops on its own signal (and writes its partial
            // results saying so) instead of finding the plant gone first.
            let c = stop(&mut ctl, sig, CONTROLLER_GRACE);
            let p = stop(&mut plant, sig, PLANT_GRACE);
            break (p, c);
        }
        if let Ok(Some(c)) = ctl.try_wait() {
            let p = wait_or_kill(&mut plant, PLANT_GRACE);
            break (p, Some(c));
        }
        if let Ok(Some(p)) = plant.try_wait() {
            if !p.success() {
                eprintln!("run {run_id}: {}", describe("plant", &plant, p));
            }
            let c = wait_or_kill(&mut ctl, CONTROLLER_GRACE);
            break (Some(p), c);
        }
    };
    if let Some(signal) = stopped_by
        && stopped_cleanly(ctl_status)
        && stopped_cleanly(plant_status)
    {
        return Err(RunError::Signalled {
            signal,
            message: format!(
                "run {run_id}: stopped by {signal:?}; plant and controller stopped cleanly (the controller's partial results are where it said)"
            ),
        });
    }
    let mut failures = Vec::new();
    match ctl_status {
        Some(s) if s.success() => {}
        Some(s) => failures.push(describe("controller", &ctl, s)),
        None => failures.push("the controller process could not be reaped".to_string()),
    }
    match plant_status {
        Some(s) if s.success() => {}
        Some(s) => failures.push(describe("plant", &plant, s)),
        None => failures.push("the plant process could not be reaped".to_string()),
    }
    if failures.is_empty() {
        Ok(())
    } else {
        Err(RunError::Loop(format!(
            "run {run_id} failed: {}",
            failures.join("; ")
        )))
    }
}
