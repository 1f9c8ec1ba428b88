//! The fit is deterministic: the same sweeps give bit-identical surrogates
//! whatever the number of sweep threads, so `shearcut fit` reproduces the
//! shipped files (a small grid here; the full fit takes a few minutes, see
//! `tests/fit.rs` at the workspace root).

use shearcut_sim::surrogate::{
    CutState, ScaleFactors, ScaledSweep, Surrogate, SweepCase, SweepRun, SweepSettings,
    fit_ratio_correction, fit_surrogate, grid, run_sweep, scaled_material,
};
use shearcut_sim::{BladeSection, KnifePreset, Material, MaterialPreset};

#[path = "support/settled_window.rs"]
mod settled_window;
use settled_window::settled_window_sums;

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

/// Each run's settled-window (travel since fracture ≥ 2 mm) sum of the full
/// model's non-friction work per depth F_n^c + ξF_t^c against the
/// surrogate's (fracture + strain-energy parts at the run's states), as the
/// relative residual (full − surrogate)/full of the window means.
fn window_residuals(s: &Surrogate, runs: &[SweepRun]) -> Vec<f64> {
    runs.iter()
        .map(|run| {
            let xi = run.case.xi;
            let (full, surrogate) =
                settled_window_sums(s, run, &ScaleFactors::default(), |x, o| {
                    (
                        (x.force_normal - x.force_normal_friction)
                            + xi * (x.force_tangential - x.force_tangential_friction),
                        o.fracture + o.strain,
                    )
                });
            (full - surrogate) / full
        })
        .filter(|r| r.is_finite())
        .collect()
}

/// `fit_window_weight`: the weight is recorded, the fit stays deterministic
/// across threads, and the window rows do what they are for: the runs'
/// settled-window means of the non-friction work per depth move towards
/// the full model's (root mean square over the runs of the relative residual). A negative weight
/// is an error, not a fit.
#[test]
fn window_rows_pull_the_settled_means_towards_the_full_model() {
    let (material, blade, settings, cases) = small_sweep();
    let runs = run_sweep(&material, &blade, &cases, &settings, 2, &|| {}).unwrap();
    let fit = |w| fit_surrogate(&material, &blade, "potato-cuboid", "straight", &runs, w);
    let plain = fit(0.0).unwrap();
    let weighted = fit(10.0).unwrap();
    assert_eq!(weighted.fit_window_weight, 10.0);
    assert!(
        weighted
            .to_toml_string()
            .contains("fit_window_weight = 10.0")
    );
    assert!(!plain.to_toml_string().contains("fit_window_weight"));
    let runs_one = run_sweep(&material, &blade, &cases, &settings, 1, &|| {}).unwrap();
    let again = fit_surrogate(
        &material,
        &blade,
        "potato-cuboid",
        "straight",
        &runs_one,
        10.0,
    )
    .unwrap();
    assert_eq!(again, weighted);
    let rms = |v: Vec<f64>| (v.iter().map(|x| x * x).sum::<f64>() / v.len() as f64).sqrt();
    let (before, after) = (
        rms(window_residuals(&plain, &runs)),
        rms(window_residuals(&weighted, &runs)),
    );
    eprintln!(
        "settled-window relative residual RMS: W = 0 {:.2} %, W = 10 {:.2} %",
        100.0 * before,
        100.0 * after
    );
    assert!(after < 0.8 * before, "W = 0 {before}, W = 10 {after}");
    for bad in [-1.0, f64::NAN, f64::INFINITY] {
        assert!(fit(bad).is_err(), "{bad}");
    }
}
