//! Through the C ABI, the MPC's tick and the plant's step allocate nothing
//! on the calling thread over the whole main job's cut
//! (`loop-potato-whole-realtime`), counted by the workspace's shared
//! counting allocator (its own test binary; only this thread counts: the
//! MPC's planner thread, where clarabel allocates per solve, and the
//! plant's section builders are not tracked).

use std::ffi::CString;
use std::ptr::null_mut;
use std::sync::atomic::Ordering;

use shearcut_ffi::*;

#[path = "../../controllers/tests/support/counting_allocator.rs"]
mod counting_allocator;

use counting_allocator::{ALLOCATIONS, Counting, TRACK};

#[global_allocator]
static GLOBAL: Counting = Counting;

#[test]
fn ticks_and_steps_through_the_c_abi_allocate_nothing() {
    let scenario = CString::new("loop-potato-whole-realtime").unwrap();
    let choice = CString::new("mpc").unwrap();
    let (mut setup, mut controller, mut plant) = (null_mut(), null_mut(), null_mut());
    let mut task = ShearcutTask::default();
    // SAFETY: valid strings, live handles and valid pointers; each handle
    // freed once at the end.
    unsafe {
        assert_eq!(
            shearcut_setup_new(scenario.as_ptr(), choice.as_ptr(), &mut setup),
            ShearcutStatus::Ok
        );
        assert_eq!(shearcut_setup_task(setup, &mut task), ShearcutStatus::Ok);
        assert_eq!(
            shearcut_controller_new(setup, &mut controller),
            ShearcutStatus::Ok
        );
        assert_eq!(shearcut_plant_new(setup, &mut plant), ShearcutStatus::Ok);
        let mut command = ShearcutCommand::default();
        let mut reading = ShearcutReading::default();
        let mut truth = ShearcutTruth::default();
        let mut telemetry = ShearcutTelemetry::default();
        let mut ticks = 0u64;
        let mut plans = 0u64;
        let ok = ShearcutStatus::Ok;
        ALLOCATIONS.store(0, Ordering::SeqCst);
        TRACK.with(|t| t.set(true));
        // (A passing assert_eq! allocates nothing; a failing one ends the test.)
        assert_eq!(
            shearcut_plant_step(plant, &command, &mut reading, &mut truth),
            ok
        );
        while ticks < task.max_ticks && truth.crack_depth < task.target_depth {
            assert_eq!(
                shearcut_controller_tick(controller, &reading, &mut command),
                ok
            );
            assert_eq!(
                shearcut_controller_telemetry(controller, &mut telemetry),
                ok
            );
            plans += u64::from(telemetry.planned);
            ticks += 1;
            assert_eq!(
                shearcut_plant_step(plant, &command, &mut reading, &mut truth),
                ok
            );
        }
        TRACK.with(|t| t.set(false));
        let allocations = ALLOCATIONS.load(Ordering::SeqCst);
        assert!(truth.crack_depth >= task.target_depth, "the cut completed");
        assert!(plans > 10, "the MPC planned along the way ({plans} plans)");
        assert_eq!(allocations, 0, "allocations over {ticks} ticks");
        shearcut_controller_free(controller);
        shearcut_plant_free(plant);
        shearcut_setup_free(setup);
    }
}
