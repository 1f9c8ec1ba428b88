//! `Surrogate::evaluate` and `Surrogate::work_quadratic` allocate nothing
//! (counting allocator), before and after fracture.

use std::alloc::{GlobalAlloc, Layout, System};
use std::path::PathBuf;
use std::sync::atomic::{AtomicUsize, Ordering};

use shearcut_sim::surrogate::{CutState, ScaleFactors, Surrogate};

struct Counting;

static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

// Forwards to the system allocator and counts allocations.
#[allow(unsafe_code)]
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::SeqCst);
        // SAFETY: same contract as the caller's.
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: same contract as the caller's.
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::SeqCst);
        // SAFETY: same contract as the caller's.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

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
    let before = ALLOCATIONS.load(Ordering::SeqCst);
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
    let after = ALLOCATIONS.load(Ordering::SeqCst);
    assert!(sum.is_finite());
    assert_eq!(
        after - before,
        0,
        "evaluate allocated {} times",
        after - before
    );
}
