//! The fit is deterministic: the same sweeps give bit-identical surrogates
//! whatever the number of sweep threads, so `shearcut fit` reproduces the
//! shipped files (a small grid here; the full fit takes a few minutes, see
//! `tests/fit.rs` at the workspace root).

use shearcut_sim::surrogate::{SweepSettings, fit_surrogate, grid, run_sweep};
use shearcut_sim::{KnifePreset, MaterialPreset};

#[test]
fn fit_is_deterministic_across_threads() {
    let material = MaterialPreset::PotatoCuboid.material();
    let blade = KnifePreset::Straight.settings().blade;
    let settings = SweepSettings {
        depth_fraction: 0.6,
        ..SweepSettings::default()
    };
    let cases = grid(
        &[0.0, 0.8, 1.6],
        &[(0.012, 0.008), (0.016, 0.012), (0.014, 0.01)],
    );
    let fit_with = |threads| {
        let runs = run_sweep(&material, &blade, &cases, &settings, threads, &|| {}).unwrap();
        fit_surrogate(&material, &blade, "potato-cuboid", "straight", &runs).unwrap()
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
