//! The fit is deterministic: the same sweeps give bit-identical surrogates
//! whatever the number of sweep threads, so `shearcut fit` reproduces the
//! shipped files (a small grid here; the full fit takes a few minutes, see
//! `tests/fit.rs` at the workspace root).

use shearcut_sim::surrogate::{
    CutState, ScaleFactors, ScaledSweep, Surrogate, SweepCase, SweepSettings, fit_ratio_correction,
    fit_surrogate, grid, run_sweep, scaled_material,
};
use shearcut_sim::{BladeSection, KnifePreset, Material, MaterialPreset};

/// A small potato sweep (three ξ on three small sections, to 60 % of the
/// height): potato-cuboid, the straight blade, its settings and cases.
fn small_sweep() -> (Material, BladeSection, SweepSettings, Vec<SweepCase>) {
    let settings = SweepSettings {
        depth_fraction: 0.6,
        ..SweepSettings::default()
    };
    let cases = grid(
        &[0.0, 0.8, 1.6],
        &[(0.012, 0.008), (0.016, 0.012), (0.014, 0.01)],
    );
    (
        MaterialPreset::PotatoCuboid.material(),
        KnifePreset::Straight.settings().blade,
        settings,
        cases,
    )
}

#[test]
fn fit_is_deterministic_across_threads() {
    let (material, blade, settings, cases) = small_sweep();
    let fit_with = |threads| {
        let runs = run_sweep(&material, &blade, &cases, &settings, threads, &|| {}).unwrap();
        fit_surrogate(&material, &blade, "potato-cuboid", "straight", &runs, 0.0).unwrap()
    };
    let one = fit_with(1);
    let two = fit_with(2);
    assert_eq!(one.to_toml_string(), two.to_toml_string());
    assert_eq!(one, two);
    // And the fit is a real one: the pre-fracture compliance is positive.
    let s = one.evaluate(
        0.5,
        &shearcut_sim::surrogate::CutState {
            depth: 1e-4,
            height: 0.014,
            half_width: 0.01,
            fractured: false,
            travel_since_fracture: 0.0,
        },
        &Default::default(),
    );
    assert!(s.force_normal > 0.0 && s.force_tangential > 0.0, "{s:?}");
}

/// The ratio corrections' fit is deterministic too (sweeps at E × 0.5 and
/// × 2 on one or two threads give the same coefficients, bit for bit), and
/// it finds the physics of the off-nominal sweeps: at ρ = 2 the faces'
/// reaction is below linear scaling (the crack runs further ahead of the
/// wedge when E/R_c grows), at ρ = 0.5 above it.
#[test]
fn ratio_correction_fit_is_deterministic_and_bends_the_right_way() {
    let (material, blade, settings, cases) = small_sweep();
    let nominal = run_sweep(&material, &blade, &cases, &settings, 2, &|| {}).unwrap();
    let s = fit_surrogate(
        &material,
        &blade,
        "potato-cuboid",
        "straight",
        &nominal,
        0.0,
    )
    .unwrap();
    let fit_with = |threads| {
        let runs: Vec<_> = [0.5, 2.0]
            .map(|k| {
                let m = scaled_material(&material, 1.0, k);
                run_sweep(&m, &blade, &cases, &settings, threads, &|| {}).unwrap()
            })
            .into_iter()
            .collect();
        let sweeps = [
            ScaledSweep {
                toughness: 1.0,
                stiffness: 0.5,
                runs: &runs[0],
            },
            ScaledSweep {
                toughness: 1.0,
                stiffness: 2.0,
                runs: &runs[1],
            },
        ];
        fit_ratio_correction(&s, &sweeps).unwrap()
    };
    let one = fit_with(1);
    let two = fit_with(2);
    assert_eq!(one, two);
    let corrected = Surrogate { ratio: one, ..s };
    let state = CutState {
        depth: 6e-3,
        height: 0.014,
        half_width: 0.01,
        fractured: true,
        travel_since_fracture: 5.5e-3,
    };
    for xi in [0.0, 0.8, 1.6] {
        let at = |stiffness: f64| {
            let scale = ScaleFactors {
                toughness: 1.0,
                stiffness,
                friction: 1.0,
            };
            corrected.evaluate(xi, &state, &scale).friction
        };
        let nominal = at(1.0);
        assert!(
            at(2.0) < 2.0 * nominal,
            "xi {xi}: {} vs {}",
            at(2.0),
            nominal
        );
        assert!(
            at(0.5) > 0.5 * nominal,
            "xi {xi}: {} vs {}",
            at(0.5),
            nominal
        );
    }
}
