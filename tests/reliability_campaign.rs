//! Issue 27's hostile campaign, the reproducers of the commands `check`,
//! `simulate`, `toughness` and `trajectory`: each is a test of the binary.
//! Bad input exits 2 with one line naming the key, the value and the
//! range; nothing panics (exit 101), nothing runs away, nothing echoes a
//! file; a closed stdout ends quietly (141), a full one with one line (1).

#[path = "support/sandbox.rs"]
#[allow(dead_code)] // This file uses part of the sandbox.
mod sandbox;

use std::path::PathBuf;
use std::process::{Command, Output, Stdio};

fn shearcut_with(args: &[&str], stdout: Stdio) -> Output {
    Command::new(env!("CARGO_BIN_EXE_shearcut"))
        .args(args)
        .env("RUST_LOG", "error")
        .env("RUST_BACKTRACE", "0")
        .stdout(stdout)
        .stderr(Stdio::piped())
        .output()
        .expect("the shearcut binary runs")
}

fn shearcut(args: &[&str]) -> Output {
    shearcut_with(args, Stdio::piped())
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// A private directory for one test, removed on drop.
struct Dir(PathBuf);

impl Dir {
    fn new(tag: &str) -> Self {
        let d = std::env::temp_dir().join(format!("shearcut-reliab-{tag}-{}", std::process::id()));
        std::fs::create_dir_all(&d).unwrap();
        Self(d)
    }

    fn file(&self, name: &str, text: &str) -> String {
        let p = self.0.join(name);
        std::fs::write(&p, text).unwrap();
        p.to_str().unwrap().to_string()
    }
}

impl Drop for Dir {
    fn drop(&mut self) {
        std::fs::remove_dir_all(&self.0).ok();
    }
}

const FIG7: &str = include_str!("../config/scenarios/fig7-potato.toml");
const LOOP_CUBOID: &str = include_str!("../config/scenarios/loop-potato-cuboid.toml");

/// Asserts exit 2 with exactly one stderr line that contains every `needle`.
fn assert_refused(o: &Output, needles: &[&str]) {
    let e = stderr(o);
    assert_eq!(o.status.code(), Some(2), "stderr: {e}");
    assert_eq!(e.lines().count(), 1, "one line: {e}");
    for n in needles {
        assert!(e.contains(n), "`{n}` not in: {e}");
    }
}

/// `check` refuses `text` (a scenario) naming `needles`.
fn check_refuses(tag: &str, text: &str, needles: &[&str]) {
    let d = Dir::new(tag);
    let path = d.file("s.toml", text);
    assert_refused(&shearcut(&["check", &path]), needles);
}

fn with_table(base: &str, table: &str) -> String {
    format!("{base}\n{table}\n")
}

const AGAR_SECTION: &str = include_str!("../config/scenarios/seed001-agar-section.toml");

/// The line of `check`'s output that starts with `# {command}: `, without
/// that.
fn readiness(o: &Output, command: &str) -> String {
    let out = String::from_utf8_lossy(&o.stdout);
    let head = format!("# {command}: ");
    out.lines()
        .find_map(|l| l.strip_prefix(&head))
        .unwrap_or_else(|| panic!("no `{head}` line in: {out}"))
        .to_string()
}

/// `check` says which command refuses a scenario and why, in the words
/// that command refuses it with: a fig. 7 cut at ξ = 20 runs its blade off
/// the edge (simulate), seed 001's agar section with 75 mm of blade asks
/// the loop's plant for more edge segments than it has (run), a knife that
/// is no preset has no surrogate for the MPC (run), a cuboid 5 mm from the
/// heel with 12 mm of blade would leave the edge (run).
#[test]
fn check_says_which_command_refuses_a_scenario_in_its_words() {
    let d = Dir::new("readiness");
    let xi20 = d.file(
        "xi20.toml",
        &FIG7.replace(
            "slice_push_ratios = [0.0, 0.33, 0.75, 1.8]",
            "slice_push_ratios = [0.0, 0.33, 0.75, 20.0]",
        ),
    );
    let agar_long_stroke = d.file(
        "agar-long-stroke.toml",
        &with_table(
            &AGAR_SECTION.replacen("z0 = 0.02 ", "z0 = 0.08 ", 1),
            "[controller]\nblade_budget = 0.075",
        ),
    );
    let no_surrogate = d.file(
        "no-surrogate.toml",
        &LOOP_CUBOID.replacen(
            "preset = \"straight\"",
            "preset = \"straight\"\nblade = { thickness = 0.003 }",
            1,
        ),
    );
    let cuboid_near_heel = d.file(
        "near-heel.toml",
        &LOOP_CUBOID.replacen("z0 = 0.02", "z0 = 0.005", 1),
    );
    for (scenario, refusing, ready, reason) in [
        (
            xi20.as_str(),
            "simulate",
            "run",
            "`motion.slice_push_ratios[3]` = 20: the blade would travel 0.4000 m along the edge",
        ),
        (
            // 75 mm of blade: the plant's edge segments over the stroke.
            agar_long_stroke.as_str(),
            "run",
            "simulate",
            "gives 382 segments of the edge (segments = 20), at most 256 are allowed",
        ),
        (
            // A knife that is no preset: no built-in surrogate for the
            // scenario's MPC (`run --controller slice:0.5` runs it).
            no_surrogate.as_str(),
            "run",
            "simulate",
            "`controller.surrogate` = (none): the material or knife is not a preset",
        ),
        (
            // 5 mm from the heel, with 12 mm of blade towards the tip: the
            // object would leave the edge at the heel.
            cuboid_near_heel.as_str(),
            "run",
            "simulate",
            "`motion.z0` = 0.005: must be in [0.0120, 0.1700] m: the object (30.0 mm along the edge) stays on the 200 mm edge over a 12.0 mm stroke towards the heel",
        ),
    ] {
        let o = shearcut(&["check", scenario]);
        assert!(o.status.success(), "{scenario}: {}", stderr(&o));
        assert_eq!(readiness(&o, ready), "ready", "{scenario}");
        let why = readiness(&o, refusing);
        assert!(
            why.starts_with("refuses it: ") && why.contains(reason),
            "{why}"
        );
        // The command itself refuses it, before any output, with the
        // same words.
        let out = d.0.join(format!("{refusing}-out"));
        let o = shearcut(&[refusing, scenario, "--out", out.to_str().unwrap()]);
        assert_refused(&o, &[why.strip_prefix("refuses it: ").unwrap()]);
        assert!(!out.exists(), "{}", out.display());
    }
}

/// A scenario that neither command can use is refused by `check`, in one
/// line naming both reasons.
#[test]
fn check_refuses_a_scenario_no_command_can_use() {
    check_refuses(
        "unusable",
        &AGAR_SECTION.replace("z0 = 0.02 ", "z0 = 0.2 "),
        &[
            "neither simulate nor run can use it",
            "simulate: `motion.slice_push_ratios[0]` = 0: the blade would travel 0.0000 m along the edge; z0 + piece length + travel = 0.2050 m exceeds the edge's 0.1000 m",
            "run: `motion.z0` = 0.2: must be at most 0.0950 m, with a blade budget of at most 0.0950 m: the object (5.0 mm along the edge) and a 200.0 mm stroke towards the heel need more than the 100 mm edge",
        ],
    );
}

#[test]
fn issue_27_huge_or_tiny_object_sizes_are_refused_not_a_panic() {
    for (key, value) in [
        ("width", "1e300"),
        ("height", "1e300"),
        ("length", "1e300"),
        ("width", "1e-300"),
        ("length", "1e-300"),
        ("length", "1e-9"),
    ] {
        let text =
            LOOP_CUBOID.replacen(&format!("{key} = "), &format!("{key} = {value}\n# was "), 1);
        check_refuses(
            "object",
            &text,
            &[&format!("`object.{key}` = {value}"), "[0.001, 1] m"],
        );
    }
}

#[test]
fn an_object_value_of_the_wrong_type_is_named_by_its_key() {
    let text = LOOP_CUBOID.replacen("width = ", "width = \"wide\"\n# was ", 1);
    check_refuses(
        "object-type",
        &text,
        // On the key's own line (18 of loop-potato-cuboid.toml), not the
        // table's header.
        &[":18:1: `width`: invalid type: string \"wide\", expected f64"],
    );
}

#[test]
fn issue_27_row_spacing_1e_300_is_refused() {
    check_refuses(
        "rows",
        &with_table(LOOP_CUBOID, "[section]\nrow_spacing = 1e-300"),
        &["`section.row_spacing` = 1e-300", "[1e-5, 0.005] m"],
    );
}

/// A row spacing inside its range on the tallest object still asks for a
/// mesh beyond the budget: refused by the resource estimate.
#[test]
fn a_fine_mesh_on_a_tall_object_is_refused_by_the_resource_estimate() {
    let text = with_table(
        &FIG7
            .replace("height = 0.025", "height = 1.0")
            .replace("width = 0.03 ", "width = 1.0 "),
        "[section]\nrow_spacing = 1e-5\ngrading_ratio = 1.0",
    );
    check_refuses("mesh", &text, &["`resources.section_mesh`", "nodes"]);
}

#[test]
fn issue_27_motion_step_1e_12_is_refused_with_its_geometric_bound() {
    let text = FIG7.replace("depth = 0.02", "depth = 0.02\nstep = 1e-12");
    check_refuses(
        "step",
        &text,
        &["`motion.step` = 1e-12", "must be in [2e-7, 0.001] m"],
    );
}

#[test]
fn a_slow_knife_at_a_high_loop_rate_is_refused_by_the_series_budget() {
    let text = with_table(
        &LOOP_CUBOID.replace("[controller]", "[controller]\nmax_duration = 3600"),
        "[loop]\nrate_hz = 20000",
    );
    check_refuses("series", &text, &["`resources.series`", "rows"]);
}

#[test]
fn issue_27_sensor_rate_1e300_is_refused() {
    let text = LOOP_CUBOID.replace(
        "segments = 20",
        "segments = 20\nsensor = { rate_hz = 1e300 }",
    );
    check_refuses(
        "rate",
        &text,
        &["`plant.sensor.rate_hz` = 1e300", "[1, 100000] Hz"],
    );
}

#[test]
fn a_blade_table_given_with_a_wire_is_checked_too() {
    check_refuses(
        "wire-blade",
        &with_table(AGAR_SECTION, "[knife.blade]\nthickness = nan"),
        &["`knife.blade.thickness` = NaN"],
    );
}

#[test]
fn an_mpc_iteration_cap_past_a_time_budget_is_refused() {
    check_refuses(
        "iterations",
        &with_table(LOOP_CUBOID, "[controller.mpc]\nmax_iterations = 4000000000"),
        &[
            "`controller.mpc.max_iterations` = 4000000000",
            "in 1..=1000",
        ],
    );
    check_refuses(
        "reversals",
        &with_table(LOOP_CUBOID, "[controller.mpc]\nmax_reversals = 4000000000"),
        &[
            "`controller.mpc.max_reversals` = 4000000000",
            "in 0..=10000",
        ],
    );
}

#[test]
fn issue_27_arm_jerk_1e300_is_refused() {
    check_refuses(
        "jerk",
        &with_table(LOOP_CUBOID, "[loop.arm_limits]\njerk = 1e300"),
        &["`loop.arm_limits.jerk` = 1e300"],
    );
}

#[test]
fn issue_27_one_bracket_doubling_is_refused() {
    check_refuses(
        "doublings",
        &with_table(FIG7, "[section]\nmax_bracket_doublings = 1"),
        &[
            "`section.max_bracket_doublings` = 1",
            "integer in [30, 200]",
        ],
    );
}

#[test]
fn issue_27_friction_1e300_and_poisson_0_4999999_are_refused() {
    for (key, value) in [
        ("friction_coefficient", "1e300"),
        ("poisson_ratio", "0.4999999"),
    ] {
        let text = FIG7.replace(
            "preset = \"potato-cuboid\"",
            &format!("preset = \"potato-cuboid\"\n{key} = {value}"),
        );
        check_refuses("material", &text, &[&format!("`material.{key}` = {value}")]);
    }
}

#[test]
fn issue_27_arrays_of_the_wrong_length_are_refused() {
    let text = LOOP_CUBOID.replace(
        "preset = \"straight\"",
        "preset = \"straight\"\nsensor = { position = [0, 0.03, -0.03, 1] }",
    );
    check_refuses(
        "position",
        &text,
        &["`knife.sensor.position` = 4 element(s)", "exactly 3"],
    );
    let text = LOOP_CUBOID.replace(
        "segments = 20",
        "segments = 20\nsensor = { bias = [0, 0, 0, 0, 0, 0, 0] }",
    );
    check_refuses(
        "bias",
        &text,
        &["`plant.sensor.bias` = 7 element(s)", "exactly 6"],
    );
}

#[test]
fn issue_27_surrogate_dev_zero_is_refused_by_the_size_cap() {
    let text = LOOP_CUBOID.replace(
        "kind = \"mpc\"",
        "kind = \"mpc\"\nsurrogate = \"/dev/zero\"",
    );
    check_refuses(
        "zero",
        &text,
        &[
            "`controller.surrogate` = /dev/zero",
            "larger than 1048576 bytes",
        ],
    );
}

#[test]
fn issue_27_surrogate_etc_passwd_is_described_never_echoed() {
    let d = Dir::new("passwd");
    let secret = d.file(
        "secret.toml",
        "root:x:0:0:SECRET-CONTENT:/root:/bin/bash\nmore = \"SECRET\"\n",
    );
    let text = LOOP_CUBOID.replace(
        "kind = \"mpc\"",
        &format!("kind = \"mpc\"\nsurrogate = \"{secret}\""),
    );
    let path = d.file("s.toml", &text);
    let o = shearcut(&["check", &path]);
    assert_refused(&o, &["`controller.surrogate`", "surrogate file: 1:"]);
    assert!(!stderr(&o).contains("SECRET"), "{}", stderr(&o));
}

#[test]
fn a_surrogate_whose_prediction_overflows_is_refused() {
    let d = Dir::new("overflow");
    let shipped = include_str!("../config/surrogates/potato-cuboid-straight.toml");
    let drag = shipped.lines().find(|l| l.starts_with("drag = [")).unwrap();
    let first = drag
        .trim_start_matches("drag = [")
        .split(',')
        .next()
        .unwrap();
    let file = d.file(
        "overflow.toml",
        &shipped.replace(drag, &drag.replacen(first, "1e308", 1)),
    );
    let text = LOOP_CUBOID.replace(
        "kind = \"mpc\"",
        &format!("kind = \"mpc\"\nsurrogate = \"{file}\""),
    );
    let path = d.file("s.toml", &text);
    assert_refused(
        &shearcut(&["check", &path]),
        &[
            "`controller.surrogate`",
            "its prediction `force_normal_slope` is not finite at ξ = 0",
            "refit with `shearcut fit`",
        ],
    );
}

#[test]
fn issue_27_check_dev_zero_is_refused_by_the_size_cap() {
    assert_refused(
        &shearcut(&["check", "/dev/zero"]),
        &["cannot read `/dev/zero`", "larger than 1048576 bytes"],
    );
}

#[test]
fn a_scenario_that_is_not_text_is_refused_without_echo() {
    let d = Dir::new("binary");
    let p = d.0.join("s.toml");
    std::fs::write(&p, [b'a', 0xff, 0xfe, b'\n']).unwrap();
    assert_refused(
        &shearcut(&["check", p.to_str().unwrap()]),
        &["not UTF-8 text"],
    );
}

#[test]
fn check_opens_the_mesh_and_refuses_an_open_surface() {
    let d = Dir::new("mesh");
    d.file("open.obj", "v 0 0 0\nv 0.05 0 0\nv 0 0.05 0\nf 1 2 3\n");
    let text = FIG7
        .replace(
            "kind = \"cuboid\"\nwidth = 0.03    # m, across the cut (world x)\nheight = 0.025  # m, above the board (world y)\nlength = 0.03   # m, along the edge (world z)",
            "kind = \"mesh\"\npath = \"open.obj\"",
        )
        .replace("depth = 0.02", "depth = 0.01");
    assert!(text.contains("open.obj"), "the fixture replaced the object");
    let path = d.file("s.toml", &text);
    assert_refused(
        &shearcut(&["check", &path]),
        &["`object.path`", "not closed"],
    );
    // A closed tetrahedron with one face reversed.
    d.file(
        "reversed.obj",
        "v 0 0 0\nv 0.05 0 0\nv 0 0.05 0\nv 0 0 0.05\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 4 3\n",
    );
    let path = d.file("reversed.toml", &text.replace("open.obj", "reversed.obj"));
    assert_refused(
        &shearcut(&["check", &path]),
        &[
            "`object.path`",
            "not consistently wound",
            // The file's coordinates as written (read as f32).
            "run from (0, 0.05, 0) m to (0.05, 0, 0) m",
        ],
    );
    // Two separate tetrahedra, each consistent, the smaller wound inwards.
    d.file(
        "two.obj",
        "v 0 0 0\nv 0.05 0 0\nv 0 0.05 0\nv 0 0 0.05\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n\
         v 0.1 0 0\nv 0.12 0 0\nv 0.1 0.02 0\nv 0.1 0 0.02\nf 5 6 7\nf 5 8 6\nf 5 7 8\nf 6 8 7\n",
    );
    let path = d.file("two.toml", &text.replace("open.obj", "two.obj"));
    assert_refused(
        &shearcut(&["check", &path]),
        &[
            "`object.path`",
            "the closed shell through (0.1, 0, 0) m faces the other way from the largest shell",
        ],
    );
    // A tetrahedron with a smaller one inside it wound as it is: a cavity
    // must face the other way.
    d.file(
        "cavity.obj",
        "v 0 0 0\nv 0.05 0 0\nv 0 0.05 0\nv 0 0 0.05\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n\
         v 0.005 0.005 0.005\nv 0.015 0.005 0.005\nv 0.005 0.015 0.005\nv 0.005 0.005 0.015\n\
         f 5 7 6\nf 5 6 8\nf 5 8 7\nf 6 7 8\n",
    );
    let path = d.file("cavity.toml", &text.replace("open.obj", "cavity.obj"));
    assert_refused(
        &shearcut(&["check", &path]),
        &[
            "`object.path`",
            "the closed shell through (0.005, 0.005, 0.005) m lies within a piece's material, so it is a cavity's wall",
        ],
    );
}

#[test]
fn a_mesh_larger_than_a_metre_is_refused_by_its_bounding_box() {
    let d = Dir::new("bigmesh");
    // A closed tetrahedron 2 m across.
    d.file(
        "big.obj",
        "v 0 0 0\nv 2 0 0\nv 0 0.05 0\nv 0 0 0.05\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n",
    );
    let text = FIG7
        .replace(
            "kind = \"cuboid\"\nwidth = 0.03    # m, across the cut (world x)\nheight = 0.025  # m, above the board (world y)\nlength = 0.03   # m, along the edge (world z)",
            "kind = \"mesh\"\npath = \"big.obj\"",
        )
        .replace("depth = 0.02", "depth = 0.01");
    let path = d.file("s.toml", &text);
    assert_refused(
        &shearcut(&["check", &path]),
        &["`object.path (bounding box along x)` = 2"],
    );
}

#[test]
fn issue_27_toughness_xi_1e300_is_refused_not_nan() {
    let o = shearcut(&["toughness", "--nu", "0.4", "--xi", "1e300"]);
    assert_refused(&o, &["`--xi` = 1e300", "[0, 20]"]);
    assert!(o.stdout.is_empty());
}

/// A pipe whose reader is already gone: every write gets EPIPE.
fn closed_pipe() -> Stdio {
    let (reader, writer) = std::io::pipe().unwrap();
    drop(reader);
    Stdio::from(writer)
}

fn dev_full() -> Stdio {
    Stdio::from(std::fs::File::create("/dev/full").unwrap())
}

#[test]
fn issue_27_a_closed_stdout_ends_quietly_with_141() {
    for args in [
        &["check", "fig7-potato"][..],
        &["toughness", "--nu", "0.4", "--xi", "0.75"][..],
    ] {
        let o = shearcut_with(args, closed_pipe());
        assert_eq!(o.status.code(), Some(141), "{args:?}: {}", stderr(&o));
        assert!(o.stderr.is_empty(), "{args:?}: {}", stderr(&o));
    }
}

#[test]
fn issue_27_a_full_stdout_is_one_line_and_exit_1() {
    for args in [
        &["check", "fig7-potato"][..],
        &["toughness", "--nu", "0.4", "--xi", "0.75"][..],
    ] {
        let o = shearcut_with(args, dev_full());
        assert_eq!(o.status.code(), Some(1), "{args:?}: {}", stderr(&o));
        let e = stderr(&o);
        assert_eq!(e.lines().count(), 1, "{e}");
        assert!(e.contains("cannot write to stdout"), "{e}");
    }
}

/// A quick single-section scenario: one ratio, a coarse mesh and steps.
fn quick_simulation(d: &Dir) -> String {
    let text = FIG7
        .replace(
            "slice_push_ratios = [0.0, 0.33, 0.75, 1.8]",
            "slice_push_ratios = [0.75]",
        )
        .replace("depth = 0.02", "depth = 0.005\nstep = 1e-4")
        + "\n[section]\nrow_spacing = 5e-4\n";
    d.file("quick.toml", &text)
}

#[test]
fn issue_27_simulate_to_a_closed_or_full_stdout_keeps_its_results() {
    let d = Dir::new("simulate");
    let scenario = quick_simulation(&d);
    for (stdout, code, tag) in [(closed_pipe(), 141, "pipe"), (dev_full(), 1, "full")] {
        let out = d.0.join(tag);
        let o = shearcut_with(
            &["simulate", &scenario, "--out", out.to_str().unwrap()],
            stdout,
        );
        assert_eq!(o.status.code(), Some(code), "{tag}: {}", stderr(&o));
        // The results were written before the summary was printed.
        let summary = std::fs::read_to_string(out.join("summary.json")).unwrap();
        let v: serde_json::Value = serde_json::from_str(&summary).unwrap();
        assert!(v["cuts"][0]["work_j"].as_f64().unwrap() > 0.0, "{summary}");
    }
}

fn cases(d: &Dir, lines: &[&[u8]]) -> String {
    let p = d.0.join("cases.jsonl");
    let mut bytes = Vec::new();
    for l in lines {
        bytes.extend_from_slice(l);
        bytes.push(b'\n');
    }
    std::fs::write(&p, bytes).unwrap();
    p.to_str().unwrap().to_string()
}

fn case_results(o: &Output) -> Vec<serde_json::Value> {
    String::from_utf8(o.stdout.clone())
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect()
}

const CASE: &[u8] = br#"{"current_position":[0],"target_position":[1],"max_velocity":[1],"max_acceleration":[1],"max_jerk":[1]}"#;

#[test]
fn issue_27_invalid_utf8_in_cases_is_an_error_line_and_the_rest_runs() {
    let d = Dir::new("utf8");
    let path = cases(&d, &[CASE, b"{\"id\": \"\xff\xfe\"}", CASE]);
    let o = shearcut(&["trajectory", "--cases", &path]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let r = case_results(&o);
    assert_eq!(r.len(), 3);
    assert_eq!(r[1]["line"], 2);
    assert!(r[1]["error"].as_str().unwrap().contains("not UTF-8"));
    // The lines around it run: one DoF 0 → 1 at v = a = j = 1 takes
    // 3.1748021039 s (ruckig's value, DEPENDENCIES.md), to 1e-9 s.
    for i in [0, 2] {
        assert!((r[i]["duration"].as_f64().unwrap() - 3.174_802_103_9).abs() < 1e-9);
    }
}

#[test]
fn issue_27_cycle_time_5e_324_is_an_error_not_a_null_duration() {
    let d = Dir::new("cycle");
    let line = br#"{"current_position":[0],"target_position":[1],"max_velocity":[1],"max_acceleration":[1],"max_jerk":[1],"cycle_time":5e-324,"duration_discretization":"discrete"}"#;
    let o = shearcut(&["trajectory", "--cases", &cases(&d, &[line])]);
    let r = case_results(&o);
    let e = r[0]["error"].as_str().unwrap();
    assert!(e.contains("`cycle_time` = 5e-324"), "{e}");
    assert!(r[0].get("duration").is_none());
}

#[test]
fn issue_27_a_short_case_cannot_ask_for_gigabytes_of_output() {
    let d = Dir::new("samples");
    let line = br#"{"current_position":[0,0,0,0,0,0,0,0],"target_position":[1,1,1,1,1,1,1,1],"max_velocity":[1,1,1,1,1,1,1,1],"max_acceleration":[1,1,1,1,1,1,1,1],"max_jerk":[1,1,1,1,1,1,1,1],"sample_count":1000000}"#;
    assert!(line.len() < 250);
    let o = shearcut(&["trajectory", "--cases", &cases(&d, &[line])]);
    assert!(o.stdout.len() < 1000, "{} bytes", o.stdout.len());
    let r = case_results(&o);
    assert!(r[0]["error"].as_str().unwrap().contains("`sample_count`"));
    // The file's budget is shared: two cases of 100 000 fit, a third does not.
    let ok = br#"{"current_position":[0],"target_position":[1],"max_velocity":[1],"max_acceleration":[1],"max_jerk":[1],"sample_count":100000}"#;
    let o = shearcut(&[
        "trajectory",
        "--cases",
        &cases(&d, &[ok, ok, ok]),
        "--out",
        d.0.join("out.jsonl").to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let text = std::fs::read_to_string(d.0.join("out.jsonl")).unwrap();
    let r: Vec<serde_json::Value> = text
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert!(r[0]["error"].is_null() && r[1]["error"].is_null());
    assert!(r[2]["error"].as_str().unwrap().contains("left"), "{}", r[2]);
}

#[test]
fn cases_file_dev_zero_is_refused_by_the_size_cap_with_exit_2() {
    assert_refused(
        &shearcut(&["trajectory", "--cases", "/dev/zero"]),
        &["cannot read `/dev/zero`", "larger than"],
    );
}

#[test]
fn a_missing_cases_file_is_exit_2() {
    assert_refused(
        &shearcut(&["trajectory", "--cases", "/nonexistent/cases.jsonl"]),
        &["cannot read `/nonexistent/cases.jsonl`"],
    );
}

/// The small closed loop of `tests/closed_loop.rs`: a force controller
/// 3 mm into the fig7 potato on a two-segment plant.
fn quick_loop(d: &Dir) -> String {
    d.file("loop.toml", &quick_loop_text())
}

/// The names in a result directory, sorted.
fn listing(dir: &std::path::Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

#[test]
fn issue_27_an_out_that_holds_files_is_refused_unless_overwrite() {
    let d = Dir::new("out-refused");
    let scenario = quick_simulation(&d);
    let out = d.0.join("results");
    let o = shearcut(&["simulate", &scenario, "--out", out.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let first = std::fs::read(out.join("summary.json")).unwrap();
    // Every file is whole: none is left under its temporary name.
    assert!(
        listing(&out).iter().all(|n| !n.starts_with(".partial-")),
        "{:?}",
        listing(&out)
    );
    // A second run into the same directory is refused before it starts,
    // and the first run's results stay as they were.
    let o = shearcut(&["simulate", &scenario, "--out", out.to_str().unwrap()]);
    assert_refused(&o, &["`--out`", "--overwrite"]);
    assert_eq!(std::fs::read(out.join("summary.json")).unwrap(), first);
    // --overwrite replaces the directory's contents, strays included.
    std::fs::write(out.join("stray.txt"), "x").unwrap();
    let o = shearcut(&[
        "simulate",
        &scenario,
        "--out",
        out.to_str().unwrap(),
        "--overwrite",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(!out.join("stray.txt").exists());
    assert!(out.join("summary.json").is_file());
    // An empty directory (`mktemp -d`) is taken as it is.
    let empty = d.0.join("empty");
    std::fs::create_dir_all(&empty).unwrap();
    let o = shearcut(&["simulate", &scenario, "--out", empty.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    // --overwrite alone names nothing to overwrite: a usage error.
    let o = shearcut(&["simulate", &scenario, "--overwrite"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
}

#[test]
fn issue_27_a_refused_run_leaves_no_directory() {
    let d = Dir::new("refused-leaves-nothing");
    let scenario = d.file(
        "bad.toml",
        &quick_loop_text().replace("kind = \"force:5\"", "kind = \"force:0\""),
    );
    let out = d.0.join("never");
    let o = shearcut(&["run", &scenario, "--out", out.to_str().unwrap()]);
    assert_refused(&o, &["force"]);
    assert!(!out.exists(), "{:?}", listing(&out));
}

fn quick_loop_text() -> String {
    FIG7.replace("depth = 0.02", "depth = 0.003")
        + "\n[plant]\nsegments = 2\n\n[section]\nrow_spacing = 0.0005\n\n[controller]\nkind = \"force:5\"\n"
}

#[test]
fn issue_27_run_to_a_closed_or_full_stdout_keeps_its_results() {
    let d = Dir::new("run-stdout");
    let scenario = quick_loop(&d);
    for (stdout, code, tag) in [(closed_pipe(), 141, "pipe"), (dev_full(), 1, "full")] {
        let out = d.0.join(tag);
        let o = shearcut_with(&["run", &scenario, "--out", out.to_str().unwrap()], stdout);
        assert_eq!(o.status.code(), Some(code), "{tag}: {}", stderr(&o));
        if code == 141 {
            assert!(o.stderr.is_empty(), "{}", stderr(&o));
        }
        let summary = std::fs::read_to_string(out.join("summary.json")).unwrap();
        let v: serde_json::Value = serde_json::from_str(&summary).unwrap();
        assert_eq!(v["end"], "completed", "{summary}");
        assert!(v["cut"]["work_j"].as_f64().unwrap() > 0.0, "{summary}");
    }
}

/// Whole CSV rows: every line that ends in a newline has the header's
/// number of fields (a kill during a flush's write may leave the last line
/// cut short, without its newline: it is not counted).
fn whole_rows(path: &std::path::Path) -> usize {
    let text = std::fs::read_to_string(path).unwrap();
    let whole = &text[..text.rfind('\n').map_or(0, |i| i + 1)];
    let mut r = csv::Reader::from_reader(whole.as_bytes());
    let fields = r.headers().unwrap().len();
    let mut rows = 0;
    for record in r.records() {
        let record = record.unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        assert_eq!(record.len(), fields, "{}: {record:?}", path.display());
        rows += 1;
    }
    rows
}

/// Lines in `path` that end in a newline (0 while it does not exist).
fn lines_in(path: &std::path::Path) -> usize {
    std::fs::read(path).map_or(0, |b| b.iter().filter(|&&c| c == b'\n').count())
}

/// `shearcut run` of the small loop cut 20 mm deep (long enough to be
/// stopped mid-run) into `out`, returned once its first flush of the
/// series (100 ms of simulated time) is on disk, still running.
#[allow(clippy::disallowed_methods)] // A watchdog on a child process.
fn long_run_after_first_flush(d: &Dir, out: &std::path::Path) -> std::process::Child {
    let scenario = d.file(
        "long.toml",
        &quick_loop_text().replace("depth = 0.003", "depth = 0.02"),
    );
    let mut child = Command::new(env!("CARGO_BIN_EXE_shearcut"))
        .args(["run", &scenario, "--out", out.to_str().unwrap()])
        .env("RUST_LOG", "error")
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let controller = out.join("controller.csv");
    let started = std::time::Instant::now();
    // The first flush holds the header and 100 rows (100 ms at 1 kHz): once
    // they are all there, it is complete.
    while lines_in(&controller) < 101 {
        assert!(
            started.elapsed() < std::time::Duration::from_secs(120),
            "no flush"
        );
        assert!(child.try_wait().unwrap().is_none(), "the run ended first");
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
    child
}

#[test]
fn issue_27_a_run_killed_mid_loop_leaves_whole_series() {
    let d = Dir::new("sigkill");
    let out = d.0.join("killed");
    let mut child = long_run_after_first_flush(&d, &out);
    child.kill().unwrap();
    child.wait().unwrap();
    // Every record up to the last flush, in whole rows: 100 ms at 1 kHz
    // at least (the first flush), and no summary (the run never finished).
    assert!(whole_rows(&out.join("controller.csv")) >= 100);
    whole_rows(&out.join("timeseries.csv"));
    assert!(!out.join("summary.json").exists());
}

#[test]
fn issue_27_sigint_and_sigterm_stop_a_run_with_a_partial_summary() {
    let d = Dir::new("signals");
    for (signal, number, code, name) in [("INT", 2, 130, "sigint"), ("TERM", 15, 143, "sigterm")] {
        let out = d.0.join(name);
        let child = long_run_after_first_flush(&d, &out);
        sandbox::send_signal(&child, signal);
        let o = child.wait_with_output().unwrap();
        assert_eq!(
            o.status.code(),
            Some(code),
            "{name} ({number}): {}",
            stderr(&o)
        );
        assert_eq!(stderr(&o).lines().count(), 1, "{}", stderr(&o));
        // The summary says why it stopped; the series hold whole rows up
        // to the stop; the plots are drawn.
        let summary = std::fs::read_to_string(out.join("summary.json")).unwrap();
        let v: serde_json::Value = serde_json::from_str(&summary).unwrap();
        assert_eq!(v["end"]["stopped"], name, "{summary}");
        let rows = whole_rows(&out.join("controller.csv"));
        assert_eq!(v["ticks"].as_u64().unwrap() as usize, rows, "{summary}");
        assert!(out.join("forces_work.png").is_file());
    }
}

/// Realtime at 1 kHz with the knife at 2 mm/s: the 2 cm cut of the
/// sandbox's small potato takes about 10 s of wall time, time enough to
/// act on a run mid-way; a high missed-command limit so that a loaded
/// machine's stalls do not brake the plant first.
const REALTIME_SLOW: &str = "\n[loop]\nclock = \"realtime\"\nrate_hz = 1000\nmissed_command_limit = 1000\n\n[controller]\nspeed = 0.002\n";

/// Waits (watchdog: 120 s) until `done`, `what` naming it; fails if
/// `child` ends first.
#[allow(clippy::disallowed_methods)] // A watchdog on child processes.
fn wait_until(what: &str, child: &mut std::process::Child, done: impl Fn() -> bool) {
    let started = std::time::Instant::now();
    while !done() {
        assert!(
            started.elapsed() < std::time::Duration::from_secs(120),
            "watchdog: {what}"
        );
        sandbox::assert_running(child, what);
        std::thread::sleep(std::time::Duration::from_millis(2));
    }
}

/// Waits until `path` holds at least `lines` lines.
fn wait_for_lines(path: &std::path::Path, lines: usize, child: &mut std::process::Child) {
    wait_until(
        &format!("{lines} lines in {}", path.display()),
        child,
        || lines_in(path) >= lines,
    );
}

/// Runs `child` to its end under the watchdog; its output and how long
/// that took.
#[allow(clippy::disallowed_methods)] // Elapsed time of a start-up fault, bounded loosely.
fn timed(child: std::process::Child) -> (Output, std::time::Duration) {
    let started = std::time::Instant::now();
    let o = sandbox::watchdog(child, sandbox::WATCHDOG);
    (o, started.elapsed())
}

/// Start-up faults are reported "within 1 s" (issue 27): the tests bound
/// the time loosely, as a loaded machine may stall; docs/reliability.md
/// gives the measured times.
const STARTUP_FAULT_BOUND: std::time::Duration = std::time::Duration::from_secs(5);

/// `child` ends (under the watchdog) with exit 1 and one line holding
/// `needle`, within [`STARTUP_FAULT_BOUND`].
fn assert_start_up_fault(child: std::process::Child, needle: &str) {
    let (o, elapsed) = timed(child);
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{e}");
    assert_eq!(e.lines().count(), 1, "one line: {e}");
    assert!(e.contains(needle), "`{needle}` not in: {e}");
    assert!(elapsed < STARTUP_FAULT_BOUND, "{elapsed:?}");
}

/// `scenario` with the plant's build made slow (16 segments of a fine
/// mesh: about a second on the 2-core machine), for faults while it builds.
fn slow_plant(sb: &sandbox::Sandbox, name: &str) -> String {
    slow_build(sb.scenario(name, 0.02, REALTIME_SLOW))
}

/// The scenario at path `s` with the plant's build made slow (16 segments
/// of a fine mesh: about a second on the 2-core machine).
fn slow_build(s: String) -> String {
    let s_text = std::fs::read_to_string(&s)
        .unwrap()
        .replace("segments = 2", "segments = 16")
        .replace("row_spacing = 0.0005", "row_spacing = 0.0001");
    std::fs::write(&s, s_text).unwrap();
    s
}

#[test]
fn issue_27_a_second_controller_or_plant_on_a_live_run_id_is_refused_at_once() {
    let sb = sandbox::Sandbox::new("in-use");
    let s = sb.scenario("long", 0.02, REALTIME_SLOW);
    let first = sb.dir.join("first");
    let (mut plant, mut controller) = sb.spawn_pair(&s, "busy", &first);
    wait_for_lines(&first.join("controller.csv"), 101, &mut controller);
    let second = sb.dir.join("second");
    let out = second.to_str().unwrap();
    for role in ["controller", "plant"] {
        let mut args = vec![
            "--scenario",
            &s,
            "--run-id",
            "busy",
            "--controller",
            "slice:0.75",
        ];
        if role == "controller" {
            args.extend(["--out", out]);
        }
        let (o, elapsed) = timed(sb.spawn(&[&[role], &args[..]].concat()));
        assert_refused(
            &o,
            &[&format!(
                "run id `busy` is in use: a {role} of it is running"
            )],
        );
        assert!(elapsed < STARTUP_FAULT_BOUND, "{role}: {elapsed:?}");
    }
    // The refused controller claimed no directory; the first run goes on.
    assert!(!second.exists());
    sandbox::assert_running(&mut plant, "plant");
    sandbox::assert_running(&mut controller, "controller");
    controller.kill().unwrap();
    plant.kill().unwrap();
    controller.wait().unwrap();
    plant.wait().unwrap();
}

/// Waits until iceoryx2 lists a live node `name` under `prefix`.
fn wait_for_node(prefix: &str, name: &str, child: &mut std::process::Child) {
    let config = shearcut::transport::loop_services::config(prefix).unwrap();
    wait_until(&format!("node {name}"), child, || {
        shearcut::transport::run_node::node_state(&config, name, None)
            == shearcut::transport::PeerState::Alive
    });
}

#[test]
fn issue_27_a_plant_that_dies_before_serving_is_reported_at_once() {
    let sb = sandbox::Sandbox::new("plant-dies");
    // It is killed while it builds, its node there, its boards not.
    let s = slow_plant(&sb, "slow-plant");
    let out = sb.dir.join("never");
    let (mut plant, mut controller) = sb.spawn_pair(&s, "dies", &out);
    // Stopped (SIGSTOP) as soon as its node is there: it cannot finish its
    // build however long the controller takes to start on a loaded machine.
    wait_for_node(sb.prefix(), "plant/dies", &mut plant);
    sandbox::send_signal(&plant, "STOP");
    // The controller past its start-up (its series files exist): its
    // node's cleanup of dead nodes is over, so a plant that dies from now
    // on stays listed dead (a plant that died before is, to the
    // controller, one that never came).
    let series = out.join("controller.csv");
    wait_until("the controller's series files", &mut controller, || {
        series.exists()
    });
    plant.kill().unwrap(); // SIGKILL while it builds.
    plant.wait().unwrap();
    assert_start_up_fault(
        controller,
        "the plant 'plant/dies' died before serving run 'dies'",
    );
    // The run never started: it leaves no directory.
    assert!(!out.exists());
}

#[test]
fn issue_27_sigint_and_sigterm_stop_an_iceoryx2_run_with_130_and_143() {
    let sb = sandbox::Sandbox::new("ipc-signals");
    let s = sb.scenario("long", 0.02, REALTIME_SLOW);
    for (signal, code, name) in [("INT", 130, "sigint"), ("TERM", 143, "sigterm")] {
        let out = sb.dir.join(name);
        let mut run = sb.spawn_run(&s, "iceoryx2", &out);
        wait_for_lines(&out.join("controller.csv"), 101, &mut run);
        sandbox::send_signal(&run, signal);
        let o = sandbox::watchdog(run, sandbox::WATCHDOG);
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(code), "{name}: {e}");
        // Both children stopped by themselves (none needed a SIGKILL), and
        // the supervisor says so on its last line.
        assert!(!e.contains("signal 9"), "{e}");
        assert!(e.lines().last().unwrap().contains("stopped cleanly"), "{e}");
        // The controller's partial results: the summary says why, the
        // series hold whole rows, one per tick.
        let summary = std::fs::read_to_string(out.join("summary.json")).unwrap();
        let v: serde_json::Value = serde_json::from_str(&summary).unwrap();
        assert_eq!(v["end"]["stopped"], name, "{summary}");
        let rows = whole_rows(&out.join("controller.csv"));
        assert_eq!(v["ticks"].as_u64().unwrap() as usize, rows, "{summary}");
        assert_eq!(v["dropped_rows"]["controller"], 0, "{summary}");
        assert!(out.join("loop_stats.json").is_file());
    }
}

/// A controller that dies (SIGKILL) or exits (SIGTERM: a clean stop, its
/// node removed) before its first command, while its plant builds: the
/// plant's peer watch saw it alive and sees it go, and the plant says so
/// as soon as its build is done (not after its 30 s connect timeout).
#[test]
fn issue_27_a_plant_whose_controller_dies_before_its_first_command_says_so_at_once() {
    let sb = sandbox::Sandbox::new("controller-dies");
    let s = slow_plant(&sb, "slow-plant");
    for (signal, id, cause) in [
        ("KILL", "ctl-killed", "died before its first command"),
        ("TERM", "ctl-stopped", "ended before its first command"),
    ] {
        // The controller first: it waits for its plant.
        let mut controller = sb.spawn_controller(&s, id, &sb.dir.join(id));
        wait_for_node(sb.prefix(), &format!("controller/{id}"), &mut controller);
        let mut plant = sb.spawn_plant(&s, id);
        wait_for_node(sb.prefix(), &format!("plant/{id}"), &mut plant);
        // The plant builds for about a second from here.
        sandbox::send_signal(&controller, signal);
        controller.wait().unwrap();
        assert_start_up_fault(
            plant,
            &format!(
                "plant/{id}: lost the controller: the controller 'controller/{id}' {cause} of run '{id}'"
            ),
        );
    }
}

/// A plant started after its controller and killed before any look of the
/// controller's saw it alive (the controller is stopped, SIGSTOP, from
/// before the plant's start to after its death): its dead node, younger
/// than the controller's own, is this run's plant, and the controller
/// reports its death instead of waiting for its connect timeout.
#[test]
fn issue_27_a_plant_killed_between_two_looks_is_reported_at_once() {
    let sb = sandbox::Sandbox::new("plant-dies-unseen");
    let s = slow_plant(&sb, "slow-plant");
    let out = sb.dir.join("never");
    let mut controller = sb.spawn_controller(&s, "unseen", &out);
    let series = out.join("controller.csv");
    wait_until("the controller's series files", &mut controller, || {
        series.exists()
    });
    sandbox::send_signal(&controller, "STOP");
    let mut plant = sb.spawn_plant(&s, "unseen");
    wait_for_node(sb.prefix(), "plant/unseen", &mut plant);
    plant.kill().unwrap(); // SIGKILL while it builds.
    plant.wait().unwrap();
    sandbox::send_signal(&controller, "CONT");
    assert_start_up_fault(
        controller,
        "the plant 'plant/unseen' died before serving run 'unseen'",
    );
    assert!(!out.exists());
}

/// A plant killed while its controller starts (its node just created, its
/// dead-node cleanup running or just done): the controller saw the plant
/// alive before its cleanup and reports its death, instead of taking it
/// for a plant that never came and waiting for its connect timeout.
#[test]
fn issue_27_a_plant_that_dies_as_its_controller_starts_is_reported_at_once() {
    let sb = sandbox::Sandbox::new("plant-dies-early");
    let s = slow_plant(&sb, "slow-plant");
    let mut plant = sb.spawn_plant(&s, "early");
    wait_for_node(sb.prefix(), "plant/early", &mut plant);
    // Held (SIGSTOP) in its build while the controller starts.
    sandbox::send_signal(&plant, "STOP");
    let out = sb.dir.join("never");
    let mut controller = sb.spawn_controller(&s, "early", &out);
    wait_for_node(sb.prefix(), "controller/early", &mut controller);
    plant.kill().unwrap(); // SIGKILL while it builds.
    plant.wait().unwrap();
    assert_start_up_fault(
        controller,
        "the plant 'plant/early' died before serving run 'early'",
    );
    assert!(!out.exists());
}

/// A peer killed (SIGKILL) before the other process starts: the other
/// finds its dead node, recent, at its node's creation, and reports the
/// death once no live peer of the name has appeared within the grace
/// (`UNSEEN_GRACE`), instead of waiting for its connect timeout (10 s for
/// the controller, 30 s for the plant).
#[test]
fn issue_27_a_peer_killed_before_the_other_starts_is_reported_at_once() {
    let sb = sandbox::Sandbox::new("peer-gone-first");
    let s = sb.scenario("quick", 0.003, "");
    let mut plant = sb.spawn_plant(&s, "gone-p");
    wait_for_node(sb.prefix(), "plant/gone-p", &mut plant);
    plant.kill().unwrap();
    plant.wait().unwrap();
    let out = sb.dir.join("never");
    assert_start_up_fault(
        sb.spawn_controller(&s, "gone-p", &out),
        "the plant 'plant/gone-p' died before serving run 'gone-p'",
    );
    assert!(!out.exists());
    let mut controller = sb.spawn_controller(&s, "gone-c", &sb.dir.join("gone-c"));
    wait_for_node(sb.prefix(), "controller/gone-c", &mut controller);
    controller.kill().unwrap();
    controller.wait().unwrap();
    assert_start_up_fault(
        sb.spawn_plant(&s, "gone-c"),
        "plant/gone-c: lost the controller: the controller 'controller/gone-c' died before its first command of run 'gone-c'",
    );
}

/// A lockstep plant whose controller is killed (SIGKILL) mid-run: at its
/// first missed command it looks at the controller's node, finds it dead,
/// brakes and says so (not after its 20 missed commands); the controller's
/// series hold whole rows.
#[test]
fn issue_27_a_lockstep_plant_whose_controller_dies_mid_run_says_so_at_its_first_miss() {
    assert_plant_says_its_controller_died_mid_run("controller-dies-mid-run", "", "mid");
}

/// A realtime plant whose controller is killed (SIGKILL) mid-run: it
/// steps on with the last command to its missed-command limit (1000 ticks
/// here: 1 s), brakes, then looks once at the controller's node and says
/// it died (not only "braked"); the controller's series hold whole rows.
#[test]
fn issue_27_a_realtime_plant_whose_controller_dies_mid_run_says_so_once_braked() {
    assert_plant_says_its_controller_died_mid_run(
        "rt-controller-dies-mid-run",
        REALTIME_SLOW,
        "rtmid",
    );
}

/// The small potato cut 2 cm deep with `extra` TOML, run as plant and
/// controller of run `id`; the controller killed (SIGKILL) after its first
/// flush. The plant exits 1 with one line naming the controller's death
/// after its first commands, braked, within [`STARTUP_FAULT_BOUND`]; the
/// controller's series hold whole rows.
fn assert_plant_says_its_controller_died_mid_run(tag: &str, extra: &str, id: &str) {
    let sb = sandbox::Sandbox::new(tag);
    let s = sb.scenario("long", 0.02, extra);
    let out = sb.dir.join("killed");
    let (plant, mut controller) = sb.spawn_pair(&s, id, &out);
    let series = out.join("controller.csv");
    wait_for_lines(&series, 101, &mut controller);
    controller.kill().unwrap();
    controller.wait().unwrap();
    let (o, elapsed) = timed(plant);
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{e}");
    assert_eq!(e.lines().count(), 1, "one line: {e}");
    let cause =
        format!("plant/{id}: lost the controller: the controller 'controller/{id}' died after");
    assert!(e.contains(&cause), "{e}");
    assert!(e.contains("; braked;"), "{e}");
    assert!(elapsed < STARTUP_FAULT_BOUND, "{elapsed:?}");
    assert!(whole_rows(&series) >= 100);
    whole_rows(&out.join("timeseries.csv"));
}

/// `run --transport iceoryx2` killed (SIGKILL) mid-run: its children,
/// orphaned, finish the run by themselves (their stderr closed), and the
/// controller's directory holds the whole run: a summary that parses and
/// whole rows, one per tick.
#[test]
fn issue_27_an_iceoryx2_run_whose_supervisor_is_killed_mid_run_is_finished_by_its_children() {
    let sb = sandbox::Sandbox::new("supervisor-killed");
    let s = sb.scenario("long", 0.02, "");
    let out = sb.dir.join("orphans");
    let mut run = sb.spawn_run(&s, "iceoryx2", &out);
    wait_for_lines(&out.join("controller.csv"), 101, &mut run);
    run.kill().unwrap();
    run.wait().unwrap();
    assert_finished_by_orphans(&out);
}

/// `run --transport iceoryx2` killed (SIGKILL) during its children's
/// start-up, its plant building: the orphaned children go on, serve and
/// finish the run as after a kill mid-run (neither runs on: each ends with
/// the run), and the directory holds that one run whole.
#[test]
fn issue_27_an_iceoryx2_run_whose_supervisor_is_killed_while_its_plant_builds_is_finished_by_its_children()
 {
    let sb = sandbox::Sandbox::new("supervisor-killed-start-up");
    let s = slow_build(sb.scenario("slow-lockstep", 0.006, ""));
    let out = sb.dir.join("orphans");
    let mut run = sb.spawn_run(&s, "iceoryx2", &out);
    // The controller past its start-up (its series files exist), the plant
    // building for about a second.
    let series = out.join("controller.csv");
    wait_until("the controller's series files", &mut run, || {
        series.exists()
    });
    assert_eq!(lines_in(&series), 0, "the loop had started");
    let supervisor = run.id();
    run.kill().unwrap();
    run.wait().unwrap();
    assert_finished_by_orphans(&out);
    // Both children end with the run: no process of its run id is left.
    let run_id = format!("--run-id slow-lockstep-{supervisor}-");
    #[allow(clippy::disallowed_methods)] // A watchdog on orphaned processes.
    let started = std::time::Instant::now();
    while !processes_with(&run_id).is_empty() {
        assert!(
            started.elapsed() < sandbox::WATCHDOG,
            "watchdog: the orphans {:?} run on",
            processes_with(&run_id)
        );
        std::thread::sleep(std::time::Duration::from_millis(10));
    }
}

/// The processes whose command line (arguments joined by spaces) holds
/// `needle`.
fn processes_with(needle: &str) -> Vec<u32> {
    std::fs::read_dir("/proc")
        .unwrap()
        .filter_map(|e| e.ok()?.file_name().to_str()?.parse::<u32>().ok())
        .filter(|pid| {
            std::fs::read(format!("/proc/{pid}/cmdline")).is_ok_and(|b| {
                String::from_utf8_lossy(&b)
                    .replace('\0', " ")
                    .contains(needle)
            })
        })
        .collect()
}

/// The orphaned children of a killed supervisor finish the run into
/// `out` (watchdog: [`sandbox::WATCHDOG`]): its summary parses, its ticks
/// equal the controller's whole rows, and the run was not stopped.
#[allow(clippy::disallowed_methods)] // A watchdog on orphaned processes.
fn assert_finished_by_orphans(out: &std::path::Path) {
    let series = out.join("controller.csv");
    let summary = out.join("summary.json");
    let started = std::time::Instant::now();
    while !summary.is_file() {
        assert!(
            started.elapsed() < sandbox::WATCHDOG,
            "watchdog: the orphaned controller's summary"
        );
        std::thread::sleep(std::time::Duration::from_millis(10));
    }
    // The summary is renamed into place after the series' last flush.
    let text = std::fs::read_to_string(&summary).unwrap();
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert_eq!(
        v["ticks"].as_u64().unwrap() as usize,
        whole_rows(&series),
        "{text}"
    );
    assert!(
        v.get("end").is_none_or(|e| e.get("stopped").is_none()),
        "{text}"
    );
}

/// A plant stopped by SIGTERM (or SIGINT) while it builds: it stops once
/// its build is done, 143 (130) and one line; its controller reports the
/// plant ended before serving, exit 1, and leaves no directory.
#[test]
fn issue_27_a_plant_stopped_while_it_builds_exits_cleanly_and_its_controller_says_so() {
    let sb = sandbox::Sandbox::new("plant-stopped-building");
    let s = slow_plant(&sb, "slow-plant");
    for (signal, code, id) in [("TERM", 143, "pterm"), ("INT", 130, "pint")] {
        let out = sb.dir.join(id);
        let mut controller = sb.spawn_controller(&s, id, &out);
        wait_for_node(sb.prefix(), &format!("controller/{id}"), &mut controller);
        let mut plant = sb.spawn_plant(&s, id);
        wait_for_node(sb.prefix(), &format!("plant/{id}"), &mut plant);
        sandbox::send_signal(&plant, signal);
        let (o, _) = timed(plant);
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(code), "{e}");
        assert_eq!(e.lines().count(), 1, "one line: {e}");
        assert!(
            e.contains(&format!("plant/{id}: stopped by SIG{signal}")),
            "{e}"
        );
        assert_start_up_fault(
            controller,
            &format!("the plant 'plant/{id}' ended before serving run '{id}'"),
        );
        assert!(!out.exists());
    }
}

/// SIGINT/SIGTERM to `run --transport iceoryx2` while its plant builds:
/// the supervisor stops the controller, then the plant, which finds its
/// controller ended and waits for its own signal: both stop cleanly and the
/// run exits 130/143 (not 1 for a lost controller).
#[test]
fn issue_27_a_signal_to_an_iceoryx2_run_while_its_plant_builds_stops_both_cleanly() {
    let sb = sandbox::Sandbox::new("ipc-signal-start-up");
    let s = slow_plant(&sb, "slow-plant");
    for (signal, code) in [("TERM", 143), ("INT", 130)] {
        let out = sb.dir.join(signal);
        let mut run = sb.spawn_run(&s, "iceoryx2", &out);
        // The controller past its start-up (its series files exist), the
        // plant building for about a second.
        let series = out.join("controller.csv");
        wait_until("the controller's series files", &mut run, || {
            series.exists()
        });
        sandbox::send_signal(&run, signal);
        let (o, _) = timed(run);
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(code), "{e}");
        assert!(
            e.lines()
                .last()
                .unwrap()
                .contains("plant and controller stopped cleanly"),
            "{e}"
        );
    }
}

/// The supervisor refuses bad input itself, before it starts a process:
/// exit 2 and the one line `run` gives in process (both children used to
/// fail on it and the supervisor exit 1).
#[test]
fn issue_27_an_iceoryx2_run_on_bad_input_exits_2_with_one_line() {
    let sb = sandbox::Sandbox::new("ipc-bad-input");
    let s = sb.scenario("bad", 0.003, "\n[controller]\nkind = \"force:0\"\n");
    let out = sb.dir.join("never");
    let (o, _) = timed(sb.spawn_run(&s, "iceoryx2", &out));
    assert_refused(&o, &["force"]);
    assert!(!out.exists());
    // A controller the command line names, refused the same way, within
    // the ranges of the scenario's `[controller] kind`.
    let s = sb.scenario("good", 0.003, "");
    for (controller, needle) in [
        ("shear:1", "`--controller` = shear:1: one of"),
        (
            "slice:1000",
            "`--controller (slice ratio)` = 1000: must be in [0, 20]",
        ),
    ] {
        let (o, _) = timed(sb.spawn(&[
            "run",
            &s,
            "--controller",
            controller,
            "--transport",
            "iceoryx2",
            "--out",
            out.to_str().unwrap(),
        ]));
        assert_refused(&o, &[needle]);
        assert!(!out.exists());
    }
}

/// A squatter holding the run's command board (a node of another name):
/// the controller's board creation retries for a second; a SIGINT or
/// SIGTERM meanwhile stops it at once with 130/143 and one line, not as a
/// failed board after the retries.
#[test]
fn issue_27_a_signal_during_the_board_retries_stops_the_controller_with_130_or_143() {
    use iceoryx2::prelude::*;
    use shearcut::transport::wire::WireCommand;
    let sb = sandbox::Sandbox::new("board-signal");
    let s = sb.scenario("short", 0.003, "");
    let config = shearcut::transport::loop_services::config(sb.prefix()).unwrap();
    let node = NodeBuilder::new()
        .config(&config)
        .create::<ipc::Service>()
        .unwrap();
    for (signal, code, name) in [("INT", 130, "SIGINT"), ("TERM", 143, "SIGTERM")] {
        let id = format!("held-{name}");
        let service = ServiceName::new(&format!("shearcut/{id}/command")).unwrap();
        let _board = node
            .service_builder(&service)
            .blackboard_creator::<u64>()
            .add::<WireCommand>(0, WireCommand::empty())
            .create()
            .unwrap();
        let out = sb.dir.join(&id);
        let mut controller = sb.spawn_controller(&s, &id, &out);
        // Its series files come just before its services.
        let series = out.join("controller.csv");
        wait_until("the controller's series files", &mut controller, || {
            series.exists()
        });
        sandbox::send_signal(&controller, signal);
        let (o, _) = timed(controller);
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(code), "{name}: {e}");
        assert_eq!(e.lines().count(), 1, "{name}: one line: {e}");
        assert!(
            e.contains(&format!(
                "controller/{id}: stopped by {name} while starting"
            )),
            "{name}: {e}"
        );
    }
}

/// A scenario whose series would exceed the budget is refused by `run`
/// before it preallocates anything: the loop's records are preallocated
/// for at most the budget's rows (`record_capacity`).
#[test]
fn a_run_over_the_series_budget_is_refused_before_it_preallocates() {
    let d = Dir::new("run-budget");
    let s = d.file(
        "s.toml",
        &with_table(
            &quick_loop_text().replace("[controller]", "[controller]\nmax_duration = 3600"),
            "[loop]\nrate_hz = 20000",
        ),
    );
    let out = d.0.join("never");
    let o = shearcut(&["run", &s, "--out", out.to_str().unwrap()]);
    assert_refused(
        &o,
        &["`resources.series` = 7.2e7 rows: must be at most 1e6 rows"],
    );
    assert!(!out.exists());
    // What a run at the budget preallocates (docs/reliability.md quotes it).
    let bytes = shearcut::closed_loop::record_capacity(72_000_000)
        * shearcut::closed_loop::LOOP_RECORD_BYTES;
    eprintln!("records at the series budget: {bytes} bytes");
    assert_eq!(bytes, 1_000_000 * shearcut::closed_loop::LOOP_RECORD_BYTES);
}

/// Both children refuse their input (an iceoryx2 prefix that is not
/// allowed, from the environment they inherit): the supervisor exits 2, not
/// 1, on one line that quotes each child's line.
#[test]
fn issue_27_a_childs_refusal_is_the_supervisors_exit_2_and_one_line() {
    let sb = sandbox::Sandbox::new("ipc-child-refuses");
    let s = sb.scenario("short", 0.003, "");
    let out = sb.dir.join("never");
    let child = Command::new(env!("CARGO_BIN_EXE_shearcut"))
        .args(["run", &s, "--transport", "iceoryx2", "--out"])
        .arg(&out)
        .env("RUST_LOG", "error")
        .env("SHEARCUT_IPC_PREFIX", "not/a/prefix")
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let (o, elapsed) = timed(child);
    let e = stderr(&o);
    assert_refused(&o, &["failed: the "]);
    for role in ["controller", "plant"] {
        assert!(e.contains(&format!("the {role} process (pid ")), "{e}");
    }
    let quoted =
        "exited with code 2: `SHEARCUT_IPC_PREFIX` = not/a/prefix: must be 1 to 32 characters";
    assert_eq!(e.matches(quoted).count(), 2, "{e}");
    assert!(elapsed < STARTUP_FAULT_BOUND, "{elapsed:?}");
    assert!(!out.exists());
}

/// The number written just before ` label` in `text` (`…, 12 successor
/// deferrals`).
fn count_before(text: &str, label: &str) -> u64 {
    let end = text
        .find(&format!(" {label}"))
        .unwrap_or_else(|| panic!("`{label}` not in: {text}"));
    let word = text[..end].rsplit([' ', ',']).next().unwrap();
    word.parse()
        .unwrap_or_else(|e| panic!("`{word}` before `{label}`: {e}"))
}

/// The realtime plant's successor counts (its end line) reach the
/// controller's `loop_stats.json` through the plant's counts board.
#[test]
fn issue_27_the_plants_successor_counts_are_in_loop_stats() {
    let sb = sandbox::Sandbox::new("successor-counts");
    let s = sb.scenario("short-rt", 0.003, REALTIME_SLOW);
    let out = sb.dir.join("out");
    let o = sandbox::watchdog(sb.spawn_run(&s, "iceoryx2", &out), sandbox::WATCHDOG);
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(0), "{e}");
    let stats = sandbox::read_json(&out.join("loop_stats.json"));
    for label in ["successor deferrals", "successor waits"] {
        let key = label.replace(' ', "_");
        assert_eq!(
            stats[&key].as_u64(),
            Some(count_before(&e, label)),
            "{key}: {stats}"
        );
    }
}

/// Seed 000 Fig. 10's half potato on coarse sections: three cuts of 4 s
/// of simulated time each, seconds of wall time in release; a signal or a
/// kill comes during the first.
fn long_simulation(d: &Dir) -> String {
    d.file(
        "fig10-coarse.toml",
        &(include_str!("../config/scenarios/fig10-potato-whole.toml").to_string()
            + "\n[section]\nrow_spacing = 0.0005\n"),
    )
}

/// `simulate scenario --out out`, killed (SIGKILL) once `file` holds its
/// header and a row.
fn simulation_killed_at(scenario: &str, out: &std::path::Path, file: &std::path::Path) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_shearcut"))
        .args(["simulate", scenario, "--out", out.to_str().unwrap()])
        .env("RUST_LOG", "error")
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    wait_for_lines(file, 2, &mut child);
    child.kill().unwrap();
    child.wait().unwrap();
}

/// `simulate` killed (SIGKILL) mid-cut, once its first flush is on disk:
/// its series hold whole rows, in the order of simulated time, and its
/// `cuts.csv` the cuts that finished (none: it died in the first); no
/// summary.
#[test]
fn issue_27_a_simulation_killed_mid_cut_leaves_whole_series() {
    let d = Dir::new("simulate-sigkill");
    let scenario = long_simulation(&d);
    let out = d.0.join("killed");
    let series = out.join("timeseries.csv");
    simulation_killed_at(&scenario, &out, &series);
    let rows = whole_rows(&series);
    assert!(rows >= 1);
    let mut r = csv::Reader::from_path(&series).unwrap();
    let time = r
        .headers()
        .unwrap()
        .iter()
        .position(|h| h == "time_s")
        .unwrap();
    let times: Vec<f64> = r
        .records()
        .take(rows)
        .map(|row| row.unwrap()[time].parse().unwrap())
        .collect();
    assert!(times.windows(2).all(|w| w[0] < w[1]), "{times:?}");
    assert_eq!(std::fs::read(out.join("cuts.csv")).unwrap().len(), 0);
    assert!(!out.join("summary.json").exists());
}

/// `simulate scenario --out out` sent `signal` (`kill -INT`: `("INT",
/// 130, "sigint")`) once its directory is claimed (its handlers are
/// installed before): exit `code`, one line naming the partial results, and
/// the summary's `end` naming the signal. The summary, parsed and as text.
fn simulation_stopped_by(
    scenario: &str,
    out: &std::path::Path,
    (signal, code, name): (&str, i32, &str),
) -> (serde_json::Value, String) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_shearcut"))
        .args(["simulate", scenario, "--out", out.to_str().unwrap()])
        .env("RUST_LOG", "error")
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    wait_until("the run's directory", &mut child, || {
        out.join("scenario.toml").is_file()
    });
    sandbox::send_signal(&child, signal);
    let o = sandbox::watchdog(child, sandbox::WATCHDOG);
    assert_eq!(o.status.code(), Some(code), "{name}: {}", stderr(&o));
    assert_eq!(stderr(&o).lines().count(), 1, "{}", stderr(&o));
    assert!(stderr(&o).contains("partial results in"), "{}", stderr(&o));
    let summary = std::fs::read_to_string(out.join("summary.json")).unwrap();
    let v: serde_json::Value = serde_json::from_str(&summary).unwrap();
    assert_eq!(v["end"]["stopped"], name, "{summary}");
    (v, summary)
}

/// `simulate` stopped by SIGINT or SIGTERM mid-cut: 130/143 and one line,
/// and the results so far written as a finished run's are (whole rows, a
/// summary saying why it stopped and summarising the cut in progress, the
/// plot).
#[test]
fn issue_27_sigint_and_sigterm_stop_a_simulation_with_its_results_so_far() {
    let d = Dir::new("simulate-signals");
    let scenario = long_simulation(&d);
    for (signal, code, name) in [("INT", 130, "sigint"), ("TERM", 143, "sigterm")] {
        let out = d.0.join(name);
        let (v, summary) = simulation_stopped_by(&scenario, &out, (signal, code, name));
        let cuts = v["cuts"].as_array().unwrap();
        assert_eq!(
            cuts.len(),
            1,
            "stopped in the first of three cuts: {summary}"
        );
        assert_eq!(cuts[0]["completed"], false, "{summary}");
        assert_eq!(whole_rows(&out.join("cuts.csv")), 1);
        assert!(whole_rows(&out.join("timeseries.csv")) > 0);
        assert!(out.join("forces_work.png").is_file());
    }
}

/// The wire slab's `simulate` (seed 001) stopped by SIGINT or SIGTERM:
/// 130/143 and one line, the angles in progress ended after their load
/// step and written with the rest (`series.csv` whole rows, each run
/// marked stopped, the summary's `end`, the plots).
#[test]
fn issue_27_sigint_and_sigterm_stop_a_wire_slab_sweep_with_its_angles_so_far() {
    let d = Dir::new("slab-signals");
    for (signal, code, name) in [("INT", 130, "sigint"), ("TERM", 143, "sigterm")] {
        let out = d.0.join(name);
        // The sweep of six angles takes tens of seconds.
        let (v, summary) = simulation_stopped_by("seed001-agar-wire", &out, (signal, code, name));
        // Two threads: each one's first angle started and was stopped.
        let angles = v["nucleation"].as_array().unwrap();
        assert!(
            !angles.is_empty() && angles.len() < 6,
            "stopped mid-sweep: {summary}"
        );
        assert!(angles.iter().any(|a| a["stopped"] == true), "{summary}");
        let steps: u64 = angles
            .iter()
            .map(|a| a["load_steps"].as_u64().unwrap())
            .sum();
        assert_eq!(whole_rows(&out.join("series.csv")) as u64, steps);
        assert!(out.join("stress_map.png").is_file());
    }
}

/// The wire slab's `simulate` killed (SIGKILL) once its first angle has
/// ended: `series.csv` and `surface.csv` hold whole rows of the angles
/// that ended, each angle whole (one thread: angle after angle, each
/// 15 load steps to a depth of 0.3 mm on a coarse mesh; the surface may
/// lack the last of them, killed between its two writes); no summary.
#[test]
fn issue_27_a_wire_slab_sweep_killed_mid_way_leaves_its_finished_angles() {
    let d = Dir::new("slab-sigkill");
    let scenario = d.file(
        "slab-quick.toml",
        &include_str!("../config/scenarios/seed001-agar-wire.toml")
            .replace("max_depth = 8e-3", "max_depth = 0.3e-3")
            .replace("threads = 2", "threads = 1")
            .replace("elements_per_radius = 6 ", "elements_per_radius = 4 "),
    );
    let out = d.0.join("killed");
    let series = out.join("series.csv");
    simulation_killed_at(&scenario, &out, &series);
    let rows = whole_rows(&series);
    let mut r = csv::Reader::from_path(&series).unwrap();
    let angles: Vec<String> = r
        .records()
        .take(rows)
        .map(|row| row.unwrap()[0].to_string())
        .collect();
    let mut per_angle: Vec<(String, usize)> = Vec::new();
    for a in angles {
        match per_angle.last_mut() {
            Some((last, n)) if *last == a => *n += 1,
            _ => per_angle.push((a, 1)),
        }
    }
    assert!(
        !per_angle.is_empty() && per_angle.len() < 6,
        "{per_angle:?}"
    );
    assert!(
        per_angle.iter().all(|(_, n)| *n == per_angle[0].1),
        "{per_angle:?}"
    );
    // Each angle's surface profile is written just after its series, so
    // the kill may fall between the two: the surface holds whole rows of
    // the same angles, or of all but the last (empty before its first).
    let surface = std::fs::read_to_string(out.join("surface.csv")).unwrap();
    assert!(surface.is_empty() || surface.ends_with('\n'), "{surface:?}");
    let mut surface_angles: Vec<String> = Vec::new();
    for row in csv::Reader::from_reader(surface.as_bytes()).records() {
        let angle = row.unwrap()[0].to_string();
        if surface_angles.last() != Some(&angle) {
            surface_angles.push(angle);
        }
    }
    let series_angles: Vec<String> = per_angle.iter().map(|(a, _)| a.clone()).collect();
    assert!(
        surface_angles == series_angles
            || surface_angles == series_angles[..series_angles.len() - 1],
        "surface {surface_angles:?}, series {series_angles:?}"
    );
    assert!(!out.join("summary.json").exists());
}

/// `loop-potato-cuboid-short-stroke` 6 mm deep with 1.2 mm of blade on a
/// coarse plant (as `tests/compare_cli.rs`): each run takes a tenth of a
/// second, a compare on 21 replicas one at a time about 90 runs.
fn small_short_stroke(d: &Dir) -> String {
    d.file(
        "small.toml",
        &(include_str!("../config/scenarios/loop-potato-cuboid-short-stroke.toml")
            .replace("depth = 0.02", "depth = 0.006")
            .replace("blade_budget = 0.004", "blade_budget = 0.0012")
            .replace("segments = 20", "segments = 4")
            + "\n[section]\nrow_spacing = 0.0005\n"),
    )
}

/// `compare` killed (SIGKILL) once `runs.csv` holds its header and two
/// rows: the file parses, each whole row names its run (a 16-digit job
/// id, unique, the controller it ran, its replica) and how it ended; no
/// table (the comparison never finished).
#[test]
fn issue_27_a_compare_killed_mid_way_leaves_its_finished_runs() {
    let d = Dir::new("compare-sigkill");
    let scenario = small_short_stroke(&d);
    let out = d.0.join("killed");
    let mut child = Command::new(env!("CARGO_BIN_EXE_shearcut"))
        .args([
            "compare",
            &scenario,
            "--replicas",
            "21",
            "--jobs",
            "1",
            "--out",
            out.to_str().unwrap(),
        ])
        .env("RUST_LOG", "error")
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let log = out.join("runs.csv");
    wait_for_lines(&log, 3, &mut child);
    child.kill().unwrap();
    child.wait().unwrap();
    let rows = whole_rows(&log);
    assert!(rows >= 2, "{rows}");
    let text = std::fs::read_to_string(&log).unwrap();
    let whole = &text[..text.rfind('\n').unwrap() + 1];
    let mut r = csv::Reader::from_reader(whole.as_bytes());
    let header: Vec<String> = r.headers().unwrap().iter().map(String::from).collect();
    let at = |name: &str| header.iter().position(|h| h == name).unwrap();
    let (id, controller, replica, end) = (at("id"), at("controller"), at("replica"), at("end"));
    let mut ids = Vec::new();
    for record in r.records() {
        let record = record.unwrap();
        assert_eq!(record[id].len(), 16, "{record:?}");
        assert!(
            record[id].chars().all(|c| c.is_ascii_hexdigit()),
            "{record:?}"
        );
        let c = &record[controller];
        assert!(
            c == "press" || c == "mpc" || c.starts_with("slice:") || c.starts_with("force:"),
            "{record:?}"
        );
        record[replica].parse::<u32>().unwrap();
        assert_eq!(&record[end], "completed", "{record:?}");
        ids.push(record[id].to_string());
    }
    let count = ids.len();
    ids.sort();
    ids.dedup();
    assert_eq!(ids.len(), count, "one row per run");
    assert!(!out.join("comparison.json").exists());
}
