//! Every shipped scenario by name: `shearcut scenarios`, `shearcut --help`
//! and `shearcut check NAME` know each file of `config/scenarios/`.

#[path = "support/binary_run.rs"]
mod binary_run;

use binary_run::shearcut;

/// The stems of `config/scenarios/*.toml`, sorted.
fn shipped_names() -> Vec<String> {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/config/scenarios");
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .map(|p| p.file_stem().unwrap().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

#[test]
fn scenarios_lists_every_shipped_file_once_with_its_description() {
    let o = shearcut(&["scenarios"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let out = String::from_utf8_lossy(&o.stdout).into_owned();
    let mut listed: Vec<String> = out
        .lines()
        .map(|l| l.split_whitespace().next().unwrap().to_string())
        .collect();
    listed.sort();
    assert_eq!(listed, shipped_names(), "{out}");
    // One line each: the name, then the file's own description.
    for line in out.lines() {
        let name = line.split_whitespace().next().unwrap();
        let file = std::fs::read_to_string(format!(
            "{}/config/scenarios/{name}.toml",
            env!("CARGO_MANIFEST_DIR")
        ))
        .unwrap();
        let description = file
            .lines()
            .find_map(|l| l.strip_prefix("description = \""))
            .and_then(|l| l.strip_suffix('"'))
            .unwrap();
        assert!(line.ends_with(description), "{line}");
    }
}

#[test]
fn every_shipped_scenario_checks_by_name() {
    for name in shipped_names() {
        let o = shearcut(&["check", &name]);
        assert!(
            o.status.success(),
            "{name}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        let out = String::from_utf8_lossy(&o.stdout);
        assert!(out.contains(&format!("name = \"{name}\"")), "{name}: {out}");
        // A loop scenario is ready to run, a figure's to simulate.
        let ready = if name.starts_with("loop-") {
            Some("# run: ready")
        } else if name.starts_with("fig") {
            Some("# simulate: ready")
        } else {
            None
        };
        if let Some(line) = ready {
            assert!(out.lines().any(|l| l == line), "{name}: {out}");
        }
    }
}

#[test]
fn help_names_every_shipped_scenario() {
    let o = shearcut(&["--help"]);
    assert!(o.status.success());
    let out = String::from_utf8_lossy(&o.stdout);
    for name in shipped_names() {
        assert!(
            out.lines().any(|l| l.trim() == name),
            "{name} missing from --help:\n{out}"
        );
    }
}

/// The scenario table of docs/scenarios.md names every shipped file, each
/// in backticks as a user types it.
#[test]
fn the_scenarios_doc_names_every_shipped_scenario() {
    let doc =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/scenarios.md")).unwrap();
    for name in shipped_names() {
        assert!(
            doc.contains(&format!("`{name}`")),
            "{name} missing from docs/scenarios.md"
        );
    }
}
