//! The half potato's largest surface deflection against the surrogate's
//! onset deflection: what the MPC's deformation term does and does not see
//! (docs/heldout.md, "The half potato with 30 mm of blade at z0 40 mm").

use shearcut::closed_loop::run_closed_loop;
use shearcut::controller_choice::ControllerChoice;
use shearcut::object_profile::surrogate_profile;
use shearcut::scenario::Scenario;
use shearcut::surrogates::surrogate_for;
use shearcut::tune::perturbation::Perturbation;
use shearcut_controllers::mpc::{SliceModel, StageState, SurrogateModel};

/// `loop-potato-whole-realtime` at z0 40 mm with 30 mm of blade, the
/// held-out variant as `config/sweeps/mpc-heldout.toml` builds it, so that
/// constant ratios up to 1.2 fit its 25 mm.
fn potato_with_a_long_blade() -> Scenario {
    let variant = Perturbation {
        z0: Some(0.04),
        blade_budget: Some(0.03),
        ..Perturbation::default()
    };
    let mut s = variant
        .apply(&Scenario::load("loop-potato-whole-realtime").unwrap())
        .unwrap();
    s.controller.max_duration = 6.0;
    s
}

/// At constant ratios the plant's largest deflection, reached as the crack
/// runs through the flesh and stands between its jumps, falls with ξ as the
/// surrogate's onset deflection δ*(ξ) of intact material does (for the
/// object's equivalent section): their ratio stays within 5 % over
/// ξ = 0.5–1.12 while both fall by about half. The MPC's deformation term
/// sums δ* at the first fracture and over the edge entering contact; it has
/// no term for the cut's largest deflection.
#[test]
fn the_half_potatos_largest_deflection_follows_the_onset_deflection_of_its_flesh() {
    let s = potato_with_a_long_blade();
    let surrogate = surrogate_for(&s).unwrap();
    let mesh = s.object.mesh().unwrap();
    let profile = surrogate_profile(&s, &surrogate, &mesh, s.motion.depth.unwrap()).unwrap();
    let model = SurrogateModel::new(surrogate);
    let intact = StageState {
        depth: 0.0,
        height: profile.height(),
        half_width: profile.half_width(),
        fractured: false,
        travel_since_fracture: 0.0,
    };
    let mut deflections = Vec::new();
    for xi in [0.5, 0.84, 1.12] {
        let run = run_closed_loop(&s, ControllerChoice::Slice(xi)).unwrap();
        assert!(run.summary.completed, "ξ = {xi}");
        let plant = run.summary.max_deformation_m;
        let (onset, _) = model.onset_deflection(xi, &intact);
        println!(
            "ξ = {xi}: plant {:.3} mm, δ* {:.3} mm, ratio {:.3}",
            plant * 1e3,
            onset * 1e3,
            plant / onset
        );
        deflections.push((plant, onset));
    }
    let (first, last) = (deflections[0], deflections[deflections.len() - 1]);
    assert!(
        first.0 / last.0 > 1.8,
        "the plant's falls by about half: {deflections:?}"
    );
    assert!(
        first.1 / last.1 > 1.8,
        "δ* falls by about half: {deflections:?}"
    );
    let r: Vec<f64> = deflections.iter().map(|(p, d)| p / d).collect();
    let (lo, hi) = r
        .iter()
        .fold((f64::MAX, 0.0f64), |(l, h), &x| (l.min(x), h.max(x)));
    assert!(hi / lo < 1.05, "plant / δ* {r:?}");
}
