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
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../config/surrogates/potato-cuboid-straight.toml");
    let s = Surrogate::from_path(&path).unwrap();
    let scale = ScaleFactors {
        toughness: 1.1,
        stiffness: 0.9,
        friction: 1.2,
    };
    let mut sum = 0.0;
    let before = ALLOCATIONS.load(Ordering::SeqCst);
    for i in 0..2000 {
        let xi = 0.0015 * i as f64;
        let state = CutState {
            depth: 1e-5 * i as f64,
            height: 0.03,
            half_width: 0.015,
            fractured: i % 2 == 0,
            travel_since_fracture: 5e-6 * i as f64,
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
