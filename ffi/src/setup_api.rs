//! `shearcut_setup_*`: a scenario and a controller choice, set up once;
//! controllers and plants are made from it.

use std::ffi::c_char;

use crate::boundary::{CallError, guarded, non_null, non_null_mut, utf8};
use crate::cut_setup::CutSetup;
use crate::status::ShearcutStatus;
use crate::task_mirror::ShearcutTask;

/// A scenario set up for one controller (opaque). Made by
/// `shearcut_setup_new`, freed by `shearcut_setup_free`; controllers and
/// plants made from it keep their own copy, so it may be freed first.
#[derive(Debug)]
pub struct ShearcutSetup {
    pub(crate) setup: CutSetup,
}

/// Loads `scenario` (a TOML path, or a built-in scenario's name such as
/// `"loop-potato-whole-realtime"`) and sets it up for `controller`
/// (`"mpc"`, `"press"`, `"slice:XI"`, `"force:N"`; NULL: the scenario's
/// `[controller] kind`). Builds what `shearcut run` builds before its loop
/// (for the MPC its view of the object: up to about a second).
///
/// On `SHEARCUT_STATUS_OK`, `*out` holds the new setup.
///
/// # Safety
/// `scenario` must be a NUL-terminated string; `controller` NULL or a
/// NUL-terminated string; `out` a valid pointer to write to.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn shearcut_setup_new(
    scenario: *const c_char,
    controller: *const c_char,
    out: *mut *mut ShearcutSetup,
) -> ShearcutStatus {
    guarded("shearcut_setup_new", || {
        // SAFETY: the caller's contract.
        let scenario = unsafe { utf8(scenario, "scenario") }?;
        let controller = if controller.is_null() {
            None
        } else {
            // SAFETY: non-null, the caller's contract.
            Some(unsafe { utf8(controller, "controller") }?)
        };
        // SAFETY: the caller's contract.
        let out = unsafe { non_null_mut(out, "out") }?;
        let setup = CutSetup::load(scenario, controller)
            .map_err(|e| CallError::new((&e).into(), e.to_string()))?;
        *out = Box::into_raw(Box::new(ShearcutSetup { setup }));
        Ok(())
    })
}

/// The cut the setup's controller is told, and the simulated loop's limits.
///
/// # Safety
/// `setup` must come from `shearcut_setup_new` and not be freed; `out`
/// must be a valid pointer to write to.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn shearcut_setup_task(
    setup: *const ShearcutSetup,
    out: *mut ShearcutTask,
) -> ShearcutStatus {
    guarded("shearcut_setup_task", || {
        // SAFETY: the caller's contract.
        let setup = unsafe { non_null(setup, "setup") }?;
        // SAFETY: the caller's contract.
        let out = unsafe { non_null_mut(out, "out") }?;
        *out = ShearcutTask::from(&setup.setup);
        Ok(())
    })
}

/// Frees a setup (NULL: nothing happens).
///
/// # Safety
/// `setup` must be NULL or come from `shearcut_setup_new`, and not be used
/// after this call.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn shearcut_setup_free(setup: *mut ShearcutSetup) {
    if setup.is_null() {
        return;
    }
    let _ = guarded("shearcut_setup_free", || {
        // SAFETY: the caller's contract: a pointer from Box::into_raw,
        // freed once.
        drop(unsafe { Box::from_raw(setup) });
        Ok(())
    });
}

/// Checks a handle's poison flag.
pub(crate) fn not_poisoned(poisoned: bool, what: &str) -> Result<(), CallError> {
    if poisoned {
        Err(CallError::new(
            ShearcutStatus::Poisoned,
            format!("the {what} failed earlier (panic or model failure): reset or free it"),
        ))
    } else {
        Ok(())
    }
}
