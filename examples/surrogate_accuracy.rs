//! Surrogate files against the cross-section model at one section size:
//! the model's runs at ξ ∈ {0, 0.6, 1.2, 2.1} (to 80 % of the height, the
//! fit's sweep settings) compared with each file as `shearcut fit`'s
//! accuracy report compares its held-out runs (`surrogate::compare_run`:
//! RMS errors in % of the run's range, F_n after fracture as 2 mm window
//! means; docs/surrogates.md, "Objects beyond the default sizes").
//!
//! ```sh
//! cargo run --release --example surrogate_accuracy -- MATERIAL KNIFE HxW FILE...
//! cargo run --release --example surrogate_accuracy -- eggplant-whole chef 60x80 \
//!   eggplant-whole-chef config/surrogates/eggplant-whole-chef-wide.toml
//! ```
//!
//! HxW: the section's height and half width, mm. FILE: a surrogate file or
//! a built-in name. Prints, per file, the table `shearcut fit` prints for its
//! held-out runs.

use shearcut::commands::fit::{parse_section_sizes, resolve};
use shearcut::surrogates::surrogate_named;
use shearcut_sim::surrogate::{AccuracyReport, SweepSettings, compare_run, grid, run_sweep};

/// The ratios compared: pressing and the fit's held-out ratios.
const RATIOS: [f64; 4] = [0.0, 0.6, 1.2, 2.1];

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [material, knife, size, files @ ..] = args.as_slice() else {
        eprintln!("usage: surrogate_accuracy MATERIAL KNIFE HxW FILE...");
        std::process::exit(2);
    };
    let fail = |e: &dyn std::fmt::Display| -> ! {
        eprintln!("error: {e}");
        std::process::exit(2)
    };
    let (m, k) = resolve(material, knife).unwrap_or_else(|e| fail(&e));
    let sizes = parse_section_sizes("HxW", std::slice::from_ref(size)).unwrap_or_else(|e| fail(&e));
    let surrogates: Vec<_> = files
        .iter()
        .map(|f| surrogate_named(f).unwrap_or_else(|e| fail(&format!("FILE {f}: {}", e.allowed))))
        .collect();
    let runs = run_sweep(
        &m.material(),
        &k.settings().blade,
        &grid(&RATIOS, &sizes),
        &SweepSettings::default(),
        2,
        &|| {},
    )
    .unwrap_or_else(|e| fail(&e));
    for (file, surrogate) in files.iter().zip(&surrogates) {
        let runs = runs
            .iter()
            .map(|r| compare_run(surrogate, r).accuracy)
            .collect();
        let report = AccuracyReport::new(m.name(), k.name(), runs);
        print!("{file}: {}", report.table());
    }
}
