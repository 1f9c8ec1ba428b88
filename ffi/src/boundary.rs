//! The boundary every entry point crosses: panics caught and turned into
//! [`ShearcutStatus::Panic`], errors into a status and the thread's last
//! error, null pointers refused.

use std::any::Any;
use std::ffi::{CStr, c_char};
use std::panic::{AssertUnwindSafe, catch_unwind};

use crate::last_error::set_last_error;
use crate::status::ShearcutStatus;

/// A failed call: its status and, for the last error, its message. Boxed,
/// so that a call's `Result<(), CallError>` is one pointer wide and the
/// success path (the servo tick's) moves nothing more.
pub(crate) struct CallError(Box<(ShearcutStatus, String)>);

impl CallError {
    /// A failure with `status` saying `message`.
    pub(crate) fn new(status: ShearcutStatus, message: impl Into<String>) -> Self {
        Self(Box::new((status, message.into())))
    }
}

/// Runs `body` with panics caught: `Ok` becomes [`ShearcutStatus::Ok`];
/// an error or a panic sets the thread's last error and returns its
/// status. `what` names the entry point in messages. Allocates nothing
/// on success.
pub(crate) fn guarded(
    what: &'static str,
    body: impl FnOnce() -> Result<(), CallError>,
) -> ShearcutStatus {
    match catch_unwind(AssertUnwindSafe(body)) {
        Ok(Ok(())) => ShearcutStatus::Ok,
        Ok(Err(CallError(e))) => {
            set_last_error(&format!("{what}: {}", e.1));
            e.0
        }
        Err(payload) => {
            set_last_error(&format!(
                "{what}: shearcut panicked: {} (caught at the C boundary)",
                panic_message(payload.as_ref())
            ));
            ShearcutStatus::Panic
        }
    }
}

/// The text of a panic payload.
fn panic_message(payload: &(dyn Any + Send)) -> &str {
    if let Some(s) = payload.downcast_ref::<&str>() {
        s
    } else if let Some(s) = payload.downcast_ref::<String>() {
        s
    } else {
        "(no message)"
    }
}

/// `pointer` as a shared reference, or a [`ShearcutStatus::NullArgument`]
/// error naming `name`.
///
/// # Safety
/// A non-null `pointer` must point to a valid, initialised `T` that
/// nothing mutates for `'a`.
pub(crate) unsafe fn non_null<'a, T>(pointer: *const T, name: &str) -> Result<&'a T, CallError> {
    // SAFETY: the caller guarantees a non-null pointer is valid for 'a.
    unsafe { pointer.as_ref() }.ok_or_else(|| null_argument(name))
}

/// `pointer` as an exclusive reference, or a
/// [`ShearcutStatus::NullArgument`] error naming `name`.
///
/// # Safety
/// A non-null `pointer` must point to a valid `T` that nothing else
/// accesses for `'a`.
pub(crate) unsafe fn non_null_mut<'a, T>(
    pointer: *mut T,
    name: &str,
) -> Result<&'a mut T, CallError> {
    // SAFETY: the caller guarantees a non-null pointer is valid and
    // unaliased for 'a.
    unsafe { pointer.as_mut() }.ok_or_else(|| null_argument(name))
}

/// The UTF-8 text of a C string, or an error naming `name`.
///
/// # Safety
/// A non-null `pointer` must point to a NUL-terminated string valid for
/// `'a`.
pub(crate) unsafe fn utf8<'a>(pointer: *const c_char, name: &str) -> Result<&'a str, CallError> {
    if pointer.is_null() {
        return Err(null_argument(name));
    }
    // SAFETY: non-null, and the caller guarantees NUL termination.
    let text = unsafe { CStr::from_ptr(pointer) };
    text.to_str().map_err(|_| {
        CallError::new(
            ShearcutStatus::InvalidArgument,
            format!("`{name}` is not UTF-8 text"),
        )
    })
}

fn null_argument(name: &str) -> CallError {
    CallError::new(
        ShearcutStatus::NullArgument,
        format!("`{name}` is a null pointer"),
    )
}

#[cfg(test)]
mod tests {
    use std::ffi::CStr;

    use super::*;
    use crate::last_error::shearcut_last_error;

    fn last_error() -> String {
        // SAFETY: shearcut_last_error never returns null and the text lives
        // until the next failing call on this thread.
        unsafe { CStr::from_ptr(shearcut_last_error()) }
            .to_string_lossy()
            .into_owned()
    }

    #[test]
    fn a_panic_becomes_a_status_and_a_message() {
        let status = guarded("shearcut_test", || panic!("the knife broke"));
        assert_eq!(status, ShearcutStatus::Panic);
        let message = last_error();
        assert!(message.starts_with("shearcut_test: shearcut panicked: the knife broke"));
    }

    #[test]
    fn an_error_keeps_its_status_and_names_the_call() {
        let status = guarded("shearcut_test", || {
            Err(CallError::new(ShearcutStatus::Config, "`speed` = -1: > 0"))
        });
        assert_eq!(status, ShearcutStatus::Config);
        assert_eq!(last_error(), "shearcut_test: `speed` = -1: > 0");
        assert_eq!(guarded("shearcut_test", || Ok(())), ShearcutStatus::Ok);
        // Success leaves the last error as it was.
        assert_eq!(last_error(), "shearcut_test: `speed` = -1: > 0");
    }

    #[test]
    fn interior_nul_bytes_do_not_lose_the_message() {
        set_last_error("a\0b");
        assert_eq!(last_error(), "a b");
    }
}
