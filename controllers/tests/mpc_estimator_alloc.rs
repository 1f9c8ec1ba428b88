//! Proves that the scale-factor estimator's work in a tick — the model's
//! force parts and the indentation and cut rows — allocates nothing, with a
//! counting global allocator (its own test binary). The MPC's tick with
//! `estimate` on adds exactly this to the tick `controller_alloc.rs` counts.

use std::sync::atomic::Ordering;

use std::path::Path;

use shearcut_controllers::mpc::{ScaleEstimator, SliceModel, StageState, SurrogateModel};
use shearcut_sim::surrogate::Surrogate;

#[path = "support/counting_allocator.rs"]
mod counting_allocator;

use counting_allocator::{ALLOCATIONS, Counting, TRACK};

#[global_allocator]
static GLOBAL: Counting = Counting;

#[test]
fn estimator_ticks_allocate_nothing() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../config/surrogates/potato-cuboid-straight.toml");
    let model = SurrogateModel::new(Surrogate::from_path(&path).unwrap());
    let mut e = ScaleEstimator::new(1.0, 1.0, 0.05);
    let state = |depth: f64, fractured: bool| StageState {
        depth,
        height: 0.025,
        half_width: 0.015,
        fractured,
        travel_since_fracture: (depth - 2e-4).max(0.0),
    };
    ALLOCATIONS.store(0, Ordering::SeqCst);
    TRACK.with(|t| t.set(true));
    for k in 0..400 {
        let depth = k as f64 * 5e-5;
        let fractured = depth > 2e-4;
        let seen = model
            .force_model(0.7, &state(depth, fractured), e.factors())
            .unwrap();
        let f = [1.1 * seen[0].nominal, 0.9 * seen[1].nominal];
        if fractured {
            e.observe_cut([Some(f[0]), Some(f[1])], seen);
        } else {
            e.observe_indentation(0.03, f, seen, 0.01);
        }
    }
    TRACK.with(|t| t.set(false));
    assert_eq!(ALLOCATIONS.load(Ordering::SeqCst), 0);
    assert!(e.updates() > 700, "{} rows", e.updates());
}
