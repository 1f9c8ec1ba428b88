//! shearcut's errors as Python exceptions: bad input is a `ValueError`
//! (one line naming the file, key, value and what is allowed), a model
//! failure a `RuntimeError`.

use pyo3::PyErr;
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use shearcut_ffi::EmbedError;

/// The exception for `e`.
pub(crate) fn to_py(e: EmbedError) -> PyErr {
    match e {
        EmbedError::Config(m) => PyValueError::new_err(m),
        EmbedError::Model(m) => PyRuntimeError::new_err(m),
    }
}
