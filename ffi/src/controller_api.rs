//! `shearcut_controller_*`: the controller in a foreign servo loop.

use std::ffi::{CString, c_char};

use shearcut_controllers::controller::Controller;

use crate::arm_mirror::{ShearcutCommand, ShearcutReading};
use crate::boundary::{CallError, guarded, non_null, non_null_mut};
use crate::cut_setup::CutSetup;
use crate::setup_api::{ShearcutSetup, not_poisoned};
use crate::status::ShearcutStatus;
use crate::telemetry_mirror::ShearcutTelemetry;

/// A knife controller (opaque). Made by `shearcut_controller_new`, freed by
/// `shearcut_controller_free`. One thread at a time may use it.
pub struct ShearcutController {
    setup: CutSetup,
    controller: Box<dyn Controller>,
    name: CString,
    /// Set while a tick runs: still set afterwards only if it panicked.
    poisoned: bool,
}

impl std::fmt::Debug for ShearcutController {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ShearcutController")
            .field("name", &self.name)
            .field("poisoned", &self.poisoned)
            .finish_non_exhaustive()
    }
}

impl ShearcutController {
    fn made(setup: &CutSetup) -> Result<Self, CallError> {
        let controller = setup
            .controller()
            .map_err(|e| CallError::new((&e).into(), e.to_string()))?;
        let name = CString::new(controller.name()).unwrap_or_default();
        Ok(Self {
            setup: setup.clone(),
            controller,
            name,
            poisoned: false,
        })
    }
}

/// Makes the setup's controller, as `shearcut run` makes it (the MPC starts
/// its planner thread here).
///
/// # Safety
/// `setup` must come from `shearcut_setup_new` and not be freed; `out` must
/// be a valid pointer to write to.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn shearcut_controller_new(
    setup: *const ShearcutSetup,
    out: *mut *mut ShearcutController,
) -> ShearcutStatus {
    guarded("shearcut_controller_new", || {
        // SAFETY: the caller's contract.
        let setup = unsafe { non_null(setup, "setup") }?;
        // SAFETY: the caller's contract.
        let out = unsafe { non_null_mut(out, "out") }?;
        *out = Box::into_raw(Box::new(ShearcutController::made(&setup.setup)?));
        Ok(())
    })
}

/// One servo tick: the arm's latest reading in, the command for the next
/// tick out (`SHEARCUT_STATUS_OK`), exactly `Controller::tick`.
///
/// Allocates nothing and never solves: the MPC's plans are made on its
/// planner thread. With the MPC's default `[controller.mpc.planner]
/// latency = "lockstep"`, the tick at which a plan is due waits for it (so
/// runs are bit-identical); with `"realtime"` no tick ever waits (a real
/// arm's loop).
///
/// # Safety
/// `controller` must come from `shearcut_controller_new` and not be freed
/// or used by another thread during the call; `reading` must point to a
/// valid reading; `command` must be a valid pointer to write to.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn shearcut_controller_tick(
    controller: *mut ShearcutController,
    reading: *const ShearcutReading,
    command: *mut ShearcutCommand,
) -> ShearcutStatus {
    guarded("shearcut_controller_tick", || {
        // SAFETY: the caller's contract.
        let c = unsafe { non_null_mut(controller, "controller") }?;
        // SAFETY: the caller's contract.
        let reading = unsafe { non_null(reading, "reading") }?;
        // SAFETY: the caller's contract.
        let command = unsafe { non_null_mut(command, "command") }?;
        not_poisoned(c.poisoned, "controller")?;
        let arm = reading.to_arm().map_err(|code| {
            CallError::new(
                ShearcutStatus::InvalidArgument,
                format!("reading.status = {code}: not one of SHEARCUT_ARM_* (0 to 4)"),
            )
        })?;
        c.poisoned = true;
        let answer = c.controller.tick(&arm);
        c.poisoned = false;
        *command = ShearcutCommand::from(&answer);
        Ok(())
    })
}

/// What the controller's last tick planned.
///
/// # Safety
/// `controller` must come from `shearcut_controller_new` and not be freed;
/// `out` must be a valid pointer to write to.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn shearcut_controller_telemetry(
    controller: *const ShearcutController,
    out: *mut ShearcutTelemetry,
) -> ShearcutStatus {
    guarded("shearcut_controller_telemetry", || {
        // SAFETY: the caller's contract.
        let c = unsafe { non_null(controller, "controller") }?;
        // SAFETY: the caller's contract.
        let out = unsafe { non_null_mut(out, "out") }?;
        not_poisoned(c.poisoned, "controller")?;
        *out = ShearcutTelemetry::from(&c.controller.telemetry());
        Ok(())
    })
}

/// The controller's short name (e.g. `"mpc"`, `"slice:0.75"`); valid until
/// the controller is reset or freed. NULL if `controller` is NULL.
///
/// # Safety
/// `controller` must be NULL or come from `shearcut_controller_new` and
/// not be freed.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn shearcut_controller_name(
    controller: *const ShearcutController,
) -> *const c_char {
    // SAFETY: the caller's contract.
    match unsafe { controller.as_ref() } {
        Some(c) => c.name.as_ptr(),
        None => std::ptr::null(),
    }
}

/// Replaces the controller by a fresh one from its setup, as before its
/// first tick (clears a poisoned state). Allocates; not for the servo tick.
///
/// # Safety
/// `controller` must come from `shearcut_controller_new`, not be freed and
/// not be used by another thread during the call.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn shearcut_controller_reset(
    controller: *mut ShearcutController,
) -> ShearcutStatus {
    guarded("shearcut_controller_reset", || {
        // SAFETY: the caller's contract.
        let c = unsafe { non_null_mut(controller, "controller") }?;
        let fresh = ShearcutController::made(&c.setup)?;
        *c = fresh;
        Ok(())
    })
}

/// Frees a controller (NULL: nothing happens); the MPC's planner thread is
/// joined.
///
/// # Safety
/// `controller` must be NULL or come from `shearcut_controller_new`, and
/// not be used after this call.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn shearcut_controller_free(controller: *mut ShearcutController) {
    if controller.is_null() {
        return;
    }
    let _ = guarded("shearcut_controller_free", || {
        // SAFETY: the caller's contract: a pointer from Box::into_raw,
        // freed once.
        drop(unsafe { Box::from_raw(controller) });
        Ok(())
    });
}
