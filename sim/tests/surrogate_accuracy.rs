//! The shipped surrogates against held-out full-model runs recomputed here
//! (issue #6: RMS error of F_n, F_t and total work below 5 % of their range,
//! peak force and fracture-onset depth within 10 %).
//!
//! Held out: ξ = 0.6, 1.2, 2.1 (the fit used 0, 0.25, 0.5, 0.75, 1, 1.4, 1.8,
//! 2.4) on a 25 mm high, 40 mm wide section (the fit's sizes are listed in
//! `FIT_SECTION_SIZES`; this one is not among them), for potato (no crack
//! jump at the onset), cuboid eggplant (R'_c/R_c ≈ 2: the first crack jumps
//! 0.5–2 mm ahead of the edge and the surrogate's catch-up carries the
//! forces to the knee) and whole eggplant (R'_c/R_c = 2.5: jumps of 3–7 mm
//! on this section, the longest catch-up). Forces are compared with the
//! full model's window means after fracture (the sawtooth; see
//! `shearcut_sim::surrogate::accuracy`). `shearcut fit` also reports the
//! second held-out size, 40 mm × 24 mm (tall and narrow), and whole potato:
//! the figures are in docs/surrogates.md (all within the targets); they are
//! not recomputed here to keep the test short.

use std::path::PathBuf;

use shearcut_sim::surrogate::{
    CutState, HELD_OUT_SLICE_PUSH_RATIOS, ScaleFactors, Surrogate, SweepCase, SweepRun,
    SweepSettings, compare_run, grid, run_sweep, scaled_material,
};
use shearcut_sim::{KnifePreset, Material, MaterialPreset};

#[path = "support/settled_window.rs"]
mod settled_window;
use settled_window::settled_window_sums;

/// The shipped straight-knife surrogate of a material preset.
fn shipped_surrogate(material: MaterialPreset) -> Surrogate {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(format!(
        "../config/surrogates/{}-straight.toml",
        material.name()
    ));
    Surrogate::from_path(&path).unwrap()
}

/// The section model's straight-knife runs of `cases` on `material` (two
/// threads).
fn straight_knife_runs(
    material: &Material,
    cases: &[SweepCase],
    settings: &SweepSettings,
) -> Vec<SweepRun> {
    let blade = KnifePreset::Straight.settings().blade;
    run_sweep(material, &blade, cases, settings, 2, &|| {}).unwrap()
}

fn meets_the_issue_tolerances(material: MaterialPreset) {
    let s = shipped_surrogate(material);
    let cases: Vec<SweepCase> = HELD_OUT_SLICE_PUSH_RATIOS
        .iter()
        .map(|&xi| SweepCase {
            xi,
            height: 0.025,
            half_width: 0.02,
        })
        .collect();
    let runs = straight_knife_runs(&material.material(), &cases, &SweepSettings::default());
    for run in &runs {
        let a = compare_run(&s, run).accuracy;
        eprintln!("{}: {a:?}", material.name());
        let xi = a.xi;
        assert!(a.force_normal_rms_pct < 5.0, "xi {xi}: F_n {a:?}");
        assert!(a.force_tangential_rms_pct < 5.0, "xi {xi}: F_t {a:?}");
        assert!(a.work_rms_pct < 5.0, "xi {xi}: work {a:?}");
        assert!(a.peak_force_error_pct.abs() < 10.0, "xi {xi}: peak {a:?}");
        assert!(a.onset_depth_error_pct.abs() < 10.0, "xi {xi}: onset {a:?}");
    }
}

#[test]
fn potato_surrogate_meets_the_issue_tolerances_on_held_out_runs() {
    meets_the_issue_tolerances(MaterialPreset::PotatoCuboid);
}

#[test]
fn eggplant_surrogate_meets_the_issue_tolerances_on_held_out_runs() {
    meets_the_issue_tolerances(MaterialPreset::EggplantCuboid);
}

#[test]
fn whole_eggplant_surrogate_meets_the_issue_tolerances_on_held_out_runs() {
    meets_the_issue_tolerances(MaterialPreset::EggplantWhole);
}

/// The indentation before the first fracture (linear elasticity: F_n and
/// F_t proportional to the depth) on sections of every proportion the
/// plants meet, none of them among the fit's sizes: squat and wide
/// (15 × 60 mm), tall and narrow (60 × 20 mm), the potato cuboid's
/// 25 × 30 mm and a large one (60 × 60 mm). The compliances' column term
/// H/w (`column_aspect`) keeps them within 2 % (without it, [1, λ_H, λ_w]
/// alone was 12 % off on F_n and 28 % on F_t at 15 × 60 mm, 2.4 % and 5.5 %
/// on the cuboid, whose indentation is what the MPC's estimator takes its
/// stiffness from).
#[test]
fn indentation_stiffness_follows_the_section_off_the_fit_sizes() {
    let s = shipped_surrogate(MaterialPreset::PotatoCuboid);
    let material = MaterialPreset::PotatoCuboid.material();
    let cases: Vec<SweepCase> = [(0.015, 0.03), (0.06, 0.01), (0.025, 0.015), (0.06, 0.03)]
        .into_iter()
        .map(|(height, half_width)| SweepCase {
            xi: 1.0,
            height,
            half_width,
        })
        .collect();
    // One step, well before the onset (≈ 0.1 mm at ξ = 1).
    let settings = SweepSettings {
        depth_fraction: 1e-4,
        ..SweepSettings::default()
    };
    let runs = straight_knife_runs(&material, &cases, &settings);
    for run in &runs {
        let sample = &run.samples[0];
        assert!(!sample.fractured);
        let c = run.case;
        let state = CutState {
            depth: sample.depth,
            height: c.height,
            half_width: c.half_width,
            fractured: false,
            travel_since_fracture: 0.0,
        };
        let o = s.evaluate(c.xi, &state, &ScaleFactors::default());
        let normal = sample.force_normal / o.force_normal;
        let tangential = sample.force_tangential / o.force_tangential;
        eprintln!(
            "{} x {} mm: section over surrogate F_n {normal:.4}, F_t {tangential:.4}",
            1e3 * c.height,
            2e3 * c.half_width
        );
        assert!((normal - 1.0).abs() < 0.02, "{c:?}: F_n {normal}");
        assert!((tangential - 1.0).abs() < 0.02, "{c:?}: F_t {tangential}");
    }
}

/// The mean normal force after fracture (docs/surrogates.md, "The normal
/// force's mean after fracture"): the MPC's estimator takes the toughness
/// factor from F_n less friction, so a bias of the surrogate's mean F_n
/// that changes with ξ goes into the estimate. On a section size the fit
/// did not use (potato cuboid, 25 mm high, 2 × 15 mm wide), summed over the
/// fractured steps 2 mm or more past the onset (the window of the sawtooth
/// the accuracy report averages, `compare_run`), the section model's F_n
/// over the surrogate's at the nominal factors is within 2.5 % of 1 at every
/// ξ and varies by less than 1.2 % over ξ. Before the steady strain-energy
/// rate, the faces' slip ratio and the face reaction's ξ-terms it was
/// 0.993, 0.979, 0.975, 0.968, 0.977 at ξ = 0, 0.3, 0.6, 1, 2.5 (3.2 % and a
/// spread of 2.5 %); now 0.986, 0.980, 0.984, 0.983, 0.979 (the rest, about
/// 2 % at every ξ, is the wedge's strain-energy rate and the face reaction
/// off the fit's sizes, which the size terms follow only to that level).
#[test]
fn potato_mean_normal_force_after_fracture_is_unbiased_across_xi() {
    let s = shipped_surrogate(MaterialPreset::PotatoCuboid);
    let material = MaterialPreset::PotatoCuboid.material();
    let cases: Vec<SweepCase> = [0.0, 0.3, 0.6, 1.0, 2.5]
        .iter()
        .map(|&xi| SweepCase {
            xi,
            height: 0.025,
            half_width: 0.015,
        })
        .collect();
    let runs = straight_knife_runs(&material, &cases, &SweepSettings::default());
    let mut ratios = Vec::new();
    for run in &runs {
        let c = run.case;
        let (full, surrogate) = settled_window_sums(&s, run, &ScaleFactors::default(), |x, o| {
            (x.force_normal, o.force_normal)
        });
        let ratio = full / surrogate;
        eprintln!("xi {}: full/surrogate mean F_n {ratio:.4}", c.xi);
        assert!((ratio - 1.0).abs() < 0.025, "xi {}: {ratio}", c.xi);
        ratios.push(ratio);
    }
    let spread = ratios.iter().cloned().fold(f64::MIN, f64::max)
        - ratios.iter().cloned().fold(f64::MAX, f64::min);
    assert!(spread < 0.012, "spread over xi {spread}: {ratios:?}");
}

/// The mean friction after fracture at another stiffness-to-toughness
/// ratio, off the fit's sizes: potato cuboid with R_c, R'_c × 0.7 and
/// E × 1.3 (ρ = S/T = 1.86, the estimator's corner plant), on the cuboid
/// plant's 25 × 15 mm section and the held-out 25 × 20 mm, ξ = 0.6 and 1,
/// summed over the fractured samples at least 2 mm past the onset, section
/// over surrogate (F_t's friction part; the estimator takes the friction
/// factor from F_t). The face reaction's ratio correction took its ξ-factor
/// alike for every size, and at ρ ≈ 2 the section's friction falls with ξ
/// by an amount set by the section (the crack leads the edge by 3.6 mm at
/// E × 2, 0.7 mm at nominal; `docs/surrogates.md`): the ratios were 0.966,
/// 0.950 (25 × 15) and 0.972, 0.964 (25 × 20), the surrogate up to 5 %
/// high. With the slice factor by size (`ratio::slice_size_basis`) they are
/// 1.005, 0.992 and 0.997, 0.987. 2.5 % is the scatter of the nominal
/// surrogate's mean friction over section sizes (±2.5 % at ρ = 1 over the
/// eight fit and held-out sizes), which no smooth size term follows.
#[test]
fn potato_mean_friction_at_another_ratio_is_unbiased_off_the_fit_sizes() {
    let s = shipped_surrogate(MaterialPreset::PotatoCuboid);
    let (t, st) = (0.7, 1.3);
    let material = scaled_material(&MaterialPreset::PotatoCuboid.material(), t, st);
    let cases = grid(&[0.6, 1.0], &[(0.025, 0.015), (0.025, 0.02)]);
    let runs = straight_knife_runs(&material, &cases, &SweepSettings::default());
    let scale = ScaleFactors {
        toughness: t,
        stiffness: st,
        friction: 1.0,
    };
    for run in &runs {
        let c = run.case;
        let (full, surrogate) = settled_window_sums(&s, run, &scale, |x, o| {
            (
                x.force_tangential_friction,
                st * o.force_tangential_parts.by_friction_stiffness,
            )
        });
        let ratio = full / surrogate;
        eprintln!(
            "{} x {} mm, xi {}: full/surrogate mean F_t friction {ratio:.4}",
            c.height * 1e3,
            c.half_width * 1e3,
            c.xi
        );
        assert!(
            (ratio - 1.0).abs() < 0.025,
            "{} x {} mm, xi {}: {ratio}",
            c.height * 1e3,
            c.half_width * 1e3,
            c.xi
        );
    }
}
