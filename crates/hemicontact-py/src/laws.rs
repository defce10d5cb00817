//! User-defined laws written in Python: a friction coefficient μ(r) as a Python callable,
//! called by the solver with all slips of a contact part at once (see the library's
//! `SlipFunction`). The call goes through `hemicontact._laws.evaluate`, which wraps the
//! slips as a numpy array and checks the result's shape. An exception raised by the callable
//! is kept and raised again, as itself, when the library reports the failure.

use crate::mesh::{f64_bytes, f64s};
use hemicontact::contact::SlipFunction;
use pyo3::prelude::*;
use std::sync::{Mutex, PoisonError};

/// A friction coefficient μ(r) computed by a Python callable.
pub struct PySlipFunction {
    /// The callable: numpy array of slips (m) → array of μ.
    function: Py<PyAny>,
    /// The law's name in messages, e.g. `contact[0].friction.mu (weakening, part 'left')`.
    pub name: String,
    /// The first exception the callable (or the adapter) raised, to raise again.
    error: Mutex<Option<PyErr>>,
}

impl std::fmt::Debug for PySlipFunction {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}", self.name)
    }
}

impl PySlipFunction {
    /// The law of the callable `function` named `name`.
    pub fn new(function: Py<PyAny>, name: String) -> Self {
        PySlipFunction {
            function,
            name,
            error: Mutex::new(None),
        }
    }

    /// The exception the callable raised, if any (taken: a second call returns `None`).
    pub fn take_error(&self) -> Option<PyErr> {
        self.error
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .take()
    }

    fn call(&self, py: Python<'_>, slips: &[f64], out: &mut [f64]) -> PyResult<()> {
        let adapter = py.import("hemicontact._laws")?.getattr("evaluate")?;
        let result = adapter.call1((self.function.bind(py), f64_bytes(py, slips), &self.name))?;
        let values = f64s(&result.extract::<Vec<u8>>()?, &self.name)?;
        if values.len() != out.len() {
            return Err(pyo3::exceptions::PyRuntimeError::new_err(format!(
                "{}: {} values for {} slips",
                self.name,
                values.len(),
                out.len()
            )));
        }
        out.copy_from_slice(&values);
        Ok(())
    }
}

impl SlipFunction for PySlipFunction {
    fn evaluate(&self, slips: &[f64], out: &mut [f64]) -> Result<(), String> {
        Python::attach(|py| {
            self.call(py, slips, out).map_err(|e| {
                let text = e.to_string();
                let mut kept = self.error.lock().unwrap_or_else(PoisonError::into_inner);
                if kept.is_none() {
                    *kept = Some(e);
                }
                text
            })
        })
    }
}
