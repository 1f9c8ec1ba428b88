//! The `shearcut` command line as a user meets it: outputs, exit codes, errors.

#[path = "support/binary_run.rs"]
mod binary_run;

use binary_run::{shearcut, stderr, stdout};

#[test]
fn toughness_prints_the_issue_value() {
    let o = shearcut(&["toughness", "--nu", "0.4", "--xi", "0.75"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stdout(&o).contains("= 0.6224"), "{}", stdout(&o));
    // A tiny ν is echoed short, not as its 300 digits.
    let o = shearcut(&["toughness", "--nu", "1e-300", "--xi", "1"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stdout(&o).starts_with("r(xi=1, nu=1e-300) = "),
        "{}",
        stdout(&o)
    );
}

#[test]
fn toughness_plot_writes_svg_and_csv() {
    let dir = std::env::temp_dir().join(format!("shearcut-cli-{}", std::process::id()));
    let svg = dir.join("fig3.svg");
    let o = shearcut(&[
        "toughness",
        "--nu",
        "0.35",
        "--xi",
        "0.33",
        "--plot",
        svg.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(text.starts_with("<svg") && text.contains("Poisson"));
    let csv = std::fs::read_to_string(dir.join("fig3.csv")).unwrap();
    let mut lines = csv.lines();
    assert!(lines.next().unwrap().starts_with("poisson_ratio,r_xi_0,"));
    // Every row has ν and six ratios; the ξ = 0 column is exactly 1.
    for line in lines {
        let cols: Vec<f64> = line.split(',').map(|c| c.parse().unwrap()).collect();
        assert_eq!(cols.len(), 7);
        assert_eq!(cols[1], 1.0);
    }
    std::fs::remove_dir_all(dir).ok();
}

#[test]
fn bad_plot_extension_is_exit_2() {
    let o = shearcut(&["toughness", "--nu", "0.4", "--xi", "1", "--plot", "x.jpg"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("--plot"));
}

#[test]
fn scenario_with_bad_poisson_ratio_is_refused_in_one_line() {
    let dir = std::env::temp_dir().join(format!("shearcut-cli-nu-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("bad.toml");
    let text = include_str!("../config/scenarios/fig7-potato.toml").replace(
        "preset = \"potato-cuboid\"",
        "preset = \"potato-cuboid\"\npoisson_ratio = 0.7",
    );
    std::fs::write(&path, text).unwrap();
    let o = shearcut(&["check", path.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    let err = stderr(&o);
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.contains("`material.poisson_ratio` = 0.7: must be in [0, 0.49]"),
        "{err}"
    );
    assert!(!err.contains("panicked"));
    std::fs::remove_dir_all(dir).ok();
}

#[test]
fn missing_scenario_file_is_exit_2() {
    let o = shearcut(&["check", "/nonexistent/scenario.toml"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("cannot read `/nonexistent/scenario.toml`"));
}

#[test]
fn check_resolves_a_built_in_scenario() {
    let o = shearcut(&["check", "fig7-eggplant"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = stdout(&o);
    assert!(
        out.contains("youngs_modulus = 400000.0")
            && out.contains("initial_fracture_toughness = 275.0")
    );
}

#[test]
fn shipped_scenarios_all_check() {
    for entry in
        std::fs::read_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/config/scenarios")).unwrap()
    {
        let path = entry.unwrap().path();
        let o = shearcut(&["check", path.to_str().unwrap()]);
        assert!(o.status.success(), "{}: {}", path.display(), stderr(&o));
    }
}

#[test]
fn unknown_subcommand_is_exit_2() {
    let o = shearcut(&["frobnicate"]);
    assert_eq!(o.status.code(), Some(2));
}

#[test]
fn trajectory_cases_from_jsonl() {
    let dir = std::env::temp_dir().join(format!("shearcut-cli-otg-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let cases = dir.join("cases.jsonl");
    std::fs::write(
        &cases,
        concat!(
            r#"{"current_position":[0.0],"target_position":[1.0],"max_velocity":[1.0],"max_acceleration":[1.0],"max_jerk":[1.0]}"#,
            "\n{not json\n"
        ),
    )
    .unwrap();
    let out = dir.join("out.jsonl");
    let o = shearcut(&[
        "trajectory",
        "--cases",
        cases.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = std::fs::read_to_string(&out).unwrap();
    let lines: Vec<serde_json::Value> = text
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(lines.len(), 2, "one result per case line, errors included");
    // 0 → 1 with v = a = j = 1 takes 2·∛4 s.
    assert!((lines[0]["duration"].as_f64().unwrap() - 3.174_802_103_9).abs() < 1e-9);
    assert!(lines[1].get("error").is_some(), "{}", lines[1]);
    let missing = shearcut(&["trajectory", "--cases", "/nonexistent.jsonl"]);
    assert_eq!(missing.status.code(), Some(2));
    // The cases file as its own output is refused before it is emptied.
    let before = std::fs::read(&cases).unwrap();
    let onto = dir.join(".").join("cases.jsonl");
    let o = shearcut(&[
        "trajectory",
        "--cases",
        cases.to_str().unwrap(),
        "--out",
        onto.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert_eq!(stderr(&o).lines().count(), 1, "{}", stderr(&o));
    assert!(
        stderr(&o).contains("a file other than --cases"),
        "{}",
        stderr(&o)
    );
    assert_eq!(std::fs::read(&cases).unwrap(), before);
    std::fs::remove_dir_all(dir).ok();
}

#[test]
fn replica_counts_and_indices_out_of_range_are_refused_in_one_line() {
    for bad in ["0", "22"] {
        let o = shearcut(&["compare", "loop-potato-cuboid", "--replicas", bad]);
        assert_eq!(o.status.code(), Some(2));
        let e = stderr(&o);
        assert!(e.contains("--replicas") && e.contains("1..=21"), "{e}");
    }
    let o = shearcut(&["run", "loop-potato-cuboid", "--replica", "21"]);
    assert_eq!(o.status.code(), Some(2));
    let e = stderr(&o);
    assert!(e.contains("--replica") && e.contains("0..=20"), "{e}");
}

/// `RUST_LOG=info` tells the story of a closed-loop cut, one line per
/// milestone and a summary of the plant's re-choices; by default a run is
/// quiet on stderr.
#[test]
fn info_logs_tell_the_story_of_a_cut_and_the_default_is_quiet() {
    let dir = binary_run::scratch("story");
    let scenario = dir.join("small.toml");
    let text = include_str!("../config/scenarios/fig7-potato.toml")
        .replace("depth = 0.02", "depth = 0.006")
        + "\n[plant]\nsegments = 2\n\n[section]\nrow_spacing = 0.0005\n";
    std::fs::write(&scenario, text).unwrap();
    let run = |log: &str, out: &str| {
        std::process::Command::new(env!("CARGO_BIN_EXE_shearcut"))
            .args([
                "run",
                scenario.to_str().unwrap(),
                "--controller",
                "slice:0.75",
            ])
            .args(["--out", dir.join(out).to_str().unwrap()])
            .env("RUST_LOG", log)
            .output()
            .expect("the shearcut binary runs")
    };
    let told = run("info", "told");
    binary_run::assert_success(&told);
    let story = stderr(&told);
    for line in [
        "the edge touches",
        "first fracture",
        "target depth reached after",
        "the plant re-chose its moving sections",
        "results written to",
    ] {
        assert_eq!(story.matches(line).count(), 1, "{line}:\n{story}");
    }
    let quiet = std::process::Command::new(env!("CARGO_BIN_EXE_shearcut"))
        .args([
            "run",
            scenario.to_str().unwrap(),
            "--controller",
            "slice:0.75",
        ])
        .args(["--out", dir.join("quiet").to_str().unwrap()])
        .env_remove("RUST_LOG")
        .output()
        .unwrap();
    binary_run::assert_success(&quiet);
    assert!(quiet.stderr.is_empty(), "{}", stderr(&quiet));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A realtime clock with the MPC needs the realtime planner: a lockstep or
/// inline one would make the servo tick wait for a solve. Refused on load
/// when the scenario's controller is the MPC, and by a run that chooses the
/// MPC on the command line; with `latency = "realtime"` the scenario checks.
#[test]
fn a_realtime_clock_with_a_waiting_planner_is_refused_in_one_line() {
    let dir = std::env::temp_dir().join(format!("shearcut-cli-rt-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let write = |name: &str, kind: &str, extra: &str| {
        let path = dir.join(name);
        let text = include_str!("../config/scenarios/loop-potato-cuboid.toml")
            .replace("kind = \"mpc\"", &format!("kind = \"{kind}\""))
            + "\n[loop]\nclock = \"realtime\"\n"
            + extra;
        std::fs::write(&path, text).unwrap();
        path.to_str().unwrap().to_string()
    };
    let key = "`controller.mpc.planner.latency` = \"lockstep\": must be \"realtime\" under [loop] clock = \"realtime\"";
    let refused = |o: &std::process::Output| {
        assert_eq!(o.status.code(), Some(2));
        let err = stderr(o);
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(err.contains(key), "{err}");
    };
    let mpc = write("mpc.toml", "mpc", "");
    refused(&shearcut(&["check", &mpc]));
    let slice = write("slice.toml", "slice:0.5", "");
    assert_eq!(shearcut(&["check", &slice]).status.code(), Some(0));
    let out = dir.join("out");
    refused(&shearcut(&[
        "run",
        &slice,
        "--controller",
        "mpc",
        "--out",
        out.to_str().unwrap(),
    ]));
    let ok = write(
        "ok.toml",
        "mpc",
        "\n[controller.mpc.planner]\nlatency = \"realtime\"\n",
    );
    assert_eq!(shearcut(&["check", &ok]).status.code(), Some(0));
    std::fs::remove_dir_all(dir).ok();
}

#[test]
fn a_file_named_like_a_built_in_scenario_is_read_and_said_to_be() {
    let dir = binary_run::scratch("shadow");
    let text = include_str!("../config/scenarios/fig7-potato.toml")
        .replace("depth = 0.02", "depth = 0.006");
    std::fs::write(dir.join("fig7-potato"), text).unwrap();
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_shearcut"))
        .args(["check", "fig7-potato"])
        .current_dir(&dir)
        .output()
        .expect("the shearcut binary runs");
    binary_run::assert_success(&o);
    assert!(
        stderr(&o).contains("`fig7-potato` is read from the file of that name"),
        "{}",
        stderr(&o)
    );
    // stderr is a pipe here: the warning is plain text, no colour codes.
    assert!(!stderr(&o).contains('\x1b'), "{:?}", stderr(&o));
    // The file's values, not the built-in's.
    assert!(stdout(&o).contains("depth = 0.006"), "{}", stdout(&o));
    // Elsewhere the name is the built-in scenario, without a word.
    let o = shearcut(&["check", "fig7-potato"]);
    binary_run::assert_success(&o);
    assert!(!stderr(&o).contains("read from the file"), "{}", stderr(&o));
    assert!(stdout(&o).contains("depth = 0.02"), "{}", stdout(&o));
}

/// A missing argument and a bad choice are named on their one line.
#[test]
fn a_missing_argument_and_a_bad_choice_are_named_in_one_line() {
    let o = shearcut(&["run"]);
    assert_eq!(o.status.code(), Some(2));
    let e = stderr(&o);
    assert_eq!(e.lines().count(), 1, "{e}");
    assert!(e.contains("<SCENARIO>"), "{e}");
    let o = shearcut(&["run", "loop-potato-cuboid", "--transport", "foo"]);
    assert_eq!(o.status.code(), Some(2));
    let e = stderr(&o);
    assert_eq!(e.lines().count(), 1, "{e}");
    assert!(e.contains("inproc") && e.contains("iceoryx2"), "{e}");
}

/// An output path that cannot be created (under a file) is bad input:
/// exit 2, one line naming the argument and the file in the way, before
/// anything runs or is printed.
#[test]
fn output_paths_under_a_file_are_refused_in_one_line() {
    let dir = std::env::temp_dir().join(format!("shearcut-cli-out-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("a-file");
    std::fs::write(&file, "x").unwrap();
    let under = file.join("x");
    let under = under.to_str().unwrap();
    let svg = format!("{under}.svg");
    let toml = format!("{under}.toml");
    let sweep = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/config/sweeps/mpc-heldout.toml"
    );
    for (args, key) in [
        (vec!["run", "loop-potato-cuboid", "--out", under], "--out"),
        (
            vec!["toughness", "--nu", "0.3", "--xi", "1", "--plot", &svg],
            "--plot",
        ),
        (vec!["tune", sweep, "--jobs", "1", "--out", under], "--out"),
        (
            vec![
                "fit",
                "--material",
                "potato-cuboid",
                "--knife",
                "straight",
                "--out",
                &toml,
            ],
            "--out",
        ),
    ] {
        let o = shearcut(&args);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        let e = stderr(&o);
        assert_eq!(e.lines().count(), 1, "{args:?}: {e}");
        assert!(e.contains(key) && e.contains("a-file is a file"), "{e}");
        assert!(stdout(&o).is_empty(), "{args:?}: {}", stdout(&o));
    }
    std::fs::remove_dir_all(dir).ok();
}

/// `toughness --plot` claims its table's path (the plot's with `.csv`) as
/// well as the plot's before it draws: a directory there is refused, and no
/// plot is left behind.
#[test]
fn a_plot_whose_table_cannot_be_written_is_refused_before_drawing() {
    let dir = binary_run::scratch("plot-table");
    std::fs::create_dir_all(dir.join("fig3.csv")).unwrap();
    let svg = dir.join("fig3.svg");
    let plot = svg.to_str().unwrap();
    let o = shearcut(&["toughness", "--nu", "0.4", "--xi", "0.5", "--plot", plot]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let e = stderr(&o);
    assert_eq!(e.lines().count(), 1, "{e}");
    assert!(
        e.contains("`--plot (its table)`") && e.contains("fig3.csv"),
        "{e}"
    );
    assert!(!svg.exists() && stdout(&o).is_empty(), "{}", stdout(&o));
    std::fs::remove_dir_all(dir).ok();
}

/// A mesh path is relative to the scenario file; the scenario as resolved
/// (what `check` prints and a run writes to `scenario.toml`) names the
/// mesh so that it reads back from another directory.
#[test]
fn a_resolved_mesh_scenario_reads_back_from_another_directory() {
    let dir = binary_run::scratch("mesh-resolved");
    std::fs::create_dir_all(dir.join("c")).unwrap();
    std::fs::create_dir_all(dir.join("w")).unwrap();
    std::fs::write(
        dir.join("c/tetrahedron.obj"),
        "v 0 0 0\nv 0.05 0 0\nv 0 0.05 0\nv 0 0 0.05\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n",
    )
    .unwrap();
    let text = include_str!("../config/scenarios/fig7-potato.toml")
        .replace(
            "kind = \"cuboid\"\nwidth = 0.03    # m, across the cut (world x)\nheight = 0.025  # m, above the board (world y)\nlength = 0.03   # m, along the edge (world z)",
            "kind = \"mesh\"\npath = \"tetrahedron.obj\"",
        )
        .replace("depth = 0.02", "depth = 0.01");
    assert!(
        text.contains("tetrahedron.obj"),
        "the fixture replaced the object"
    );
    std::fs::write(dir.join("c/s.toml"), text).unwrap();
    let check = |scenario: &str| {
        std::process::Command::new(env!("CARGO_BIN_EXE_shearcut"))
            .args(["check", scenario])
            .current_dir(&dir)
            .output()
            .expect("the shearcut binary runs")
    };
    let o = check("c/s.toml");
    binary_run::assert_success(&o);
    // The mesh named by its absolute path.
    let mesh = dir.join("c/tetrahedron.obj");
    assert!(
        stdout(&o).contains(&format!("path = \"{}\"", mesh.display())),
        "{}",
        stdout(&o)
    );
    std::fs::write(dir.join("w/scenario.toml"), stdout(&o)).unwrap();
    let again = check("w/scenario.toml");
    binary_run::assert_success(&again);
    std::fs::remove_dir_all(dir).ok();
}

/// A negative count given to a flag is refused naming the flag, not as a
/// stray argument.
#[test]
fn a_negative_count_is_refused_naming_its_flag() {
    let sweep = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/config/sweeps/mpc-heldout.toml"
    );
    for (args, flag) in [
        (
            vec!["compare", "loop-potato-cuboid", "--replicas", "-1"],
            "--replicas",
        ),
        (
            vec!["compare", "loop-potato-cuboid", "--jobs", "-2"],
            "--jobs",
        ),
        (
            vec!["run", "loop-potato-cuboid", "--replica", "-1"],
            "--replica",
        ),
        (vec!["tune", sweep, "--shard", "-1/2"], "--shard"),
        (vec!["tune", sweep, "--jobs", "-1"], "--jobs"),
    ] {
        let o = shearcut(&args);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        let e = stderr(&o);
        assert_eq!(e.trim_end().lines().count(), 1, "{args:?}: {e}");
        assert!(
            e.contains(flag) && !e.contains("unexpected argument"),
            "{e}"
        );
    }
}

/// A finite-strain wire scenario given to the cutting model's commands is
/// named as what it is, with the commands that run it.
#[test]
fn a_wire_slab_scenario_is_sent_to_simulate() {
    let file = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/config/scenarios/seed001-agar-wire.toml"
    );
    for scenario in ["seed001-agar-wire", file] {
        let o = shearcut(&["run", scenario]);
        assert_eq!(o.status.code(), Some(2));
        let e = stderr(&o);
        assert_eq!(e.lines().count(), 1, "{e}");
        assert!(e.contains("shearcut simulate"), "{e}");
    }
}

/// A scenario's name names its result directory under `runs/`: a wire
/// scenario's is checked as the cutting model's is (no path separators),
/// and neither may be longer than a directory's name allows.
#[test]
fn a_scenario_named_with_a_path_or_too_long_a_name_is_refused() {
    let dir = std::env::temp_dir().join(format!("shearcut-cli-wire-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/config/scenarios/seed001-agar-wire.toml"
    ))
    .unwrap()
    .replace("name = \"seed001-agar-wire\"", "name = \"../outside\"");
    let file = dir.join("wire.toml");
    std::fs::write(&file, text).unwrap();
    for command in ["check", "simulate"] {
        let o = shearcut(&[command, file.to_str().unwrap()]);
        assert_eq!(o.status.code(), Some(2), "{command}: {}", stderr(&o));
        let e = stderr(&o);
        assert_eq!(e.lines().count(), 1, "{e}");
        assert!(e.contains("name") && e.contains("path separators"), "{e}");
    }
    // A name too long for a directory's name is refused before a run.
    let long = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/config/scenarios/loop-potato-cuboid.toml"
    ))
    .unwrap()
    .replace(
        "name = \"loop-potato-cuboid\"",
        &format!("name = \"{}\"", "a".repeat(300)),
    );
    let file = dir.join("long.toml");
    std::fs::write(&file, long).unwrap();
    let o = shearcut(&["check", file.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("at most 100 bytes"), "{}", stderr(&o));
    std::fs::remove_dir_all(dir).ok();
}
