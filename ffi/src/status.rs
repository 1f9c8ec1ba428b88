//! What every fallible entry point of the C ABI returns.

use crate::cut_setup::EmbedError;

/// The outcome of a call. `SHEARCUT_STATUS_OK` is 0; on any other status
/// the call changed none of its outputs, and `shearcut_last_error()` gives
/// one line saying why (on the calling thread, until its next failing call).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ShearcutStatus {
    /// Success.
    Ok = 0,
    /// A required pointer argument was null.
    NullArgument = 1,
    /// An argument is malformed: a string that is not UTF-8, an unknown
    /// arm status code.
    InvalidArgument = 2,
    /// The scenario or the controller choice is unusable (the message
    /// names the file, the key, the value and what is allowed).
    Config = 3,
    /// The simulated plant's model failed (a section could not be solved
    /// or built); the plant is unusable until `shearcut_plant_reset`.
    Model = 4,
    /// shearcut panicked inside the call; the panic was caught at the
    /// boundary and the handle is poisoned until it is reset.
    Panic = 5,
    /// The handle is poisoned by an earlier panic or model failure: reset
    /// it (`shearcut_controller_reset`, `shearcut_plant_reset`) or free it.
    Poisoned = 6,
}

impl From<&EmbedError> for ShearcutStatus {
    fn from(e: &EmbedError) -> Self {
        match e {
            EmbedError::Config(_) => Self::Config,
            EmbedError::Model(_) => Self::Model,
        }
    }
}
