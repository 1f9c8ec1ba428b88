//! `shearcut compare` as a user meets it: its runs go through the sweep
//! executor, so its results are the same whatever `--jobs`; a bad `--jobs`
//! exits 2 with one line; SIGINT/SIGTERM stop it with the rows of the runs
//! finished written and exit 130/143.

#[path = "support/binary_run.rs"]
mod binary_run;

use std::io::BufRead;
use std::path::Path;
use std::process::{Command, Stdio};

use binary_run::{assert_success, scratch, shearcut, signal_and_wait, stderr};

/// `loop-potato-cuboid-short-stroke` 6 mm deep with 1.2 mm of blade (the
/// same ratio cap, 0.2), on a coarse plant: a compare on two replicas runs
/// in about a second.
fn small_short_stroke(dir: &Path) -> String {
    let text = include_str!("../config/scenarios/loop-potato-cuboid-short-stroke.toml")
        .replace(
            "name = \"loop-potato-cuboid-short-stroke\"",
            "name = \"small-short-stroke\"",
        )
        .replace("depth = 0.02", "depth = 0.006")
        .replace("blade_budget = 0.004", "blade_budget = 0.0012")
        .replace("segments = 20", "segments = 4")
        + "\n[section]\nrow_spacing = 0.0005\n";
    let path = dir.join("small.toml");
    std::fs::write(&path, text).unwrap();
    path.to_str().unwrap().to_string()
}

/// A file of a compare's results with the measured column (the planning
/// p99, `plan_p99_us`: wall time) blanked, in the CSV, JSON and Markdown
/// tables.
fn without_timing(dir: &Path, name: &str) -> String {
    let text = std::fs::read_to_string(dir.join(name)).unwrap();
    match name {
        "comparison.json" => {
            let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
            for row in v["rows"].as_array_mut().unwrap() {
                row["plan_p99_us"] = serde_json::Value::Null;
            }
            v.to_string()
        }
        // The last column of the CSV and of the Markdown table.
        _ => text
            .lines()
            .map(|l| {
                let last = if name.ends_with(".csv") {
                    l.rsplit_once(',')
                } else {
                    l.strip_suffix(" |").and_then(|t| t.rsplit_once('|'))
                };
                last.map_or(l, |(head, _)| head)
            })
            .collect::<Vec<_>>()
            .join("\n"),
    }
}

#[test]
fn compare_gives_the_same_results_whatever_the_jobs() {
    let dir = scratch("compare-jobs");
    let scenario = small_short_stroke(&dir);
    let out = |jobs: &str| {
        let at = dir.join(format!("jobs-{jobs}"));
        let o = shearcut(&[
            "compare",
            &scenario,
            "--replicas",
            "2",
            "--jobs",
            jobs,
            "--out",
            at.to_str().unwrap(),
        ]);
        assert_success(&o);
        at
    };
    let (one, two) = (out("1"), out("2"));
    for name in ["comparison.csv", "comparison.json", "comparison.md"] {
        assert_eq!(
            without_timing(&one, name),
            without_timing(&two, name),
            "{name}"
        );
    }
    for name in ["comparison.svg", "comparison.png", "scenario.toml"] {
        let read = |d: &Path| std::fs::read(d.join(name)).unwrap();
        assert!(read(&one) == read(&two), "{name} differs");
    }
    // The table: the MPC and the best constant on both replicas, paired;
    // pressing and the force loop on the nominal one; the search's other
    // ratios after them.
    let json = std::fs::read_to_string(one.join("comparison.json")).unwrap();
    let v: serde_json::Value = serde_json::from_str(&json).unwrap();
    let rows = v["rows"].as_array().unwrap();
    let roles: Vec<&str> = rows.iter().map(|r| r["role"].as_str().unwrap()).collect();
    assert_eq!(&roles[..4], ["mpc", "press", "best constant", "force"]);
    assert!(roles[4..].iter().all(|&r| r == "search"), "{roles:?}");
    let replicas: Vec<u64> = rows[..4]
        .iter()
        .map(|r| r["replicas"].as_u64().unwrap())
        .collect();
    assert_eq!(replicas, [2, 1, 2, 1]);
    assert_eq!(v["mpc_vs_best_constant"]["replicas"], 2, "{json}");
    assert!(v.get("stopped").is_none(), "{json}");
    std::fs::remove_dir_all(dir).ok();
}

#[test]
fn a_bad_jobs_count_exits_2_with_one_line() {
    for bad in ["0", "x"] {
        let o = shearcut(&["compare", "loop-potato-cuboid", "--jobs", bad]);
        assert_eq!(o.status.code(), Some(2));
        let e = stderr(&o);
        assert_eq!(e.lines().count(), 1, "{e}");
        assert!(e.contains("--jobs"), "{e}");
    }
}

/// A signal while a run is in flight (after the first of the coarse grid's
/// runs, one at a time, on the full short-stroke cuboid: each run takes
/// seconds) stops the comparison at that run's next tick: one line on
/// stderr, exit 130/143, and the rows of the runs finished written with
/// the comparison marked stopped.
#[test]
fn sigint_and_sigterm_stop_compare_with_the_finished_rows_written() {
    let dir = scratch("compare-signals");
    for (signal, code, name) in [("INT", 130, "sigint"), ("TERM", 143, "sigterm")] {
        let out = dir.join(name);
        let mut child = Command::new(env!("CARGO_BIN_EXE_shearcut"))
            .args([
                "compare",
                "loop-potato-cuboid-short-stroke",
                "--replicas",
                "1",
            ])
            .args(["--jobs", "1", "--out", out.to_str().unwrap()])
            .env("RUST_LOG", "error")
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        let mut stdout = std::io::BufReader::new(child.stdout.take().unwrap());
        let mut printed = Vec::new();
        while !printed.iter().any(|l: &String| l.starts_with("[1/")) {
            let mut line = String::new();
            assert!(stdout.read_line(&mut line).unwrap() > 0, "no run line");
            printed.push(line);
        }
        let (o, rest) = signal_and_wait(child, stdout, signal);
        printed.extend(rest.lines().map(str::to_string));
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(code), "{name}: {e}");
        assert_eq!(e.lines().count(), 1, "{e}");
        assert!(e.contains(&format!("stopped by SIG{signal}")), "{e}");
        // One row per run finished (each printed its line), none of the
        // run stopped mid-way; the comparison says it stopped.
        let json = std::fs::read_to_string(out.join("comparison.json")).unwrap();
        let v: serde_json::Value = serde_json::from_str(&json).unwrap();
        assert_eq!(v["stopped"], name, "{json}");
        let rows = v["rows"].as_array().unwrap();
        let finished = printed.iter().filter(|l| l.starts_with('[')).count();
        assert!(finished >= 1 && rows.len() == finished, "{json}");
        assert_eq!(rows[0]["controller"], "press", "{json}");
        assert!(rows.iter().all(|r| r["replicas"] == 1), "{json}");
        let table = std::fs::read_to_string(out.join("comparison.md")).unwrap();
        assert!(
            table.contains(&format!("stopped by SIG{signal}")),
            "{table}"
        );
        assert!(out.join("comparison.png").is_file());
    }
    std::fs::remove_dir_all(dir).ok();
}
