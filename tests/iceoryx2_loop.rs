//! The loop over iceoryx2, end to end through the `shearcut` binary: plant
//! and controller processes, bit-identity with the in-process loop, a lost
//! plant, a lost controller, parallel runs, restarts after SIGKILL, SIGTERM
//! and the realtime clock's missed-command count. Every child runs under a
//! watchdog: a hang fails the test instead of blocking.

#[path = "support/sandbox.rs"]
mod sandbox;

use std::process::Child;
use std::time::Duration;

use sandbox::{Sandbox, WATCHDOG, assert_running, read, read_json, send_signal, stderr, watchdog};

#[test]
fn lockstep_over_iceoryx2_is_bit_identical_to_the_in_process_loop() {
    let sb = Sandbox::new("identical");
    let s = sb.scenario("small", 0.006, "");
    let inproc = sb.dir.join("inproc");
    let ipc = sb.dir.join("ipc");
    for (dir, transport) in [(&inproc, "inproc"), (&ipc, "iceoryx2")] {
        let o = watchdog(sb.spawn_run(&s, transport, dir), WATCHDOG);
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
    let summary = read_json(&ipc.join("summary.json"));
    assert_eq!(summary["end"], "completed");
    assert_eq!(summary["transport"], "iceoryx2");
    let stats = read_json(&ipc.join("loop_stats.json"));
    assert_eq!(stats["missed_commands"], 0);
    assert!(stats["round_trip"]["median_us"].as_f64().unwrap() > 0.0);
}

/// Realtime at `rate_hz`, the knife at 2 mm/s: the 2 cm cut takes about
/// 10 s of wall time, time enough to kill a side mid-run.
fn realtime_extra(rate_hz: f64, limit: u32) -> String {
    format!(
        "\n[loop]\nclock = \"realtime\"\nrate_hz = {rate_hz}\nmissed_command_limit = {limit}\n\n[controller]\nspeed = 0.002\n"
    )
}

#[test]
fn killing_the_plant_stops_the_controller_with_a_named_error_and_readable_results() {
    let sb = Sandbox::new("killplant");
    // A high limit: a loaded machine's stalls must not brake the plant first.
    let s = sb.scenario("long", 0.02, &realtime_extra(1000.0, 1000));
    let out = sb.dir.join("out");
    let (mut plant, controller) = sb.spawn_pair(&s, "kp", &out);
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
    assert!(err.contains("the loop failed"), "{err}");
    // Partial results, readable.
    let rows = read(&out.join("controller.csv")).lines().count();
    assert!(rows > 100, "controller.csv has {rows} lines");
    let summary = read_json(&out.join("summary.json"));
    let end = summary["end"]["failed"].as_str().unwrap();
    assert!(end.contains("plant/kp"), "{end}");
    sb.assert_next_run_starts_cleanly("kp");
}

#[test]
fn killing_the_controller_brakes_the_plant_after_the_missed_command_limit_and_names_the_cause() {
    let sb = Sandbox::new("killctl");
    // 100 Hz: 20 missed commands are 200 ms, longer than a loaded
    // machine's stalls (at 1 kHz those alone could brake the plant).
    let s = sb.scenario("long", 0.02, &realtime_extra(100.0, 20));
    let out = sb.dir.join("out");
    let (plant, mut controller) = sb.spawn_pair(&s, "kc", &out);
    std::thread::sleep(Duration::from_millis(1500));
    assert_running(&mut controller, "controller");
    controller.kill().unwrap();
    controller.wait().unwrap();
    let o = watchdog(plant, Duration::from_secs(30));
    let err = stderr(&o);
    assert!(!o.status.success(), "{err}");
    // Braked at the limit, then one look at the controller's node names
    // the cause.
    assert!(
        err.contains("plant/kc: lost the controller: the controller 'controller/kc' died after"),
        "{err}"
    );
    assert!(
        err.contains("; braked; ") && err.contains("missed commands (longest run 20"),
        "{err}"
    );
    sb.assert_next_run_starts_cleanly("kc");
}

#[test]
fn two_runs_in_parallel_do_not_interfere() {
    let sb = Sandbox::new("parallel");
    let s = sb.scenario("small", 0.004, "");
    let dirs = [sb.dir.join("a"), sb.dir.join("b")];
    let children: Vec<Child> = dirs
        .iter()
        .map(|d| sb.spawn_run(&s, "iceoryx2", d))
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
    let s = sb.scenario("long", 0.02, &realtime_extra(1000.0, 1000));
    let (mut p, mut c) = sb.spawn_pair(&s, "sk", &sb.dir.join("killed"));
    std::thread::sleep(Duration::from_millis(1000));
    p.kill().unwrap();
    c.kill().unwrap();
    p.wait().unwrap();
    c.wait().unwrap();
    sb.assert_next_run_starts_cleanly("sk");
}

#[test]
fn sigterm_stops_plant_and_controller_cleanly_with_partial_results() {
    let sb = Sandbox::new("sigterm");
    let s = sb.scenario("long", 0.02, &realtime_extra(1000.0, 1000));
    let out = sb.dir.join("out");
    let mut run = sb.spawn_run(&s, "iceoryx2", &out);
    std::thread::sleep(Duration::from_millis(1500));
    assert_running(&mut run, "run");
    send_signal(&run, "TERM");
    let o = watchdog(run, Duration::from_secs(30));
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(143), "{err}");
    assert!(err.contains("termination requested"), "{err}");
    // Both children stopped by themselves (none needed a SIGKILL).
    assert!(!err.contains("signal 9"), "{err}");
    let summary = read_json(&out.join("summary.json"));
    assert_eq!(summary["end"]["stopped"], "sigterm", "{summary}");
    assert!(read(&out.join("controller.csv")).lines().count() > 100);
}

/// The number written just before `label` in `text` ("…, 12 missed commands").
fn count_before(text: &str, label: &str) -> u64 {
    let head = &text[..text
        .find(label)
        .unwrap_or_else(|| panic!("no {label:?} in {text}"))];
    let digits: String = head
        .trim_end()
        .chars()
        .rev()
        .take_while(char::is_ascii_digit)
        .collect::<Vec<_>>()
        .into_iter()
        .rev()
        .collect();
    digits
        .parse()
        .unwrap_or_else(|_| panic!("no count before {label:?} in {text}"))
}

#[test]
fn realtime_loop_stats_report_the_plants_missed_commands() {
    let sb = Sandbox::new("realtime");
    // 1 kHz, a 3 mm cut at 2 mm/s (about 2 s of wall time); a limit no
    // loaded machine reaches, so the run completes whatever it misses.
    let s = sb.scenario("rt", 0.003, &realtime_extra(1000.0, 1000));
    let out = sb.dir.join("out");
    let o = watchdog(sb.spawn_run(&s, "iceoryx2", &out), WATCHDOG);
    let err = stderr(&o);
    assert!(o.status.success(), "{err}");
    let stats = read_json(&out.join("loop_stats.json"));
    assert_eq!(stats["clock"], "realtime", "{stats}");
    // The plant's own account (on the run's stderr): it steps every tick,
    // with a command or, missing one, with the last.
    let commands = count_before(&err, " commands answered");
    let steps = count_before(&err, " steps,");
    let missed = count_before(&err, " missed commands (longest run");
    assert_eq!(steps, commands + missed, "{err}");
    // loop_stats carries the plant's total, whatever this machine's load
    // made it.
    assert_eq!(stats["missed_commands"].as_u64(), Some(missed), "{stats}");
    let summary = read_json(&out.join("summary.json"));
    assert_eq!(summary["end"], "completed");
}
