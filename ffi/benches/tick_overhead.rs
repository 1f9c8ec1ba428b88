//! The cost of one controller tick through the C ABI against the same call
//! in Rust: `shearcut_controller_tick` (null checks, `catch_unwind`, the
//! reading's and command's `#[repr(C)]` conversions) over
//! `Controller::tick` on the same controller kind and reading.
//!
//! `cargo bench -p shearcut-ffi --bench tick_overhead [-- BATCHES]`
//!
//! The controller is `slice:0.5` on the main job's scenario: its tick is a
//! few tens of nanoseconds, so the boundary's share shows (the MPC's tick
//! is the same boundary around a longer body, and its lockstep plan waits
//! would dominate a benchmark like this one). The reading is the knife at
//! rest at its start in free air, repeated; each controller's shaper keeps
//! ramping towards its velocity as over the first ticks of a cut.
//!
//! On a shared machine the load drifts over seconds, so the two calls are
//! timed in alternating batches of 1000 calls (the order swapped every
//! batch) and compared batch by batch: the printed overhead is the median
//! of the per-batch differences, with the p99 and the maximum of each side.
//! A batch takes tens of microseconds; on a loaded machine about one in
//! 25 is preempted for a scheduler slice (4–12 ms over its 1000 calls),
//! which is what the p99 and maximum show.

use std::ffi::CString;
use std::hint::black_box;
use std::ptr::null_mut;
use std::time::Instant;

use shearcut_ffi::{
    CutSetup, ShearcutCommand, ShearcutReading, ShearcutStatus, shearcut_controller_free,
    shearcut_controller_new, shearcut_controller_tick, shearcut_setup_free, shearcut_setup_new,
};
use shearcut_sim::arm::ArmReading;

const SCENARIO: &str = "loop-potato-whole-realtime";
const CONTROLLER: &str = "slice:0.5";
const CALLS: u32 = 1000;

/// Median, p99 and maximum of `xs` (sorted in place).
fn stats(xs: &mut [f64]) -> (f64, f64, f64) {
    xs.sort_by(f64::total_cmp);
    let at = |q: f64| xs[((xs.len() - 1) as f64 * q).round() as usize];
    (at(0.5), at(0.99), xs[xs.len() - 1])
}

#[allow(clippy::disallowed_methods)] // A benchmark reads the wall clock.
fn main() {
    let batches: usize = std::env::args()
        .skip(1)
        .find_map(|a| a.parse().ok())
        .unwrap_or(2000);
    let setup = CutSetup::load(SCENARIO, Some(CONTROLLER)).unwrap();
    let arm = ArmReading::at_rest(0.0, setup.cut().start);
    let reading = ShearcutReading::from(&arm);
    let mut rust = setup.controller().unwrap();

    let scenario = CString::new(SCENARIO).unwrap();
    let choice = CString::new(CONTROLLER).unwrap();
    let (mut c_setup, mut controller) = (null_mut(), null_mut());
    // SAFETY: valid C strings and out-pointers; the handles are freed below.
    unsafe {
        assert_eq!(
            shearcut_setup_new(scenario.as_ptr(), choice.as_ptr(), &mut c_setup),
            ShearcutStatus::Ok
        );
        assert_eq!(
            shearcut_controller_new(c_setup, &mut controller),
            ShearcutStatus::Ok
        );
    }
    let mut command = ShearcutCommand::default();
    let mut time_rust = || {
        let started = Instant::now();
        for _ in 0..CALLS {
            black_box(rust.tick(black_box(&arm)));
        }
        started.elapsed().as_secs_f64() * 1e9 / f64::from(CALLS)
    };
    let mut time_c = || {
        let started = Instant::now();
        for _ in 0..CALLS {
            // SAFETY: a live handle and valid pointers.
            let status =
                unsafe { shearcut_controller_tick(controller, black_box(&reading), &mut command) };
            black_box((status, command));
        }
        started.elapsed().as_secs_f64() * 1e9 / f64::from(CALLS)
    };
    for _ in 0..50 {
        time_rust();
        time_c();
    }
    let (mut r, mut c, mut d) = (Vec::new(), Vec::new(), Vec::new());
    for k in 0..batches {
        let (a, b) = if k % 2 == 0 {
            let a = time_rust();
            (a, time_c())
        } else {
            let b = time_c();
            (time_rust(), b)
        };
        r.push(a);
        c.push(b);
        d.push(b - a);
    }
    let (rm, rp, rx) = stats(&mut r);
    let (cm, cp, cx) = stats(&mut c);
    let (dm, dp, _) = stats(&mut d);
    println!("{batches} alternating batches of {CALLS} ticks of {CONTROLLER} ({SCENARIO}):");
    println!("  Rust Controller::tick           median {rm:.1} ns, p99 {rp:.1} ns, max {rx:.1} ns");
    println!("  C ABI shearcut_controller_tick  median {cm:.1} ns, p99 {cp:.1} ns, max {cx:.1} ns");
    println!("  overhead per tick (C - Rust)    median {dm:.1} ns, p99 {dp:.1} ns");
    // SAFETY: handles from the calls above, freed once.
    unsafe {
        shearcut_controller_free(controller);
        shearcut_setup_free(c_setup);
    }
}
