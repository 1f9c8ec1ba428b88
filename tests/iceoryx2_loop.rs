//! The loop over iceoryx2, end to end through the `shearcut` binary: plant
//! and controller processes, bit-identity with the in-process loop, a lost
//! plant, a lost controller, parallel runs and restarts after SIGKILL. Every
//! child runs under a watchdog: a hang fails the test instead of blocking.

use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output, Stdio};
use std::sync::atomic::{AtomicU32, Ordering};
use std::time::{Duration, Instant};

/// Longest any child may run.
const WATCHDOG: Duration = Duration::from_secs(120);

static NEXT: AtomicU32 = AtomicU32::new(0);

/// A test's private directory and iceoryx2 prefix, cleaned on drop.
struct Sandbox {
    dir: PathBuf,
    prefix: String,
}

impl Sandbox {
    fn new(tag: &str) -> Self {
        let n = NEXT.fetch_add(1, Ordering::Relaxed);
        let prefix = format!("sct{}x{n}_", std::process::id());
        let dir =
            std::env::temp_dir().join(format!("shearcut-ipc-{tag}-{}-{n}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        Self { dir, prefix }
    }

    /// The small potato (tests/closed_loop.rs) with `extra` TOML appended.
    fn scenario(&self, name: &str, depth: f64, extra: &str) -> String {
        let text = include_str!("../config/scenarios/fig7-potato.toml").to_string()
            + "\n[plant]\nsegments = 2\n\n[section]\nrow_spacing = 0.0005\n"
            + extra;
        let path = self.dir.join(format!("{name}.toml"));
        std::fs::write(
            &path,
            text.replace("depth = 0.02", &format!("depth = {depth}")),
        )
        .unwrap();
        path.to_str().unwrap().to_string()
    }

    fn command(&self, args: &[&str]) -> Command {
        let mut c = Command::new(env!("CARGO_BIN_EXE_shearcut"));
        c.args(args)
            .env("RUST_LOG", "error")
            .env("SHEARCUT_IPC_PREFIX", &self.prefix)
            .stdout(Stdio::piped())
            .stderr(Stdio::piped());
        c
    }

    fn spawn(&self, args: &[&str]) -> Child {
        self.command(args).spawn().expect("shearcut starts")
    }

    fn run(&self, args: &[&str]) -> Output {
        watchdog(self.spawn(args), WATCHDOG)
    }
}

impl Drop for Sandbox {
    fn drop(&mut self) {
        std::fs::remove_dir_all(&self.dir).ok();
        remove_prefixed(Path::new("/dev/shm"), &self.prefix);
        remove_prefixed(Path::new("/tmp/iceoryx2"), &self.prefix);
    }
}

/// Removes every file or directory under `dir` whose name starts with `prefix`.
fn remove_prefixed(dir: &Path, prefix: &str) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for e in entries.flatten() {
        let path = e.path();
        let named = e.file_name().to_string_lossy().starts_with(prefix);
        if path.is_dir() {
            if named {
                std::fs::remove_dir_all(&path).ok();
            } else {
                remove_prefixed(&path, prefix);
            }
        } else if named {
            std::fs::remove_file(&path).ok();
        }
    }
}

/// Waits for `child` up to `limit`; kills it and fails the test after that.
#[allow(clippy::disallowed_methods)] // A watchdog measures wall time.
fn watchdog(mut child: Child, limit: Duration) -> Output {
    let until = Instant::now() + limit;
    loop {
        if child.try_wait().unwrap().is_some() {
            return child.wait_with_output().unwrap();
        }
        if Instant::now() > until {
            child.kill().ok();
            let o = child.wait_with_output().unwrap();
            panic!(
                "watchdog: the child hung for {limit:?}; stderr: {}",
                String::from_utf8_lossy(&o.stderr)
            );
        }
        std::thread::sleep(Duration::from_millis(10));
    }
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn read(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

#[test]
fn lockstep_over_iceoryx2_is_bit_identical_to_the_in_process_loop() {
    let sb = Sandbox::new("identical");
    let s = sb.scenario("small", 0.006, "");
    let inproc = sb.dir.join("inproc");
    let ipc = sb.dir.join("ipc");
    for (dir, transport) in [(&inproc, "inproc"), (&ipc, "iceoryx2")] {
        let o = sb.run(&[
            "run",
            &s,
            "--controller",
            "slice:0.75",
            "--transport",
            transport,
            "--out",
            dir.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{transport}: {}", stderr(&o));
    }
    for f in ["timeseries.csv", "controller.csv"] {
        let (a, b) = (read(&inproc.join(f)), read(&ipc.join(f)));
        assert!(
            a.lines().count() > 100,
            "{f} has {} lines",
            a.lines().count()
        );
        assert!(a == b, "{f} differs between inproc and iceoryx2");
    }
    let summary: serde_json::Value =
        serde_json::from_str(&read(&ipc.join("summary.json"))).unwrap();
    assert_eq!(summary["end"], "completed");
    assert_eq!(summary["transport"], "iceoryx2");
    let stats: serde_json::Value =
        serde_json::from_str(&read(&ipc.join("loop_stats.json"))).unwrap();
    assert_eq!(stats["missed_commands"], 0);
    assert!(stats["round_trip"]["median_us"].as_f64().unwrap() > 0.0);
}

/// Starts plant and controller of run `id` separately (realtime clock).
fn start_pair(sb: &Sandbox, s: &str, id: &str, out: &Path) -> (Child, Child) {
    let plant = sb.spawn(&[
        "plant",
        "--scenario",
        s,
        "--run-id",
        id,
        "--controller",
        "slice:0.75",
    ]);
    let controller = sb.spawn(&[
        "controller",
        "--scenario",
        s,
        "--run-id",
        id,
        "--controller",
        "slice:0.75",
        "--out",
        out.to_str().unwrap(),
    ]);
    (plant, controller)
}

/// Realtime at `rate_hz`, the knife at 2 mm/s: the 2 cm cut takes about
/// 10 s of wall time, time enough to kill a side mid-run.
fn realtime_extra(rate_hz: f64, limit: u32) -> String {
    format!(
        "\n[loop]\nclock = \"realtime\"\nrate_hz = {rate_hz}\nmissed_command_limit = {limit}\n\n[controller]\nspeed = 0.002\n"
    )
}

/// Fails with the child's stderr if it has ended.
fn assert_running(child: &mut Child, role: &str) {
    if child.try_wait().unwrap().is_some() {
        use std::io::Read;
        let mut err = String::new();
        if let Some(e) = child.stderr.as_mut() {
            e.read_to_string(&mut err).ok();
        }
        panic!("the {role} ended early: {err}");
    }
}

#[test]
fn killing_the_plant_stops_the_controller_with_a_named_error_and_readable_results() {
    let sb = Sandbox::new("killplant");
    // A high limit: a loaded machine's stalls must not brake the plant first.
    let s = sb.scenario("long", 0.02, &realtime_extra(1000.0, 100_000));
    let out = sb.dir.join("out");
    let (mut plant, controller) = start_pair(&sb, &s, "kp", &out);
    std::thread::sleep(Duration::from_millis(1500));
    assert_running(&mut plant, "plant");
    plant.kill().unwrap(); // SIGKILL: no cleanup.
    plant.wait().unwrap();
    let o = watchdog(controller, Duration::from_secs(30));
    let err = stderr(&o);
    assert!(!o.status.success(), "the controller succeeded: {err}");
    assert!(
        err.contains("plant/kp"),
        "the message names the plant: {err}"
    );
    assert!(err.contains("aborted"), "{err}");
    // Partial results, readable.
    let rows = read(&out.join("controller.csv")).lines().count();
    assert!(rows > 100, "controller.csv has {rows} lines");
    let summary: serde_json::Value =
        serde_json::from_str(&read(&out.join("summary.json"))).unwrap();
    let end = summary["end"]["failed"].as_str().unwrap();
    assert!(end.contains("plant/kp"), "{end}");
    // The next run under the same run id and prefix starts cleanly.
    let s2 = sb.scenario("short", 0.003, "");
    let (p, c) = start_pair(&sb, &s2, "kp", &sb.dir.join("again"));
    let (p, c) = (watchdog(p, WATCHDOG), watchdog(c, WATCHDOG));
    assert!(c.status.success(), "{}", stderr(&c));
    assert!(p.status.success(), "{}", stderr(&p));
}

#[test]
fn killing_the_controller_brakes_the_plant_after_the_missed_command_limit() {
    let sb = Sandbox::new("killctl");
    // 100 Hz: 20 missed commands are 200 ms, longer than a loaded
    // machine's stalls (at 1 kHz those alone could brake the plant).
    let s = sb.scenario("long", 0.02, &realtime_extra(100.0, 20));
    let out = sb.dir.join("out");
    let (plant, mut controller) = start_pair(&sb, &s, "kc", &out);
    std::thread::sleep(Duration::from_millis(1500));
    assert_running(&mut controller, "controller");
    controller.kill().unwrap();
    controller.wait().unwrap();
    let o = watchdog(plant, Duration::from_secs(30));
    let err = stderr(&o);
    assert!(!o.status.success(), "{err}");
    assert!(
        err.contains("plant/kc: braked after 20 consecutive missed commands"),
        "{err}"
    );
    // The next run under the same run id and prefix starts cleanly.
    let s2 = sb.scenario("short", 0.003, "");
    let (p, c) = start_pair(&sb, &s2, "kc", &sb.dir.join("again"));
    let (p, c) = (watchdog(p, WATCHDOG), watchdog(c, WATCHDOG));
    assert!(c.status.success(), "{}", stderr(&c));
    assert!(p.status.success(), "{}", stderr(&p));
}

#[test]
fn two_runs_in_parallel_do_not_interfere() {
    let sb = Sandbox::new("parallel");
    let s = sb.scenario("small", 0.004, "");
    let dirs = [sb.dir.join("a"), sb.dir.join("b")];
    let children: Vec<Child> = dirs
        .iter()
        .map(|d| {
            sb.spawn(&[
                "run",
                &s,
                "--controller",
                "slice:0.75",
                "--transport",
                "iceoryx2",
                "--out",
                d.to_str().unwrap(),
            ])
        })
        .collect();
    for o in children.into_iter().map(|c| watchdog(c, WATCHDOG)) {
        assert!(o.status.success(), "{}", stderr(&o));
    }
    let a = read(&dirs[0].join("timeseries.csv"));
    assert!(a.lines().count() > 50);
    assert!(a == read(&dirs[1].join("timeseries.csv")));
}

#[test]
fn a_run_killed_with_sigkill_leaves_nothing_that_blocks_the_next() {
    let sb = Sandbox::new("sigkill");
    let s = sb.scenario("long", 0.02, &realtime_extra(1000.0, 100_000));
    let (mut p, mut c) = start_pair(&sb, &s, "sk", &sb.dir.join("killed"));
    std::thread::sleep(Duration::from_millis(1000));
    p.kill().unwrap();
    c.kill().unwrap();
    p.wait().unwrap();
    c.wait().unwrap();
    let s2 = sb.scenario("short", 0.003, "");
    let (p, c) = start_pair(&sb, &s2, "sk", &sb.dir.join("again"));
    let (p, c) = (watchdog(p, WATCHDOG), watchdog(c, WATCHDOG));
    assert!(c.status.success(), "{}", stderr(&c));
    assert!(p.status.success(), "{}", stderr(&p));
}

#[test]
fn sigterm_stops_plant_and_controller_cleanly_with_partial_results() {
    let sb = Sandbox::new("sigterm");
    let s = sb.scenario("long", 0.02, &realtime_extra(1000.0, 100_000));
    let out = sb.dir.join("out");
    let mut run = sb.spawn(&[
        "run",
        &s,
        "--controller",
        "slice:0.75",
        "--transport",
        "iceoryx2",
        "--out",
        out.to_str().unwrap(),
    ]);
    std::thread::sleep(Duration::from_millis(1500));
    assert_running(&mut run, "run");
    let sent = Command::new("kill")
        .args(["-TERM", &run.id().to_string()])
        .status()
        .unwrap();
    assert!(sent.success());
    let o = watchdog(run, Duration::from_secs(30));
    let err = stderr(&o);
    assert!(!o.status.success(), "{err}");
    assert!(err.contains("termination requested"), "{err}");
    // Both children stopped by themselves (none needed a SIGKILL).
    assert!(!err.contains("signal 9"), "{err}");
    let summary: serde_json::Value =
        serde_json::from_str(&read(&out.join("summary.json"))).unwrap();
    let end = summary["end"]["failed"].as_str().unwrap();
    assert!(end.contains("SIGINT/SIGTERM"), "{end}");
    assert!(read(&out.join("controller.csv")).lines().count() > 100);
}
