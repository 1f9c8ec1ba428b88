//! Every input the fuzzers keep (`fuzz/corpus/<target>/`) and every crash
//! they found (`fuzz/regressions/<target>/`, a file per crash, fixed) runs
//! through the fuzz targets' own bodies on stable, so a fixed crash stays
//! fixed. The bodies assert the readers' promises (a validated value is
//! usable, a refusal is one line); see `fuzz/fuzz_targets/input_surface.rs`.

#[path = "../fuzz/fuzz_targets/input_surface.rs"]
mod input_surface;

use std::path::Path;

/// Runs `body` on every file of `fuzz/corpus/<target>` and
/// `fuzz/regressions/<target>`; returns how many there were.
fn replay(target: &str, body: fn(&[u8])) -> usize {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("fuzz");
    let mut n = 0;
    for kind in ["corpus", "regressions"] {
        let dir = root.join(kind).join(target);
        let Ok(entries) = std::fs::read_dir(&dir) else {
            continue;
        };
        let mut files: Vec<_> = entries.map(|e| e.unwrap().path()).collect();
        files.sort();
        for f in files {
            if f.file_name().is_some_and(|n| n == ".gitkeep") {
                continue;
            }
            let bytes = std::fs::read(&f).unwrap();
            let result = std::panic::catch_unwind(|| body(&bytes));
            assert!(result.is_ok(), "{} panics", f.display());
            n += 1;
        }
    }
    n
}

#[test]
fn scenario_toml_corpus_and_regressions() {
    assert!(replay("scenario_toml", input_surface::scenario_toml) >= 11);
}

#[test]
fn mesh_file_corpus_and_regressions() {
    assert!(replay("mesh_file", input_surface::mesh_file) >= 4);
}

#[test]
fn surrogate_file_corpus_and_regressions() {
    assert!(replay("surrogate_file", input_surface::surrogate_file) >= 8);
}

#[test]
fn trajectory_cases_corpus_and_regressions() {
    assert!(replay("trajectory_cases", input_surface::trajectory_cases) >= 2);
}

#[test]
fn wire_messages_corpus_and_regressions() {
    assert!(replay("wire_messages", input_surface::wire_messages) >= 7);
}
