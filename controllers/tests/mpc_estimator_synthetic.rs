//! The scale-factor estimator on synthetic measurements made by the fitted
//! surrogate itself (`potato-cuboid-straight`) at scaled factors, with what
//! the full plant adds that the model does not: the touch lagging the first
//! tick in contact (an offset of the indentation's forces), and after the
//! first fracture the crack's jumps, a ±30 % sawtooth on the forces. The
//! model is exact here — including the wedge's dependence on E/R_c, which
//! makes the forces nonlinear in the factors (the estimator takes the parts
//! at its estimate's ratio) — so the estimator must recover the factors
//! closely (1 %); on the full plant the model's own error adds to this
//! (`mpc_estimator_plants.rs`).

use std::path::Path;

use shearcut_controllers::mpc::{ScaleEstimator, SliceModel, StageState, SurrogateModel};
use shearcut_sim::surrogate::Surrogate;

/// Servo period, s.
const PERIOD: f64 = 1e-3;
/// Normal speed, m/s.
const SPEED: f64 = 0.05;
/// Knife travel per tick, m.
const STEP: f64 = SPEED * PERIOD;
/// Edge in contact, m.
const CONTACT: f64 = 0.03;
/// Indentation at the first fracture, m (the plant's: 3–5 ticks).
const ONSET: f64 = 0.2e-3;
/// Crack depth after the first fracture at which the rows start (the
/// controller's settling depth), m.
const SETTLE: f64 = 2e-3;
/// Depth of the cut, m.
const DEPTH: f64 = 0.02;
/// Crack advance per jump, m (not a whole number of ticks, so that the
/// ticks sample the sawtooth evenly), and the sawtooth's amplitude.
const JUMP: f64 = 0.37e-3;
const SAWTOOTH: f64 = 0.3;

fn model() -> SurrogateModel {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../config/surrogates/potato-cuboid-straight.toml");
    SurrogateModel::new(Surrogate::from_path(&path).unwrap())
}

fn state(depth: f64, fractured: bool, since: f64) -> StageState {
    StageState {
        depth,
        height: 0.025,
        half_width: 0.015,
        fractured,
        travel_since_fracture: since,
    }
}

/// The model's normal and tangential forces per unit length at `truth`.
fn forces(model: &SurrogateModel, xi: f64, state: &StageState, truth: [f64; 3]) -> [f64; 2] {
    model
        .force_model(xi, state, truth)
        .unwrap()
        .map(|f| f.value)
}

/// Runs a synthetic cut at slice-push ratio `xi(depth)` through material
/// `truth` (toughness, stiffness, friction) and returns the estimate.
fn estimate(model: &SurrogateModel, truth: [f64; 3], xi: impl Fn(f64) -> f64) -> ScaleEstimator {
    let mut e = ScaleEstimator::new(1.0, 1.0, 0.05);
    // The edge touched 40 % of a tick before the first tick in contact:
    // the plant is that much deeper than the knife's travel says.
    let lag = 0.4 * STEP;
    let mut travel = 0.0;
    while travel + lag < ONSET {
        let x = xi(travel);
        let seen = model
            .force_model(x, &state(travel, false, 0.0), e.factors())
            .unwrap();
        let measured = forces(model, x, &state(travel + lag, false, 0.0), truth);
        e.observe_indentation(CONTACT, measured, seen, 0.0);
        travel += STEP;
    }
    e.freeze_stiffness();
    let mut depth = travel + SETTLE;
    while depth < DEPTH {
        let x = xi(depth);
        let since = depth - travel;
        let now = state(depth, true, since);
        let seen = model.force_model(x, &now, e.factors()).unwrap();
        // Zero-mean sawtooth in the crack's advance.
        let phase = (depth / JUMP).fract();
        let jump = 1.0 + SAWTOOTH * (2.0 * phase - 1.0);
        let [n, t] = forces(model, x, &now, truth);
        e.observe_cut([Some(jump * n), Some(jump * t)], seen);
        depth += STEP;
    }
    e
}

const PLANTS: [[f64; 3]; 5] = [
    [1.0, 1.0, 1.0],
    [1.3, 0.7, 1.0],
    [0.7, 1.3, 1.0],
    [1.0, 1.0, 1.3],
    [1.0, 1.0, 0.7],
];

#[test]
fn the_factors_are_recovered_within_1_percent_from_model_made_forces() {
    let model = model();
    for truth in PLANTS {
        // The MPC's plans vary ξ by ±0.1 or so over a cut.
        let e = estimate(&model, truth, |d| 0.65 + 0.1 * (d / 0.004).sin());
        let got = [e.toughness(), e.stiffness(), e.friction()];
        for k in 0..3 {
            assert!(
                (got[k] / truth[k] - 1.0).abs() < 0.01,
                "truth {truth:?}: estimated {got:?}"
            );
        }
    }
}
