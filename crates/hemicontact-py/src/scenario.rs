//! Scenarios: read from TOML files, built from Python dicts through the same schema, or the
//! paper's example; and their conversion back to dicts.

use crate::convert::{to_python, to_toml};
use crate::errors::{scenario_error, to_py};
use crate::laws::PyLaw;
use crate::mesh::NativeMesh;
use hemicontact::contact::{
    CustomCoefficient, CustomCompliance, CustomField, FrictionCoefficient, NormalLaw,
};
use hemicontact::scenario::schema::ScenarioFile;
use hemicontact::scenario::{builtin, Scenario};
use hemicontact::Error;
use pyo3::prelude::*;
use std::path::PathBuf;
use std::sync::Arc;

/// A law written in Python as `Scenario.from_dict` receives it: (contact entry, kind
/// `slip`/`position`/`compliance`, callable, derivative of a compliance law, label).
type PythonLaw = (usize, String, Py<PyAny>, Option<Py<PyAny>>, String);

/// A scenario of the library (parsed, not yet resolved into a problem).
#[pyclass(module = "hemicontact._core", name = "Scenario", frozen)]
pub struct NativeScenario {
    /// The library's scenario.
    pub inner: Scenario,
    /// The Python laws of the scenario (also in `inner.given_friction` and
    /// `inner.given_normal`), whose exceptions are raised again in place of the library's
    /// error.
    pub laws: Vec<Arc<PyLaw>>,
}

impl NativeScenario {
    /// A scenario without Python laws.
    fn plain(inner: Scenario) -> Self {
        NativeScenario {
            inner,
            laws: Vec::new(),
        }
    }

    /// The Python exception of the library error `e`: the exception a Python law raised,
    /// if one did (the library's error then only reports it), else [`to_py`] of `e`.
    pub fn error(&self, e: Error) -> PyErr {
        self.laws
            .iter()
            .find_map(|law| law.take_error())
            .unwrap_or_else(|| to_py(e))
    }
}

#[pymethods]
impl NativeScenario {
    /// Reads the TOML scenario file at `path`.
    #[staticmethod]
    fn from_file(py: Python<'_>, path: PathBuf) -> PyResult<Self> {
        let inner = py.detach(|| Scenario::from_file(&path)).map_err(to_py)?;
        Ok(NativeScenario::plain(inner))
    }

    /// The scenario of the Python dict `value` (the schema of a scenario file), named
    /// `source` in messages, with an optional mesh given in memory instead of `[mesh]` and
    /// the folder `dir` against which relative paths (`mesh.file`) are resolved, and the
    /// laws written in Python: (contact entry, kind, callable, derivative, label), the kind
    /// `slip` or `position` replacing the entry's `mu`, `compliance` its normal law.
    #[staticmethod]
    #[pyo3(signature = (value, source, mesh=None, dir=None, laws=Vec::new()))]
    fn from_dict(
        value: &Bound<'_, PyAny>,
        source: &str,
        mesh: Option<&NativeMesh>,
        dir: Option<PathBuf>,
        laws: Vec<PythonLaw>,
    ) -> PyResult<Self> {
        let table = to_toml(value, "", source)?;
        if !table.is_table() {
            return Err(scenario_error(
                source,
                "(scenario)",
                "not a dict",
                "a dict of tables",
            ));
        }
        let file: ScenarioFile = serde_path_to_error::deserialize(table).map_err(|e| {
            let path = e.path().to_string();
            // One line, like the file's messages (toml appends the table on a new line).
            let inner = e.inner().to_string();
            let inner = inner.split_whitespace().collect::<Vec<_>>().join(" ");
            to_py(Error::Parse {
                file: source.to_string(),
                message: if path == "." {
                    inner
                } else {
                    format!("field `{path}`: {inner}")
                },
            })
        })?;
        let mut given_friction = Vec::new();
        let mut given_normal = Vec::new();
        let mut kept = Vec::new();
        for (k, kind, f, df, label) in laws {
            let field = if kind == "compliance" {
                "normal"
            } else {
                "friction.mu"
            };
            let name = format!("contact[{k}].{field} ({label})");
            let law = Arc::new(PyLaw::new(f, df, label.clone(), name));
            match kind.as_str() {
                "slip" => given_friction.push((
                    k,
                    FrictionCoefficient::Custom(CustomCoefficient::new(label, law.clone())),
                )),
                "position" => given_friction.push((
                    k,
                    FrictionCoefficient::Field(CustomField::new(label, law.clone())),
                )),
                "compliance" => given_normal.push((
                    k,
                    NormalLaw::Custom(CustomCompliance::new(label, law.clone())),
                )),
                other => {
                    return Err(pyo3::exceptions::PyValueError::new_err(format!(
                        "unknown kind of law `{other}`: slip, position or compliance"
                    )))
                }
            }
            kept.push(law);
        }
        Ok(NativeScenario {
            inner: Scenario {
                source: source.to_string(),
                file,
                memory_limit: hemicontact::resources::available_memory(),
                dir,
                given_mesh: mesh.map(|m| m.mesh.clone()),
                given_friction,
                given_normal,
            },
            laws: kept,
        })
    }

    /// The paper's example with `n × n` squares and locking compliance `c_kappa` (Pa), as
    /// `hemicontact paper` solves it.
    #[staticmethod]
    fn paper(n: usize, c_kappa: f64) -> PyResult<Self> {
        let text = builtin::paper(n, c_kappa);
        let inner = Scenario::from_str(&text, "<built-in paper>").map_err(to_py)?;
        Ok(NativeScenario::plain(inner))
    }

    /// The scenario as a dict of the file's schema (without a mesh given in memory).
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let value = toml::Value::try_from(&self.inner.file)
            .map_err(|e| pyo3::exceptions::PyRuntimeError::new_err(e.to_string()))?;
        to_python(py, &value)
    }

    /// Where the scenario came from (a path, or a name such as `<built-in paper>`).
    #[getter]
    fn source(&self) -> String {
        self.inner.source.clone()
    }

    /// The scenario's title, if any.
    #[getter]
    fn title(&self) -> Option<String> {
        self.inner.file.title.clone()
    }

    /// Whether the scenario carries a mesh given in memory.
    #[getter]
    fn has_given_mesh(&self) -> bool {
        self.inner.given_mesh.is_some()
    }

    /// The same scenario with `n` squares along x (generated meshes only).
    fn with_resolution(&self, n: usize) -> PyResult<Self> {
        let inner = self.inner.with_resolution(n).map_err(to_py)?;
        Ok(NativeScenario {
            inner,
            laws: self.laws.clone(),
        })
    }

    /// Resolves and validates the scenario (mesh, laws, supports, settings); returns the
    /// notes it raises.
    fn check(&self, py: Python<'_>) -> PyResult<Vec<String>> {
        let scenario = &self.inner;
        py.detach(|| {
            scenario.settings()?;
            scenario.into_problem_with_notes()
        })
        .map(|(_, notes)| notes)
        .map_err(|e| self.error(e))
    }

    /// The mesh the scenario solves on (generated, read or given).
    fn mesh(&self, py: Python<'_>) -> PyResult<NativeMesh> {
        let scenario = &self.inner;
        let problem = py
            .detach(|| scenario.into_problem())
            .map_err(|e| self.error(e))?;
        Ok(NativeMesh {
            mesh: problem.mesh().clone(),
        })
    }
}
