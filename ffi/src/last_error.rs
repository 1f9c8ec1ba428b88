//! The thread-local last-error message of the C ABI.

use std::cell::RefCell;
use std::ffi::{CString, c_char};

thread_local! {
    /// The message of this thread's last failing call ("" before any).
    static LAST_ERROR: RefCell<CString> = RefCell::new(CString::default());
}

/// Records `message` as this thread's last error (interior NUL bytes,
/// which a C string cannot hold, become spaces). Allocates: called on
/// failure paths only.
pub(crate) fn set_last_error(message: &str) {
    let bytes: Vec<u8> = message
        .bytes()
        .map(|b| if b == 0 { b' ' } else { b })
        .collect();
    let text = CString::new(bytes).unwrap_or_default();
    LAST_ERROR.with(|cell| *cell.borrow_mut() = text);
}

/// One line saying why this thread's last failing call failed ("" if none
/// has failed). The pointer stays valid until the next failing call on
/// this thread; copy the text to keep it. Never null.
#[unsafe(no_mangle)]
pub extern "C" fn shearcut_last_error() -> *const c_char {
    LAST_ERROR
        .try_with(|cell| cell.borrow().as_ptr())
        .unwrap_or(c"thread-local storage is gone (thread exiting)".as_ptr())
}
