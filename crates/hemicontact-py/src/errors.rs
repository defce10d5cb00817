//! The library's errors as Python exceptions: invalid input is a `ScenarioError` (a
//! `ValueError`) with the same text as the command line's, files that cannot be read or
//! written an `OSError`, memory a `MemoryError`, numerical failures a `RuntimeError`.

use hemicontact::Error;
use pyo3::exceptions::{
    PyKeyboardInterrupt, PyMemoryError, PyOSError, PyRuntimeError, PyValueError,
};
use pyo3::{create_exception, PyErr};

create_exception!(
    hemicontact,
    ScenarioError,
    PyValueError,
    "Invalid input: a scenario field, a mesh or a law outside what is allowed. The message \
     names the source, the field, the value and what is allowed."
);

/// The Python exception of a library error.
pub fn to_py(e: Error) -> PyErr {
    let text = e.to_string();
    match e {
        Error::Scenario { .. }
        | Error::Invalid { .. }
        | Error::Parse { .. }
        | Error::Mesh(_)
        | Error::MeshFile { .. }
        | Error::RigidMotion { .. }
        | Error::Law { .. } => ScenarioError::new_err(text),
        Error::Io { .. } | Error::OutputBusy { .. } => PyOSError::new_err(text),
        Error::OutOfMemory(_) => PyMemoryError::new_err(text),
        Error::Interrupted => PyKeyboardInterrupt::new_err(text),
        _ => PyRuntimeError::new_err(text),
    }
}

/// A `ScenarioError` naming `field` of `source` with the value `value` and what is
/// allowed, in the library's format.
pub fn scenario_error(
    source: &str,
    field: &str,
    value: impl std::fmt::Display,
    allowed: &str,
) -> PyErr {
    to_py(Error::Scenario {
        file: source.to_string(),
        field: field.to_string(),
        value: value.to_string(),
        allowed: allowed.to_string(),
    })
}
