//! A private directory and iceoryx2 prefix for one test of the `shearcut`
//! binary's processes, with a watchdog on every child (included with
//! `#[path]`).

use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output, Stdio};
use std::sync::atomic::{AtomicU32, Ordering};
use std::time::{Duration, Instant};

/// Longest any child may run.
pub const WATCHDOG: Duration = Duration::from_secs(120);

static NEXT: AtomicU32 = AtomicU32::new(0);

/// A test's private directory and iceoryx2 prefix, cleaned on drop.
pub struct Sandbox {
    /// The directory (scenarios and outputs).
    pub dir: PathBuf,
    prefix: String,
}

impl Sandbox {
    /// A new sandbox; `tag` names its directory.
    pub fn new(tag: &str) -> Self {
        let n = NEXT.fetch_add(1, Ordering::Relaxed);
        let prefix = format!("sct{}x{n}_", std::process::id());
        let dir =
            std::env::temp_dir().join(format!("shearcut-ipc-{tag}-{}-{n}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        Self { dir, prefix }
    }

    /// The iceoryx2 prefix of this sandbox's processes.
    #[allow(dead_code)] // Not every test file that includes the sandbox asks.
    pub fn prefix(&self) -> &str {
        &self.prefix
    }

    /// The small potato (tests/closed_loop.rs) cut `depth` deep, with
    /// `extra` TOML appended, written as `<name>.toml`; its path.
    pub fn scenario(&self, name: &str, depth: f64, extra: &str) -> String {
        let text = include_str!("../../config/scenarios/fig7-potato.toml").to_string()
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

    /// Starts `shearcut args…` under this sandbox's prefix.
    pub fn spawn(&self, args: &[&str]) -> Child {
        self.command(args).spawn().expect("shearcut starts")
    }

    /// Starts `shearcut run <scenario> --controller slice:0.75 --transport
    /// <transport> --out <out>`.
    pub fn spawn_run(&self, scenario: &str, transport: &str, out: &Path) -> Child {
        self.spawn(&[
            "run",
            scenario,
            "--controller",
            "slice:0.75",
            "--transport",
            transport,
            "--out",
            out.to_str().unwrap(),
        ])
    }

    /// Starts the plant of run `id` (`--controller slice:0.75`).
    pub fn spawn_plant(&self, scenario: &str, id: &str) -> Child {
        self.spawn(&[
            "plant",
            "--scenario",
            scenario,
            "--run-id",
            id,
            "--controller",
            "slice:0.75",
        ])
    }

    /// Starts the controller of run `id` (`--controller slice:0.75`),
    /// writing to `out`.
    pub fn spawn_controller(&self, scenario: &str, id: &str, out: &Path) -> Child {
        self.spawn(&[
            "controller",
            "--scenario",
            scenario,
            "--run-id",
            id,
            "--controller",
            "slice:0.75",
            "--out",
            out.to_str().unwrap(),
        ])
    }

    /// Starts plant and controller of run `id` as separate processes.
    pub fn spawn_pair(&self, scenario: &str, id: &str, out: &Path) -> (Child, Child) {
        (
            self.spawn_plant(scenario, id),
            self.spawn_controller(scenario, id, out),
        )
    }

    /// A short lockstep run under run id `id` completes on both sides: what
    /// an earlier run (killed or not) left does not block it.
    pub fn assert_next_run_starts_cleanly(&self, id: &str) {
        let s = self.scenario("short", 0.003, "");
        let (p, c) = self.spawn_pair(&s, id, &self.dir.join(format!("again-{id}")));
        let (p, c) = (watchdog(p, WATCHDOG), watchdog(c, WATCHDOG));
        assert!(c.status.success(), "controller: {}", stderr(&c));
        assert!(p.status.success(), "plant: {}", stderr(&p));
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

/// Sends `signal` (a name `kill` knows: `INT`, `TERM`, `STOP`, `CONT`)
/// to `child`.
pub fn send_signal(child: &Child, signal: &str) {
    let sent = Command::new("kill")
        .args([&format!("-{signal}"), &child.id().to_string()])
        .status()
        .unwrap();
    assert!(sent.success(), "kill -{signal}");
}

/// Waits for `child` up to `limit`; kills it and fails the test after that.
#[allow(clippy::disallowed_methods)] // A watchdog measures wall time.
pub fn watchdog(mut child: Child, limit: Duration) -> Output {
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

/// Fails with the child's stderr if it has ended.
pub fn assert_running(child: &mut Child, role: &str) {
    if child.try_wait().unwrap().is_some() {
        use std::io::Read;
        let mut err = String::new();
        if let Some(e) = child.stderr.as_mut() {
            e.read_to_string(&mut err).ok();
        }
        panic!("the {role} ended early: {err}");
    }
}

/// The child's stderr as text.
pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// The file's text (fails naming the file).
pub fn read(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// Parsed JSON of the file.
pub fn read_json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&read(path)).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}
