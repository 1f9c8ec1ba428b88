//! The cost of one controller tick through the C ABI against the same call
//! in Rust: `shearcut_controller_tick` (null checks, `catch_unwind`, the
//! reading's and command's `#[repr(C)]` conversions) over
//! `Controller::tick` on the same controller and reading.
//!
//! `cargo bench -p shearcut-ffi --bench tick_overhead`
//!
//! The controller is `slice:0.5` on the main job's scenario: its tick is a
//! few tens of nanoseconds, so the boundary's share shows. The reading is
//! the knife at rest at its start in free air, repeated; the controller's
//! shaper keeps ramping towards its velocity, as it would over the first
//! ticks of a cut. (The MPC's tick is the same boundary around a longer
//! body; its lockstep plan waits would dominate a benchmark like this one.)

use criterion::{Criterion, criterion_main};
use shearcut_ffi::{
    CutSetup, ShearcutCommand, ShearcutController, ShearcutReading, ShearcutSetup, ShearcutStatus,
    shearcut_controller_free, shearcut_controller_new, shearcut_controller_tick,
    shearcut_setup_free, shearcut_setup_new,
};
use shearcut_sim::arm::ArmReading;
use std::hint::black_box;

const SCENARIO: &str = "loop-potato-whole-realtime";
const CONTROLLER: &str = "slice:0.5";

fn tick_overhead(c: &mut Criterion) {
    let setup = CutSetup::load(SCENARIO, Some(CONTROLLER)).unwrap();
    let start = setup.cut().start;
    let arm = ArmReading::at_rest(0.0, start);
    let reading = ShearcutReading::from(&arm);

    let mut group = c.benchmark_group("controller tick");
    let mut rust = setup.controller().unwrap();
    group.bench_function("Rust Controller::tick", |b| {
        b.iter(|| black_box(rust.tick(black_box(&arm))))
    });

    let scenario = std::ffi::CString::new(SCENARIO).unwrap();
    let choice = std::ffi::CString::new(CONTROLLER).unwrap();
    let mut c_setup: *mut ShearcutSetup = std::ptr::null_mut();
    let mut controller: *mut ShearcutController = std::ptr::null_mut();
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
    group.bench_function("C ABI shearcut_controller_tick", |b| {
        b.iter(|| {
            // SAFETY: a live handle and valid pointers.
            let status =
                unsafe { shearcut_controller_tick(controller, black_box(&reading), &mut command) };
            black_box((status, command))
        })
    });
    group.finish();
    // SAFETY: handles from the calls above, freed once.
    unsafe {
        shearcut_controller_free(controller);
        shearcut_setup_free(c_setup);
    }
}

#[allow(missing_docs)]
mod group {
    criterion::criterion_group!(benches, super::tick_overhead);
}
use group::benches;
criterion_main!(benches);
