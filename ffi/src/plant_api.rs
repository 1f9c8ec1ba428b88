//! `shearcut_plant_*`: the simulated plant, so that a foreign loop can
//! close the loop in simulation before it meets a real arm.

use crate::arm_mirror::{ShearcutCommand, ShearcutReading};
use crate::boundary::{CallError, guarded, non_null, non_null_mut};
use crate::cut_setup::CutSetup;
use crate::setup_api::{ShearcutSetup, not_poisoned};
use crate::simulated_plant::SimulatedPlant;
use crate::status::ShearcutStatus;
use crate::truth_mirror::ShearcutTruth;

/// The simulated plant (opaque): the arm, its F/T sensor and the object.
/// Made by `shearcut_plant_new`, freed by `shearcut_plant_free`. One
/// thread at a time may use it.
#[derive(Debug)]
pub struct ShearcutPlant {
    setup: CutSetup,
    plant: SimulatedPlant,
    /// Set while a step runs: still set afterwards if it failed or
    /// panicked.
    poisoned: bool,
}

impl ShearcutPlant {
    fn made(setup: &CutSetup) -> Result<Self, CallError> {
        let plant = setup
            .plant()
            .map_err(|e| CallError::new((&e).into(), e.to_string()))?;
        Ok(Self {
            setup: setup.clone(),
            plant,
            poisoned: false,
        })
    }
}

/// Makes the setup's simulated plant, the knife at rest at its start above
/// the object (`ShearcutTask::start_position`), as `shearcut run` makes it.
///
/// # Safety
/// `setup` must come from `shearcut_setup_new` and not be freed; `out` must
/// be a valid pointer to write to.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn shearcut_plant_new(
    setup: *const ShearcutSetup,
    out: *mut *mut ShearcutPlant,
) -> ShearcutStatus {
    guarded("shearcut_plant_new", || {
        // SAFETY: the caller's contract.
        let setup = unsafe { non_null(setup, "setup") }?;
        // SAFETY: the caller's contract.
        let out = unsafe { non_null_mut(out, "out") }?;
        *out = Box::into_raw(Box::new(ShearcutPlant::made(&setup.setup)?));
        Ok(())
    })
}

/// Executes `command` for one servo period (`ShearcutTask::period`): the
/// arm checks it against its limits by finite differences (a refused
/// command leaves the knife still; the reading's status says which limit),
/// the model advances, the F/T sensor is sampled. Writes the arm's reading
/// to `reading` and, if `truth` is not NULL, the simulated ground truth.
///
/// Allocates nothing on the calling thread. A model failure returns
/// `SHEARCUT_STATUS_MODEL` and poisons the plant.
///
/// # Safety
/// `plant` must come from `shearcut_plant_new`, not be freed and not be
/// used by another thread during the call; `command` must point to a
/// valid command; `reading` must be a valid pointer to write to; `truth`
/// NULL or a valid pointer to write to.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn shearcut_plant_step(
    plant: *mut ShearcutPlant,
    command: *const ShearcutCommand,
    reading: *mut ShearcutReading,
    truth: *mut ShearcutTruth,
) -> ShearcutStatus {
    guarded("shearcut_plant_step", || {
        // SAFETY: the caller's contract.
        let p = unsafe { non_null_mut(plant, "plant") }?;
        // SAFETY: the caller's contract.
        let command = unsafe { non_null(command, "command") }?;
        // SAFETY: the caller's contract.
        let reading = unsafe { non_null_mut(reading, "reading") }?;
        // SAFETY: the caller's contract (NULL allowed).
        let truth = unsafe { truth.as_mut() };
        not_poisoned(p.poisoned, "plant")?;
        p.poisoned = true;
        let step = p
            .plant
            .step(&command.into())
            .map_err(|e| CallError::new((&e).into(), e.to_string()))?;
        p.poisoned = false;
        *reading = ShearcutReading::from(&step.reading);
        if let Some(truth) = truth {
            *truth = ShearcutTruth::from(&step.truth);
        }
        Ok(())
    })
}

/// Replaces the plant by a fresh one from its setup: the knife back at its
/// start, the object intact, the sensor's noise restarted from the
/// scenario's seed (clears a poisoned state). Allocates; not for the
/// servo tick.
///
/// # Safety
/// `plant` must come from `shearcut_plant_new`, not be freed and not be
/// used by another thread during the call.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn shearcut_plant_reset(plant: *mut ShearcutPlant) -> ShearcutStatus {
    guarded("shearcut_plant_reset", || {
        // SAFETY: the caller's contract.
        let p = unsafe { non_null_mut(plant, "plant") }?;
        let fresh = ShearcutPlant::made(&p.setup)?;
        *p = fresh;
        Ok(())
    })
}

/// Frees a plant (NULL: nothing happens).
///
/// # Safety
/// `plant` must be NULL or come from `shearcut_plant_new`, and not be used
/// after this call.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn shearcut_plant_free(plant: *mut ShearcutPlant) {
    if plant.is_null() {
        return;
    }
    let _ = guarded("shearcut_plant_free", || {
        // SAFETY: the caller's contract: a pointer from Box::into_raw,
        // freed once.
        drop(unsafe { Box::from_raw(plant) });
        Ok(())
    });
}
