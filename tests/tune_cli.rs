//! `shearcut tune` as a user meets it: a small sweep run locally in
//! parallel is deterministic whatever the thread count, resumes where it
//! stopped (by a closed stdout or SIGINT/SIGTERM), shards and merges to the same table bit for bit (by flag and by
//! the Slurm and Kubernetes environment), and bad sweep files exit 2 with
//! one line.

#[path = "support/binary_run.rs"]
mod binary_run;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// A private directory for one test, removed on drop.
struct TempDir(PathBuf);

impl TempDir {
    fn new(tag: &str) -> Self {
        let dir = std::env::temp_dir().join(format!("shearcut-tune-{tag}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        Self(dir)
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// Fig. 7's potato cuboid, 6 mm deep, coarse (as tests/closed_loop.rs):
/// a closed-loop run takes a fraction of a second.
fn small_potato() -> String {
    include_str!("../config/scenarios/fig7-potato.toml")
        .replace("name = \"fig7-potato\"", "name = \"small-potato\"")
        .replace("depth = 0.02", "depth = 0.006")
        + "\n[plant]\nsegments = 2\n\n[section]\nrow_spacing = 0.0005\n"
}

/// Six runs: the MPC at two deformation weights and pressing, each on the
/// potato 10 % softer and 10 % stiffer.
const SWEEP: &str = r#"
scenarios = ["small-potato.toml"]

[variants]
youngs_modulus_scale = [0.9, 1.1]

[[controllers]]
kind = "mpc"
grid = { "mpc.deformation_weight" = [0.0, 100.0] }

[[controllers]]
kind = "press"
"#;

/// Writes the scenario and `sweep` into `dir`; the sweep's path.
fn write_sweep(dir: &Path, sweep: &str) -> PathBuf {
    std::fs::write(dir.join("small-potato.toml"), small_potato()).unwrap();
    let path = dir.join("sweep.toml");
    std::fs::write(&path, sweep).unwrap();
    path
}

fn tune(args: &[&str], env: &[(&str, &str)]) -> Output {
    let mut c = Command::new(env!("CARGO_BIN_EXE_shearcut"));
    c.arg("tune").args(args).env("RUST_LOG", "error");
    for k in [
        "SLURM_ARRAY_TASK_ID",
        "SLURM_ARRAY_TASK_MIN",
        "SLURM_ARRAY_TASK_COUNT",
        "JOB_COMPLETION_INDEX",
        "SHEARCUT_SHARDS",
    ] {
        c.env_remove(k);
    }
    for (k, v) in env {
        c.env(k, v);
    }
    c.output().expect("the shearcut binary runs")
}

fn ok(o: &Output) -> String {
    let out = String::from_utf8_lossy(&o.stdout).into_owned();
    assert!(
        o.status.success(),
        "{out}\n{}",
        String::from_utf8_lossy(&o.stderr)
    );
    out
}

fn read(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

#[test]
fn a_sweep_is_deterministic_resumable_and_analysed() {
    let t = TempDir::new("local");
    let sweep = write_sweep(&t.0, SWEEP);
    let (a, b) = (t.0.join("a"), t.0.join("b"));
    let out = ok(&tune(&[s(&sweep), "--jobs", "2", "--out", s(&a)], &[]));
    assert!(
        out.contains("6 runs (1 scenarios × 3 settings × 2 variants × 1 replicas)"),
        "{out}"
    );
    let results = read(&a.join("results.csv"));
    let lines: Vec<&str> = results.lines().collect();
    assert_eq!(lines.len(), 7, "a header and one row per run:\n{results}");
    assert!(lines[0].starts_with("job,id,scenario,setting,variant,replica,controller,"));
    for column in [
        "variant.youngs_modulus_scale",
        "controller.mpc.deformation_weight",
        "work_j",
        "max_deformation_m",
        "peak_force_vertical_n",
        "duration_s",
        "blade_path_m",
        "reversals",
        "limit_faults",
        "plan_fallbacks",
        "completed",
    ] {
        assert!(lines[0].split(',').any(|c| c == column), "{column}");
    }
    // Every run completed, and pressing the stiffer potato (variant 1)
    // took more force than the softer (variant 0): the variants reach the
    // plant.
    let rows: Vec<Vec<&str>> = lines[1..].iter().map(|l| l.split(',').collect()).collect();
    let col = |name: &str| lines[0].split(',').position(|c| c == name).unwrap();
    assert!(rows.iter().all(|r| r[col("completed")] == "true"));
    let force = |r: &Vec<&str>| r[col("peak_force_vertical_n")].parse::<f64>().unwrap();
    assert!(force(&rows[5]) > force(&rows[4]), "{results}");
    assert!(read(&a.join("timings.csv")).lines().count() == 7);
    for f in [
        "summary.md",
        "front.csv",
        "effects.csv",
        "front-small-potato.svg",
    ] {
        assert!(a.join(f).exists(), "{f}");
    }
    // The MPC's weight is compared among the MPC's runs only (pressing's
    // rows carry the default weight it does not use).
    let effects = read(&a.join("effects.csv"));
    let weight_levels: Vec<&str> = effects
        .lines()
        .filter(|l| l.contains(",controller.mpc.deformation_weight,"))
        .collect();
    assert_eq!(weight_levels.len(), 2, "{effects}");
    assert!(
        weight_levels.iter().all(|l| l.contains(",mpc,")),
        "{effects}"
    );
    let block = read(&a.join("recommended/small-potato-least-work.toml"));
    assert!(
        block.contains("[controller.mpc]") || block.contains("kind = \"press\""),
        "{block}"
    );
    // One thread gives the same table bit for bit.
    ok(&tune(&[s(&sweep), "--jobs", "1", "--out", s(&b)], &[]));
    assert_eq!(read(&b.join("results.csv")), results);
    // Resumption: with two row files gone, a re-run runs those two only
    // and ends with the same table.
    let ids: Vec<&str> = rows.iter().map(|r| r[col("id")]).collect();
    for id in &ids[1..3] {
        std::fs::remove_file(a.join("rows").join(format!("{id}.json"))).unwrap();
    }
    let out = ok(&tune(&[s(&sweep), "--out", s(&a)], &[]));
    assert!(out.contains("4 runs already done"), "{out}");
    assert_eq!(
        out.matches("[1/2] job").count() + out.matches("[2/2] job").count(),
        2,
        "{out}"
    );
    assert_eq!(read(&a.join("results.csv")), results);
    // Nothing left to run: nothing runs.
    let out = ok(&tune(&[s(&sweep), "--out", s(&a)], &[]));
    assert!(
        out.contains("6 runs already done") && !out.contains("] job"),
        "{out}"
    );
}

/// `shearcut tune SWEEP --jobs 1 --out OUT`, returned running once it has
/// printed its first job's line, with its stdout.
fn tune_after_first_job(
    sweep: &Path,
    out: &Path,
) -> (
    std::process::Child,
    std::io::BufReader<std::process::ChildStdout>,
) {
    use std::io::BufRead;
    let mut child = Command::new(env!("CARGO_BIN_EXE_shearcut"))
        .args(["tune", s(sweep), "--jobs", "1", "--out", s(out)])
        .env("RUST_LOG", "error")
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("the shearcut binary runs");
    let mut stdout = std::io::BufReader::new(child.stdout.take().unwrap());
    let mut first = String::new();
    while !first.contains("] job") {
        first.clear();
        assert!(stdout.read_line(&mut first).unwrap() > 0, "no job line");
    }
    (child, stdout)
}

/// A reader that stops reading mid-sweep (`shearcut tune … | head -n 3`):
/// the sweep stops quietly (141, as any command on a closed pipe), no
/// thread panics, and the rows written stay for a re-run to skip.
#[test]
fn a_stdout_closed_mid_sweep_stops_it_quietly_and_keeps_its_rows() {
    let t = TempDir::new("closed");
    let sweep = write_sweep(&t.0, SWEEP);
    let a = t.0.join("a");
    let (child, stdout) = tune_after_first_job(&sweep, &a);
    drop(stdout);
    let o = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(141), "{err}");
    assert!(!err.contains("panicked"), "{err}");
    let written = std::fs::read_dir(a.join("rows")).unwrap().count();
    // The job that printed its line wrote its row first; the sweep stopped
    // before running all six.
    assert!((1..6).contains(&written), "{written} rows");
    let out = ok(&tune(&[s(&sweep), "--out", s(&a)], &[]));
    assert!(
        out.contains(&format!("{written} runs already done")),
        "{out}"
    );
    assert_eq!(read(&a.join("results.csv")).lines().count(), 7);
}

/// SIGINT or SIGTERM mid-sweep ends the run in flight at its next tick
/// (no row for it) and starts no other: the finished runs' rows are
/// tabulated, the exit is 130/143 with one line, and a re-run runs the
/// rest.
#[test]
fn sigint_and_sigterm_stop_a_sweep_with_the_finished_rows_tabulated() {
    let t = TempDir::new("signals");
    let sweep = write_sweep(&t.0, SWEEP);
    for (signal, code) in [("INT", 130), ("TERM", 143)] {
        let a = t.0.join(signal);
        let (child, stdout) = tune_after_first_job(&sweep, &a);
        let (o, rest) = binary_run::signal_and_wait(child, stdout, signal);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(code), "{err}");
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(err.contains(&format!("stopped by SIG{signal}")), "{err}");
        // The first job's line was read before the signal; each other
        // finished job printed its line.
        let finished = 1 + rest.lines().filter(|l| l.contains("] job")).count();
        let written = std::fs::read_dir(a.join("rows")).unwrap().count();
        assert_eq!(written, finished, "{rest}");
        assert!(written < 6, "{written} rows");
        assert_eq!(
            read(&a.join("results.csv")).lines().count(),
            1 + written,
            "{rest}"
        );
        let out = ok(&tune(&[s(&sweep), "--out", s(&a)], &[]));
        assert!(
            out.contains(&format!("{written} runs already done")),
            "{out}"
        );
    }
}

#[test]
fn shards_merge_to_the_local_table_bit_for_bit() {
    let t = TempDir::new("shards");
    let sweep = write_sweep(&t.0, SWEEP);
    let local = t.0.join("local");
    ok(&tune(&[s(&sweep), "--out", s(&local)], &[]));
    // Shard 0 of 3 by flag, 1 by Slurm's array variables (ids 5–7), 2 by
    // Kubernetes' completion index.
    let sharded = t.0.join("sharded");
    let out = ok(&tune(
        &[s(&sweep), "--shard", "0/3", "--out", s(&sharded)],
        &[],
    ));
    assert!(out.contains("shard 0/3: 2 of them"), "{out}");
    ok(&tune(
        &[s(&sweep), "--out", s(&sharded)],
        &[
            ("SLURM_ARRAY_TASK_ID", "6"),
            ("SLURM_ARRAY_TASK_MIN", "5"),
            ("SLURM_ARRAY_TASK_COUNT", "3"),
        ],
    ));
    ok(&tune(
        &[s(&sweep), "--out", s(&sharded)],
        &[("JOB_COMPLETION_INDEX", "2"), ("SHEARCUT_SHARDS", "3")],
    ));
    let shards: Vec<PathBuf> = (0..3)
        .map(|i| sharded.join(format!("shard-{i}-of-3")))
        .collect();
    for (i, d) in shards.iter().enumerate() {
        // Jobs i and i + 3.
        assert_eq!(read(&d.join("results.csv")).lines().count(), 3, "shard {i}");
    }
    // Merging two of the three is refused, naming what is missing.
    let merged = t.0.join("merged");
    let o = tune(
        &["merge", s(&shards[0]), s(&shards[1]), "--out", s(&merged)],
        &[],
    );
    assert_eq!(o.status.code(), Some(2));
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(
        e.contains("2 of 6 jobs have no result (first: job 2)"),
        "{e}"
    );
    // A shard named twice (as given, or by another path to it) is refused
    // before anything is written.
    let twice = t.0.join("twice");
    let other_path = sharded.join(".").join("shard-0-of-3");
    for again in [&shards[0], &other_path] {
        let o = tune(
            &[
                "merge",
                s(&shards[0]),
                s(&shards[1]),
                s(again),
                s(&shards[2]),
                "--out",
                s(&twice),
            ],
            &[],
        );
        assert_eq!(o.status.code(), Some(2));
        let e = String::from_utf8_lossy(&o.stderr);
        assert_eq!(e.trim_end().lines().count(), 1, "{e}");
        assert!(e.contains("is named twice"), "{e}");
        assert!(!twice.exists());
    }
    // A directory that holds another command's files is not written into.
    let busy = t.0.join("busy");
    std::fs::create_dir_all(&busy).unwrap();
    std::fs::write(busy.join("notes.txt"), "mine").unwrap();
    let mut args = vec!["merge"];
    args.extend(shards.iter().map(|d| s(d)));
    args.extend(["--out", s(&busy)]);
    let o = tune(&args, &[]);
    assert_eq!(o.status.code(), Some(2));
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(e.contains("it holds files and no jobs.json"), "{e}");
    assert_eq!(std::fs::read_dir(&busy).unwrap().count(), 1);
    let o = tune(&[s(&sweep), "--out", s(&busy)], &[]);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(std::fs::read_dir(&busy).unwrap().count(), 1);
    // Nor is one whose jobs.json is not a sweep's catalogue: it is kept.
    std::fs::write(busy.join("jobs.json"), "{\"my\": \"data\"}").unwrap();
    let o = tune(&[s(&sweep), "--out", s(&busy)], &[]);
    assert_eq!(o.status.code(), Some(2));
    let e = String::from_utf8_lossy(&o.stderr);
    assert_eq!(e.trim_end().lines().count(), 1, "{e}");
    assert!(
        e.contains("is not a `shearcut tune` result directory"),
        "{e}"
    );
    assert_eq!(
        std::fs::read_to_string(busy.join("jobs.json")).unwrap(),
        "{\"my\": \"data\"}"
    );
    assert_eq!(std::fs::read_dir(&busy).unwrap().count(), 2);
    std::fs::remove_file(busy.join("jobs.json")).unwrap();
    let mut args = vec!["merge"];
    args.extend(shards.iter().map(|d| s(d)));
    args.extend(["--out", s(&merged)]);
    ok(&tune(&args, &[]));
    assert_eq!(
        read(&merged.join("results.csv")),
        read(&local.join("results.csv"))
    );
    assert_eq!(
        read(&merged.join("front.csv")),
        read(&local.join("front.csv"))
    );
    assert_eq!(
        read(&merged.join("summary.md")),
        read(&local.join("summary.md"))
    );
    // A row cut short is named as unreadable, not as a shard to run.
    let row = std::fs::read_dir(shards[2].join("rows"))
        .unwrap()
        .next()
        .unwrap()
        .unwrap()
        .path();
    std::fs::write(&row, "{\"id\": ").unwrap();
    let mut args = vec!["merge"];
    args.extend(shards.iter().map(|d| s(d)));
    let again = t.0.join("again");
    args.extend(["--out", s(&again)]);
    let o = tune(&args, &[]);
    assert_eq!(o.status.code(), Some(2));
    let e = String::from_utf8_lossy(&o.stderr);
    assert_eq!(e.trim_end().lines().count(), 1, "{e}");
    assert!(
        e.contains("is not a readable row of its job") && e.contains(&*row.to_string_lossy()),
        "{e}"
    );
}

/// The MPC and a three-point best-constant grid on two replicas of two
/// blade budgets: eight runs per budget.
const PAIRED: &str = r#"
scenarios = ["small-potato.toml"]
replicas = 2

[variants]
blade_budget = [0.006, 0.012]

[[controllers]]
kind = "mpc"

[[controllers]]
kind = "best-constant"
points = 3
"#;

#[test]
fn the_mpc_is_paired_with_each_variants_best_constant() {
    let t = TempDir::new("paired");
    let sweep = write_sweep(&t.0, PAIRED);
    let a = t.0.join("a");
    let out = ok(&tune(&[s(&sweep), "--jobs", "2", "--out", s(&a)], &[]));
    assert!(
        out.contains("16 runs (1 scenarios × 4 settings × 2 variants × 2 replicas)")
            && out.contains("recommended/, best-constant.csv, constant-grid.csv)"),
        "{out}"
    );
    let results = read(&a.join("results.csv"));
    let lines: Vec<&str> = results.lines().collect();
    let col = |name: &str| lines[0].split(',').position(|c| c == name).unwrap();
    let rows: Vec<Vec<&str>> = lines[1..].iter().map(|l| l.split(',').collect()).collect();
    // The grid's last point is each variant's cap: 6 or 12 mm of blade
    // over the 6 mm deep cut, ratio 1 or 2.
    let kinds: Vec<(&str, &str, &str)> = rows
        .iter()
        .filter(|r| r[col("controller")] == "best-constant:2/2")
        .map(|r| {
            (
                r[col("variant")],
                r[col("replica")],
                r[col("controller.kind")],
            )
        })
        .collect();
    assert_eq!(
        kinds,
        [
            ("0", "0", "slice:1"),
            ("0", "1", "slice:1"),
            ("1", "0", "slice:2"),
            ("1", "1", "slice:2")
        ]
    );
    // Recompute each variant's pairing from results.csv: the grid point of
    // least mean work over completed replicas, and the MPC's mean paired
    // difference per cent of that point's mean.
    let paired = read(&a.join("best-constant.csv"));
    let plines: Vec<&str> = paired.lines().collect();
    assert_eq!(plines.len(), 3, "{paired}");
    let pcol = |name: &str| plines[0].split(',').position(|c| c == name).unwrap();
    for (variant, line) in plines[1..].iter().enumerate() {
        let p: Vec<&str> = line.split(',').collect();
        let of = |setting: usize| -> Vec<(f64, bool)> {
            rows.iter()
                .filter(|r| {
                    r[col("variant")] == variant.to_string()
                        && r[col("setting")] == setting.to_string()
                })
                .map(|r| {
                    (
                        r[col("work_j")].parse().unwrap(),
                        r[col("completed")] == "true",
                    )
                })
                .collect()
        };
        let mean = |runs: &[(f64, bool)]| runs.iter().map(|r| r.0).sum::<f64>() / runs.len() as f64;
        let best = (1..=3)
            .filter(|&k| of(k).iter().all(|r| r.1))
            .min_by(|&a, &b| mean(&of(a)).total_cmp(&mean(&of(b))))
            .unwrap();
        let (mpc, constant) = (of(0), of(best));
        let diff = mpc
            .iter()
            .zip(&constant)
            .map(|(m, c)| m.0 - c.0)
            .sum::<f64>()
            / 2.0;
        let percent: f64 = p[pcol("work_diff_percent")].parse().unwrap();
        assert!(
            (percent - 100.0 * diff / mean(&constant)).abs() < 1e-9,
            "variant {variant}: {line}"
        );
        assert_eq!(p[pcol("replicas")], "2");
    }
    // Each grid point held over both variants: its excess over each
    // variant's best from results.csv, and the tuned point the least mean
    // excess (every point completes on this small potato).
    let grid = read(&a.join("constant-grid.csv"));
    let glines: Vec<&str> = grid.lines().collect();
    assert_eq!(glines.len(), 1 + 2 * 3, "{grid}");
    let gcol = |name: &str| glines[0].split(',').position(|c| c == name).unwrap();
    let mean_work = |variant: usize, setting: usize| {
        let works: Vec<f64> = rows
            .iter()
            .filter(|r| {
                r[col("variant")] == variant.to_string() && r[col("setting")] == setting.to_string()
            })
            .map(|r| r[col("work_j")].parse().unwrap())
            .collect();
        works.iter().sum::<f64>() / works.len() as f64
    };
    let best_work = |v: usize| {
        (1..=3)
            .map(|k| mean_work(v, k))
            .fold(f64::INFINITY, f64::min)
    };
    let excess = |v: usize, k: usize| 100.0 * (mean_work(v, k) / best_work(v) - 1.0);
    for line in &glines[1..] {
        let g: Vec<&str> = line.split(',').collect();
        let variant: usize = g[gcol("variant")].parse().unwrap();
        let point: usize = g[gcol("grid_point")]
            .trim_start_matches("best-constant:")
            .split('/')
            .next()
            .unwrap()
            .parse()
            .unwrap();
        let written: f64 = g[gcol("excess_work_percent")].parse().unwrap();
        assert!(
            (written - excess(variant, point + 1)).abs() < 1e-9,
            "{line}"
        );
    }
    let tuned = (1..=3)
        .min_by(|&a, &b| (excess(0, a) + excess(1, a)).total_cmp(&(excess(0, b) + excess(1, b))))
        .unwrap();
    let summary = read(&a.join("summary.md"));
    assert!(
        summary.contains("## The MPC against the best constant ratio, per variant")
            && summary.contains("| small-potato | blade 6 mm | 0 (as given) |"),
        "{summary}"
    );
    assert!(
        summary.contains("## Each point of the grid held over the variants")
            && summary.contains(&format!(
                "small-potato (MPC setting 0): best-constant:{}/2 (",
                tuned - 1
            )),
        "{summary}"
    );
}

/// The sweep file with `from` replaced by `to` gives exit code 2 and one
/// line on stderr containing `expected`.
fn refused(t: &TempDir, from: &str, to: &str, expected: &str) {
    assert!(SWEEP.contains(from), "{from}");
    let sweep = write_sweep(&t.0, &SWEEP.replace(from, to));
    let o = tune(&[s(&sweep), "--out", s(&t.0.join("never"))], &[]);
    let e = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{from} -> {to}: {e}");
    assert_eq!(e.trim_end().lines().count(), 1, "{e}");
    assert!(e.contains(expected), "{from} -> {to}: {e}");
    assert!(
        !t.0.join("never").exists(),
        "nothing is written for a bad sweep"
    );
}

#[test]
fn bad_sweep_files_exit_2_with_one_line() {
    let t = TempDir::new("bad");
    refused(&t, "[variants]", "[variant]", "sweep.toml:4:");
    refused(
        &t,
        "youngs_modulus_scale = [0.9, 1.1]",
        "youngs_modulus_scale = [0.9, 11.0]",
        "`variants.youngs_modulus_scale` = 11: must be in [0.1, 10]",
    );
    refused(
        &t,
        "\"mpc.deformation_weight\" = [0.0, 100.0]",
        "\"mpc.deformation_weight\" = [0.0, -1.0]",
        "`controllers[0].controller.mpc.deformation_weight` = -1: must be in [0, 1e9] J/m²",
    );
    refused(
        &t,
        "youngs_modulus_scale = [0.9, 1.1]",
        "youngs_modulus_scale = []",
        "`variants.youngs_modulus_scale` = []: needs at least one value",
    );
    refused(
        &t,
        "\"mpc.deformation_weight\" = [0.0, 100.0]",
        "\"mpc.planner.lockstep_ticks\" = [1, 0]",
        "`controllers[0].controller.mpc.planner.lockstep_ticks` = 0: in 1..=10000",
    );
    refused(
        &t,
        "\"mpc.deformation_weight\"",
        "\"mpc.deformation_wieght\"",
        "`controllers[0].controller.mpc.deformation_wieght`",
    );
    refused(
        &t,
        "kind = \"press\"",
        "kind = \"pid\"",
        "`controllers[1].kind` = pid",
    );
    refused(
        &t,
        "grid = { \"mpc.deformation_weight\" = [0.0, 100.0] }",
        "grid = { surrogate = \"elsewhere/potato-whole-chef.toml\" }",
        "neither a built-in surrogate",
    );
    refused(
        &t,
        "small-potato.toml",
        "missing.toml",
        "`scenarios[0]` = \"missing.toml\"",
    );
    refused(
        &t,
        "kind = \"press\"",
        "kind = \"press\"\nreplicas = 2",
        "replicas",
    );
    let o = tune(&["/nonexistent/sweep.toml"], &[]);
    assert_eq!(o.status.code(), Some(2));
    let o = tune(&["x.toml", "--shard", "3/3"], &[]);
    assert_eq!(o.status.code(), Some(2));
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(e.contains("`--shard` = 3/3"), "{e}");
}

#[test]
fn shipped_sweeps_all_load() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("config/sweeps");
    let mut n = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "toml") {
            let sweep =
                shearcut::tune::sweep_file::Sweep::load(&path).unwrap_or_else(|e| panic!("{e}"));
            let list = shearcut::tune::job_list::JobList::new(&sweep, s(&path)).unwrap();
            assert!(!list.jobs.is_empty(), "{}", path.display());
            n += 1;
        }
    }
    assert!(n >= 3, "{n} sweeps in {}", dir.display());
}

#[test]
fn the_heldout_set_is_whole_objects_none_of_them_in_the_tuning_set() {
    use shearcut::commands::check::resolved_toml;
    use shearcut::tune::sweep_file::Sweep;
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("config/sweeps");
    let variants = |file: &str| -> Vec<String> {
        let sweep = Sweep::load(&dir.join(file)).unwrap_or_else(|e| panic!("{e}"));
        let mut out = Vec::new();
        for s in &sweep.scenarios {
            for v in &sweep.variants {
                let applied = v.apply(s).unwrap();
                let whole = matches!(
                    applied.object,
                    shearcut_sim::ObjectShape::HalfPotato { .. }
                        | shearcut_sim::ObjectShape::Eggplant { .. }
                );
                assert!(whole, "{file}: {}", s.name);
                out.push(resolved_toml(&applied));
            }
        }
        out
    };
    // The coarse sets of both objects, the eggplants' reference sets and
    // their sets for the wide surrogate.
    for (held_out_file, tuning_file, at_least) in [
        ("mpc-heldout.toml", "mpc-tuning-set.toml", 12),
        (
            "mpc-heldout-specimens.toml",
            "mpc-tuning-set-specimens.toml",
            12,
        ),
        (
            "mpc-heldout-eggplant-reference.toml",
            "mpc-tuning-eggplant-reference.toml",
            8,
        ),
        (
            "mpc-heldout-eggplant-wide-surrogate.toml",
            "mpc-tuning-eggplant-wide-surrogate.toml",
            8,
        ),
    ] {
        let held_out = variants(held_out_file);
        let tuning = variants(tuning_file);
        assert!(
            held_out.len() >= at_least,
            "{held_out_file}: {} held-out variants",
            held_out.len()
        );
        for (i, v) in held_out.iter().enumerate() {
            assert!(
                !tuning.contains(v),
                "{held_out_file}: variant {i} is in {tuning_file}"
            );
            assert!(
                !held_out[..i].contains(v),
                "{held_out_file}: variant {i} twice"
            );
        }
    }
}
