//! The C ABI's contract at the boundary, called as C would call it: null
//! pointers and malformed input are refused with a status and a one-line
//! last error, outputs stay untouched on failure, handles are freed once
//! and NULL frees are no-ops.

use std::ffi::{CStr, CString};
use std::ptr::{null, null_mut};

use shearcut_ffi::*;

fn last_error() -> String {
    // SAFETY: never null; valid until the next failing call on this thread.
    unsafe { CStr::from_ptr(shearcut_last_error()) }
        .to_string_lossy()
        .into_owned()
}

fn setup(scenario: &str, controller: Option<&str>) -> Result<*mut ShearcutSetup, ShearcutStatus> {
    let scenario = CString::new(scenario).unwrap();
    let controller = controller.map(|c| CString::new(c).unwrap());
    let mut out = null_mut();
    // SAFETY: valid strings and out-pointer.
    let status = unsafe {
        shearcut_setup_new(
            scenario.as_ptr(),
            controller.as_ref().map_or(null(), |c| c.as_ptr()),
            &mut out,
        )
    };
    if status == ShearcutStatus::Ok {
        Ok(out)
    } else {
        assert!(out.is_null(), "a failed call leaves its output alone");
        Err(status)
    }
}

#[test]
fn the_version_is_the_crates() {
    // SAFETY: a static NUL-terminated string.
    let v = unsafe { CStr::from_ptr(shearcut_version()) };
    assert_eq!(v.to_str().unwrap(), env!("CARGO_PKG_VERSION"));
}

#[test]
fn a_bad_scenario_is_a_config_status_naming_the_file() {
    assert_eq!(
        setup("/nonexistent/cut.toml", None).unwrap_err(),
        ShearcutStatus::Config
    );
    let e = last_error();
    assert!(e.starts_with("shearcut_setup_new: "), "{e}");
    assert!(e.contains("/nonexistent/cut.toml"), "{e}");
}

#[test]
fn a_bad_controller_is_a_config_status_listing_the_choices() {
    assert_eq!(
        setup("loop-potato-cuboid", Some("pid")).unwrap_err(),
        ShearcutStatus::Config
    );
    assert!(last_error().contains("slice:XI"), "{}", last_error());
    // A ratio or setpoint the command line refuses is refused here too.
    for (text, named) in [
        ("slice:1e6", "slice ratio"),
        ("force:1e9", "force setpoint"),
    ] {
        assert_eq!(
            setup("loop-potato-cuboid", Some(text)).unwrap_err(),
            ShearcutStatus::Config
        );
        assert!(last_error().contains(named), "{}", last_error());
    }
}

#[test]
fn null_pointers_are_refused_by_name() {
    let mut out = null_mut();
    // SAFETY: null is what is being tested; the functions check it.
    unsafe {
        assert_eq!(
            shearcut_setup_new(null(), null(), &mut out),
            ShearcutStatus::NullArgument
        );
        assert!(last_error().contains("`scenario`"));
        let name = CString::new("loop-potato-cuboid").unwrap();
        assert_eq!(
            shearcut_setup_new(name.as_ptr(), null(), null_mut()),
            ShearcutStatus::NullArgument
        );
        assert!(last_error().contains("`out`"));
        let mut command = ShearcutCommand::default();
        assert_eq!(
            shearcut_controller_tick(null_mut(), &ShearcutReading::default(), &mut command),
            ShearcutStatus::NullArgument
        );
        assert_eq!(
            shearcut_plant_step(null_mut(), &command, null_mut(), null_mut()),
            ShearcutStatus::NullArgument
        );
        assert!(shearcut_controller_name(null()).is_null());
        // Freeing NULL is a no-op.
        shearcut_setup_free(null_mut());
        shearcut_controller_free(null_mut());
        shearcut_plant_free(null_mut());
    }
}

#[test]
fn a_reading_with_an_unknown_status_is_refused_and_the_command_kept() {
    let s = setup("loop-potato-cuboid", Some("press")).unwrap();
    let mut controller = null_mut();
    // SAFETY: live handles, valid pointers; freed once at the end.
    unsafe {
        assert_eq!(
            shearcut_controller_new(s, &mut controller),
            ShearcutStatus::Ok
        );
        let name = CStr::from_ptr(shearcut_controller_name(controller));
        assert_eq!(name.to_str().unwrap(), "press");
        let reading = ShearcutReading {
            status: 7,
            ..ShearcutReading::default()
        };
        let mut command = ShearcutCommand {
            velocity: [1.0, 2.0, 3.0],
        };
        assert_eq!(
            shearcut_controller_tick(controller, &reading, &mut command),
            ShearcutStatus::InvalidArgument
        );
        assert!(last_error().contains("reading.status = 7"));
        assert_eq!(command.velocity, [1.0, 2.0, 3.0]);
        shearcut_controller_free(controller);
        shearcut_setup_free(s);
    }
}

#[test]
fn the_plant_reports_the_arms_refusal_and_resets_to_its_start() {
    let s = setup("loop-potato-cuboid", Some("press")).unwrap();
    let mut plant = null_mut();
    let mut task = ShearcutTask::default();
    // SAFETY: live handles, valid pointers; freed once at the end.
    unsafe {
        assert_eq!(shearcut_setup_task(s, &mut task), ShearcutStatus::Ok);
        assert_eq!(shearcut_plant_new(s, &mut plant), ShearcutStatus::Ok);
        // The setup may go first: the plant keeps its own copy.
        shearcut_setup_free(s);
        let mut reading = ShearcutReading::default();
        let mut truth = ShearcutTruth::default();
        let rest = ShearcutCommand::default();
        assert_eq!(
            shearcut_plant_step(plant, &rest, &mut reading, &mut truth),
            ShearcutStatus::Ok
        );
        assert_eq!(reading.status, SHEARCUT_ARM_MOVING);
        assert_eq!(reading.position, task.start_position);
        // 0 -> 1 m/s down in one period: 1000 m/s² by finite differences,
        // above the default arm's 9 m/s² (Franka FR3); the knife holds.
        let lunge = ShearcutCommand {
            velocity: [0.0, -1.0, 0.0],
        };
        assert_eq!(
            shearcut_plant_step(plant, &lunge, &mut reading, null_mut()),
            ShearcutStatus::Ok
        );
        assert_eq!(reading.status, SHEARCUT_ARM_ACCELERATION_LIMIT);
        assert!((reading.violation - 1.0 / task.period).abs() < 1e-9 / task.period);
        assert_eq!(reading.position, task.start_position);
        assert_eq!(shearcut_plant_reset(plant), ShearcutStatus::Ok);
        assert_eq!(
            shearcut_plant_step(plant, &rest, &mut reading, &mut truth),
            ShearcutStatus::Ok
        );
        assert_eq!(reading.time, task.period);
        assert_eq!(truth.work, 0.0);
        shearcut_plant_free(plant);
    }
}
