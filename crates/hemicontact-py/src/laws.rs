//! User-defined laws written in Python, called by the solver with whole arrays: a friction
//! coefficient μ(r) of the slip (the library's `SlipFunction`), μ(x) of the position
//! (`PositionFunction`), and a normal compliance p(δ) with its derivative
//! (`ComplianceFunction`). Each call goes through `hemicontact._laws.evaluate`, which wraps
//! the data as a numpy array and checks the result's shape. An exception raised by a
//! callable is kept and raised again, as itself, when the library reports the failure.

use crate::mesh::{f64_bytes, f64s};
use hemicontact::contact::{ComplianceFunction, PositionFunction, SlipFunction};
use pyo3::prelude::*;
use std::sync::{Mutex, PoisonError};

/// A law computed by Python callables: `function` (μ, or the pressure p) and, for a
/// compliance law, `derivative` (dp).
pub struct PyLaw {
    /// The callable: numpy array → array of values.
    function: Py<PyAny>,
    /// The derivative dp of a compliance law.
    derivative: Option<Py<PyAny>>,
    /// The label of the callable, e.g. `weakening, part 'left'`: the library's name of the
    /// law.
    pub label: String,
    /// The law's name in the adapter's messages, e.g.
    /// `contact[0].friction.mu (weakening, part 'left')`.
    name: String,
    /// The first exception a callable (or the adapter) raised, to raise again.
    error: Mutex<Option<PyErr>>,
}

impl std::fmt::Debug for PyLaw {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}", self.name)
    }
}

impl PyLaw {
    /// The law of `function` (and `derivative`) named `name` in messages, `label` in the
    /// library.
    pub fn new(
        function: Py<PyAny>,
        derivative: Option<Py<PyAny>>,
        label: String,
        name: String,
    ) -> Self {
        PyLaw {
            function,
            derivative,
            label,
            name,
            error: Mutex::new(None),
        }
    }

    /// The exception a callable raised, if any (taken: a second call returns `None`).
    pub fn take_error(&self) -> Option<PyErr> {
        self.error
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .take()
    }

    /// `out = f(x)` through the adapter: `x` holds `out.len()` points of `dim` coordinates
    /// (`dim == 0`: one number per point); `what` names a point in messages.
    fn call(
        &self,
        py: Python<'_>,
        f: &Py<PyAny>,
        x: &[f64],
        dim: usize,
        what: &str,
        out: &mut [f64],
    ) -> PyResult<()> {
        let adapter = py.import("hemicontact._laws")?.getattr("evaluate")?;
        let result = adapter.call1((f.bind(py), f64_bytes(py, x), dim, &self.name, what))?;
        let values = f64s(&result.extract::<Vec<u8>>()?, &self.name)?;
        if values.len() != out.len() {
            return Err(pyo3::exceptions::PyRuntimeError::new_err(format!(
                "{}: {} values for {} {what}s",
                self.name,
                values.len(),
                out.len()
            )));
        }
        out.copy_from_slice(&values);
        Ok(())
    }

    /// [`PyLaw::call`] with the GIL, keeping the first exception.
    fn evaluate(
        &self,
        derivative: bool,
        x: &[f64],
        dim: usize,
        what: &str,
        out: &mut [f64],
    ) -> Result<(), String> {
        Python::attach(|py| {
            let f = if derivative {
                self.derivative.as_ref()
            } else {
                Some(&self.function)
            };
            let result = match f {
                Some(f) => self.call(py, f, x, dim, what, out),
                None => Err(pyo3::exceptions::PyRuntimeError::new_err(format!(
                    "{}: no derivative given",
                    self.name
                ))),
            };
            result.map_err(|e| {
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

impl SlipFunction for PyLaw {
    fn evaluate(&self, slips: &[f64], out: &mut [f64]) -> Result<(), String> {
        PyLaw::evaluate(self, false, slips, 0, "slip", out)
    }
}

impl PositionFunction for PyLaw {
    fn evaluate(&self, points: &[[f64; 3]], dim: usize, out: &mut [f64]) -> Result<(), String> {
        let x: Vec<f64> = points.iter().flat_map(|p| p[..dim].to_vec()).collect();
        PyLaw::evaluate(self, false, &x, dim, "point", out)
    }
}

impl ComplianceFunction for PyLaw {
    fn pressure(&self, penetration: &[f64], out: &mut [f64]) -> Result<(), String> {
        PyLaw::evaluate(self, false, penetration, 0, "penetration", out)
    }

    fn stiffness(&self, penetration: &[f64], out: &mut [f64]) -> Result<(), String> {
        PyLaw::evaluate(self, true, penetration, 0, "penetration", out)
    }
}
