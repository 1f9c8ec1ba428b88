//! `Surrogate::evaluate` and `Surrogate::work_quadratic` allocate nothing,
//! before and after fracture. Both run on the calling thread and start no
//! other, so the calling thread's count is the measurement (the workspace's
//! counting allocator, per thread): the test harness's own threads may
//! allocate meanwhile and are not the code under test.

use std::path::PathBuf;

use shearcut_sim::surrogate::{CutState, ScaleFactors, Surrogate};

#[path = "../../controllers/tests/support/counting_allocator.rs"]
mod counting_allocator;

use counting_allocator::{Counting, thread_allocations};

#[global_allocator]
static GLOBAL: Counting = Counting;

#[test]
fn evaluate_allocates_nothing() {
    // Potato (no catch-up) and whole eggplant (catch-up and knee active).
    let load = |name: &str| {
        let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
            .join(format!("../config/surrogates/{name}-straight.toml"));
        Surrogate::from_path(&path).unwrap()
    };
    let surrogates = [load("potato-cuboid"), load("eggplant-whole")];
    let scale = ScaleFactors {
        toughness: 1.1,
        stiffness: 0.9,
        friction: 1.2,
    };
    let mut sum = 0.0;
    let before = thread_allocations();
    for (i, s) in (0..4000).zip(surrogates.iter().cycle()) {
        let xi = 0.0015 * (i / 2) as f64;
        let state = CutState {
            depth: 1e-5 * (i / 2) as f64,
            height: 0.03,
            half_width: 0.015,
            fractured: i % 4 < 2,
            travel_since_fracture: 5e-6 * (i / 2) as f64,
        };
        let o = s.evaluate(xi, &state, &scale);
        let q = s.work_quadratic(xi, &state, &scale);
        sum += o.force_normal + o.force_tangential_slope + q.curvature;
    }
    let allocated = thread_allocations() - before;
    assert!(sum.is_finite());
    assert_eq!(allocated, 0, "evaluate allocated {allocated} times");
}
