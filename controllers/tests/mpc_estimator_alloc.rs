//! Proves that the scale-factor estimator's work in a tick — the model's
//! force parts and the indentation and cut rows — allocates nothing, with a
//! counting global allocator (its own test binary). The MPC's tick with
//! `estimate` on adds exactly this to the tick `controller_alloc.rs` counts.
#![allow(unsafe_code)] // GlobalAlloc is an unsafe trait; the impl only forwards to System.

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::sync::atomic::{AtomicUsize, Ordering};

use std::path::Path;

use shearcut_controllers::mpc::{ScaleEstimator, SliceModel, StageState, SurrogateModel};
use shearcut_sim::surrogate::Surrogate;

struct Counting;

static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

thread_local! {
    /// Only the measuring thread's allocations count.
    static TRACK: Cell<bool> = const { Cell::new(false) };
}

fn count() {
    if TRACK.try_with(Cell::get).unwrap_or(false) {
        ALLOCATIONS.fetch_add(1, Ordering::SeqCst);
    }
}

// SAFETY: every call is forwarded unchanged to the system allocator.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        count();
        // SAFETY: same contract as the caller's.
        unsafe { System.alloc(layout) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: same contract as the caller's.
        unsafe { System.dealloc(ptr, layout) }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        count();
        // SAFETY: same contract as the caller's.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

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
        let (n, t) = model.force_parts(0.7, &state(depth, fractured)).unwrap();
        let f = [n.iter().sum::<f64>(), t.iter().sum::<f64>()];
        if fractured {
            e.observe_cut([Some(f[0]), Some(f[1])], (n, t));
        } else {
            e.observe_indentation(0.03, f, (n, t));
        }
    }
    TRACK.with(|t| t.set(false));
    assert_eq!(ALLOCATIONS.load(Ordering::SeqCst), 0);
    assert!(e.updates() > 700, "{} rows", e.updates());
}
